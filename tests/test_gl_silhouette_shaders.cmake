# Headless OpenGL through EGL (Mesa llvmpipe where there is no GPU).
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
target_link_libraries(${name} PRIVATE OpenGL::OpenGL OpenGL::EGL)
