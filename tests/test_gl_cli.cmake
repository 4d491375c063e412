# Runs the geomview executable itself (scripted use), headless.
if(TARGET geomview)
  add_dependencies(${name} geomview)
  target_compile_definitions(${name} PRIVATE GEOMVIEW_EXE="$<TARGET_FILE:geomview>")
else()
  set_property(TARGET ${name} PROPERTY SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/gl_unavailable.cpp)
endif()
