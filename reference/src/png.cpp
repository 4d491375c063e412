// PNG writer and reader over stb_image / stb_image_write, compiled here with
// static linkage (STB_*_STATIC): no stbi_* symbol is global, so neither
// libgeom's own copy (libgeom/third_party) nor libdraco's (libdraco.so exports its own older stb) is bound to.
#include "geom/png.h"

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <stb_image.h>
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <cstdint>

#include "geom/atomic_file.h"

namespace geom {

bool encode_png(const PngImage& image, std::string& bytes, std::string& error) {
  if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
      image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels) ||
      size_t(image.width) * size_t(image.channels) > size_t(INT32_MAX)) {
    error = "inconsistent image (" + std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
            std::to_string(image.channels) + ", " + std::to_string(image.pixels.size()) + " bytes)";
    return false;
  }
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, image.width, image.height, image.channels, image.pixels.data(),
                              image.width * image.channels)) {
    error = "cannot encode the PNG image";
    return false;
  }
  return true;
}

bool write_png(const std::string& path, const PngImage& image, std::string& error) {
  std::string bytes, problem;
  if (!encode_png(image, bytes, problem)) {
    error = path + ": " + problem;
    return false;
  }
  if (!write_file_atomically(path, bytes, problem)) {
    error = problem.rfind(path, 0) == 0 ? problem : path + ": " + problem;
    return false;
  }
  return true;
}

bool read_png(const std::string& path, PngImage& image, std::string& error, int channels) {
  image = PngImage();
  if (channels < 0 || channels > 4) {
    error = path + ": asked for " + std::to_string(channels) + " channels";
    return false;
  }
  int w = 0, h = 0, n = 0;
  if (!stbi_info(path.c_str(), &w, &h, &n)) {
    error = path + ": not a readable image (" + std::string(stbi_failure_reason() ? stbi_failure_reason() : "?") + ")";
    return false;
  }
  if (w <= 0 || h <= 0 || w > 16384 || h > 16384) {
    error = path + ": image size " + std::to_string(w) + "x" + std::to_string(h) + " out of range";
    return false;
  }
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, channels);
  if (!data) {
    error = path + ": cannot decode (" + std::string(stbi_failure_reason() ? stbi_failure_reason() : "?") + ")";
    return false;
  }
  image.width = w;
  image.height = h;
  image.channels = channels ? channels : n;
  image.pixels.assign(data, data + size_t(w) * size_t(h) * size_t(image.channels));
  stbi_image_free(data);
  return true;
}

}  // namespace geom
