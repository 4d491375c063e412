# Encodes and decodes Draco streams itself (libdraco from Debian).
find_package(draco REQUIRED)
target_link_libraries(${name} PRIVATE draco::draco)
