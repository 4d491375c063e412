# The CLI tests run the geombake binary of this build: build it first.
add_dependencies(${name} geombake)
