# test_baked runs the geombake binary (bake, inspect) as a user would.
add_dependencies(${name} geombake)
target_compile_definitions(${name} PRIVATE GEOMBAKE_EXE="$<TARGET_FILE:geombake>")
