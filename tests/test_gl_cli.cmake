# Runs the geomview executable itself (scripted use), headless.
if(TARGET geomview)
  add_dependencies(${name} geomview)
  target_compile_definitions(${name} PRIVATE GEOMVIEW_EXE="$<TARGET_FILE:geomview>")
else()
  set_target_properties(${name} PROPERTIES EXCLUDE_FROM_ALL ON)
endif()
