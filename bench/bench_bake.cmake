# meshoptimizer: the adjacency baseline measured in the same run.
find_package(meshoptimizer REQUIRED)
target_link_libraries(${name} PRIVATE meshoptimizer::meshoptimizer)
# OpenMesh: the half-edge build measured in the same run; geombake: the CLI rows.
find_package(OpenMesh REQUIRED)
target_link_libraries(${name} PRIVATE OpenMeshCore)
target_compile_definitions(${name} PRIVATE GEOMBAKE_EXE="$<TARGET_FILE:geombake>")
add_dependencies(${name} geombake)
# The peers' runners, shared with bench_topology and geombench's bake table.
target_sources(${name} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/peers.cpp)
