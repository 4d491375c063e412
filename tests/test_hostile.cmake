# The CLI tests run the geombake binary of this build; libzip builds the test archives.
add_dependencies(${name} geombake)
target_link_libraries(${name} PRIVATE ${LIBZIP_LIBRARY})
target_include_directories(${name} PRIVATE ${LIBZIP_INCLUDE_DIR})
