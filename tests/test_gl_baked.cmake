include(${CMAKE_CURRENT_SOURCE_DIR}/test_gl_shadow_maps.cmake)
