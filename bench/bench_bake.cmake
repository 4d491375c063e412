# meshoptimizer: the adjacency baseline measured in the same run.
find_package(meshoptimizer REQUIRED)
target_link_libraries(${name} PRIVATE meshoptimizer::meshoptimizer)
