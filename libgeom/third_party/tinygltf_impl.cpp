// The one translation unit that compiles tinygltf and stb (heavy: ~35 s).
// Built with TINYGLTF_ENABLE_DRACO so KHR_draco_mesh_compression decodes.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>
