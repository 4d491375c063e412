# meshoptimizer: the independent reference buffer on closed manifolds.
find_package(meshoptimizer REQUIRED)
target_link_libraries(${name} PRIVATE meshoptimizer::meshoptimizer)
