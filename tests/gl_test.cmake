# Included by tests/test_gl_*.cmake: the GL tests drive the viewer's renderer
# library directly (headless EGL; llvmpipe without a GPU). Without the viewer
# (GEOM_BUILD_VIEWER=OFF) each builds as one skipped test instead.
if(TARGET geomview_renderer)
  target_link_libraries(${name} PRIVATE geomview_renderer)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/viewer)
  target_compile_definitions(${name} PRIVATE GEOMVIEW_SHADER_DIR="${PROJECT_SOURCE_DIR}/shaders")
else()
  set_property(TARGET ${name} PROPERTY SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/gl_unavailable.cpp)
endif()
