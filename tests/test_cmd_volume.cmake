# Runs the geombake binary: build it first.
add_dependencies(${name} geombake)
