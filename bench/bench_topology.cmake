find_package(meshoptimizer REQUIRED)
find_package(OpenMesh REQUIRED)
target_link_libraries(${name} PRIVATE meshoptimizer::meshoptimizer OpenMeshCore)
# The peers' runners, shared with bench_bake and geombench's bake table.
target_sources(${name} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/peers.cpp)
