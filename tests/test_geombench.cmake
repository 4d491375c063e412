# Runs `geombench --quick` (headless GL: llvmpipe without a GPU, hence the gl
# label) and checks its outputs; the reference test beside it is CPU only.
find_package(nlohmann_json 3 REQUIRED)
target_link_libraries(${name} PRIVATE nlohmann_json::nlohmann_json)
if(TARGET geombench OR (GEOM_BUILD_VIEWER AND EXISTS ${PROJECT_SOURCE_DIR}/tools/geombench/CMakeLists.txt))
  add_dependencies(${name} geombench)
  target_compile_definitions(${name} PRIVATE GEOMBENCH_EXE="$<TARGET_FILE:geombench>")
endif()
set(labels gl)
