include(${CMAKE_CURRENT_SOURCE_DIR}/gl_test.cmake)
