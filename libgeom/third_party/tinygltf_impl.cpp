// The one translation unit that compiles tinygltf and stb (heavy: ~35 s).
// Built with TINYGLTF_ENABLE_DRACO so KHR_draco_mesh_compression decodes.
// stb's functions are static here (STB_IMAGE_STATIC, STB_IMAGE_WRITE_STATIC):
// tinygltf alone calls them, and no stbi_* symbol is global in the archive, so
// a program with its own stb_image links beside geom::import.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include <tiny_gltf.h>
