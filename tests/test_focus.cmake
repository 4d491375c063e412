# test_focus runs `geombake focus` on frame files: build the CLI first.
add_dependencies(${name} geombake)
