find_package(meshoptimizer REQUIRED)
find_package(OpenMesh REQUIRED)
target_link_libraries(${name} PRIVATE meshoptimizer::meshoptimizer OpenMeshCore)
