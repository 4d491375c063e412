# GL tests drive the viewer's renderer library directly (headless EGL).
if(TARGET geomview_renderer)
  target_link_libraries(${name} PRIVATE geomview_renderer)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/viewer)
  target_compile_definitions(${name} PRIVATE GEOMVIEW_SHADER_DIR="${PROJECT_SOURCE_DIR}/shaders")
else()
  set_target_properties(${name} PROPERTIES EXCLUDE_FROM_ALL ON)
endif()
