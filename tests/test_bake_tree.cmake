# The CLI tests run the geombake binary of this build; forkpty for the terminal test.
add_dependencies(${name} geombake)
target_link_libraries(${name} PRIVATE util)
