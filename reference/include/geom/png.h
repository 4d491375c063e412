// geom/png.h: write and read 8-bit PNG images (grey, grey+alpha, RGB, RGBA).
//
// Pixels are row-major, top row first, `channels` bytes per pixel, no padding.
// Backed by stb_image / stb_image_write, compiled with static linkage in
// png.cpp; nothing of stb appears here.
// Errors are returned as "FILE: what is wrong", never thrown.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace geom {

struct PngImage {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> pixels;  // width * height * channels, top row first
};

// Writes `image` to `path` as geombake writes its files (geom/atomic_file.h):
// encoded in memory, written to a temporary file in the target's folder with
// every write and the close checked, renamed over `path` at the end; a full
// disk or a failed write leaves the old file (or none), never a truncated one.
// A target that is a FIFO, a device or a folder is refused. False with `error`
// set when the file cannot be written or the image is inconsistent (size of
// pixels, channels outside 1..4).
bool write_png(const std::string& path, const PngImage& image, std::string& error);

// The PNG file of `image`, in memory (appended to `bytes`); false with `error`
// on an inconsistent image.
bool encode_png(const PngImage& image, std::string& bytes, std::string& error);

// Reads `path`, converting to `channels` (1..4) per pixel, or keeping the file's
// own channel count when `channels` is 0. Refuses images over 16384 x 16384.
bool read_png(const std::string& path, PngImage& image, std::string& error, int channels = 0);

}  // namespace geom
