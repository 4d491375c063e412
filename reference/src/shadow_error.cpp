// A technique's mask scored against the reference, per class (geom/shadow_error.h).
#include "geom/shadow_error.h"

#include <algorithm>

namespace geom {

std::vector<uint8_t> shadow_boundary_band(const ShadowReference& ref, int radius) {
  const int w = ref.width, h = ref.height;
  std::vector<uint8_t> edge(size_t(w) * h, 0), band(size_t(w) * h, 0);
  if (ref.mask.size() != size_t(w) * h) return band;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t v = ref.mask[size_t(y) * w + x];
      if (v == 128) continue;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = x + dx, t = y + dy;
          if (u < 0 || t < 0 || u >= w || t >= h) continue;
          const uint8_t n = ref.mask[size_t(t) * w + u];
          if (n != 128 && n != v) edge[size_t(y) * w + x] = 1;
        }
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!edge[size_t(y) * w + x]) continue;
      for (int t = std::max(0, y - radius); t <= std::min(h - 1, y + radius); ++t)
        for (int u = std::max(0, x - radius); u <= std::min(w - 1, x + radius); ++u) band[size_t(t) * w + u] = 1;
    }
  return band;
}

namespace {

// Each pixel's class for scoring: a shadowed pixel's own (Cast or Self), a lit
// one's the class of its nearest shadowed pixel (multi-source breadth-first
// search, 8-connected, seeded in raster order: ties go to the first seed).
std::vector<uint8_t> scoring_class(const ShadowReference& ref) {
  const int w = ref.width, h = ref.height;
  const size_t n = size_t(w) * h;
  std::vector<uint8_t> cls(n, uint8_t(ShadowClass::None));
  std::vector<uint32_t> queue;
  queue.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    const ShadowClass c = ShadowClass(ref.pixel_class[i]);
    if (c == ShadowClass::Cast || c == ShadowClass::Self) cls[i] = uint8_t(c), queue.push_back(uint32_t(i));
  }
  for (size_t head = 0; head < queue.size(); ++head) {
    const uint32_t i = queue[head];
    const int x = int(i % w), y = int(i / w);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int u = x + dx, t = y + dy;
        if (u < 0 || t < 0 || u >= w || t >= h) continue;
        const size_t j = size_t(t) * w + u;
        if (cls[j] != uint8_t(ShadowClass::None)) continue;
        cls[j] = cls[i];
        queue.push_back(uint32_t(j));
      }
  }
  for (size_t i = 0; i < n; ++i) {  // only lit pixels inherit; the rest keep their own
    const ShadowClass c = ShadowClass(ref.pixel_class[i]);
    if (c == ShadowClass::None || c == ShadowClass::Unlit || cls[i] == uint8_t(ShadowClass::None)) cls[i] = uint8_t(c);
  }
  return cls;
}

double share(size_t wrong, size_t all) { return all ? double(wrong) / double(all) : 0.0; }

}  // namespace

ShadowError shadow_error(const std::vector<uint8_t>& mask, const ShadowReference& ref,
                         const ShadowErrorOptions& options) {
  ShadowError e;
  const size_t n = size_t(ref.width) * size_t(ref.height);
  if (!ref.ok || ref.mask.size() != n || ref.uncertain.size() != n || ref.pixel_class.size() != n) return e;
  const std::vector<uint8_t> band = shadow_boundary_band(ref, options.band_radius);
  const std::vector<uint8_t> cls = scoring_class(ref);
  if (options.wrong_mask) e.wrong.assign(n, uint8_t(WrongPixel::Right));
  for (size_t i = 0; i < n; ++i) {
    if (ref.mask[i] == 128) continue;
    const bool shadowed = i < mask.size() ? mask[i] == 0 : ref.mask[i] != 0;  // missing pixels: wrong
    const bool wrong = shadowed != (ref.mask[i] == 0);
    if (ref.uncertain[i]) {
      if (wrong && options.wrong_mask) e.wrong[i] = uint8_t(WrongPixel::Uncertain);
      continue;
    }
    ++e.visible_pixels, e.wrong_visible += wrong;
    if (band[i]) ++e.boundary_pixels, e.wrong_boundary += wrong;
    WrongPixel kind = WrongPixel::Other;
    if (cls[i] == uint8_t(ShadowClass::Cast)) ++e.cast_pixels, e.wrong_cast += wrong, kind = WrongPixel::Cast;
    if (cls[i] == uint8_t(ShadowClass::Self)) ++e.self_pixels, e.wrong_self += wrong, kind = WrongPixel::Self;
    if (wrong && options.wrong_mask) e.wrong[i] = uint8_t(kind);
  }
  e.error_visible = share(e.wrong_visible, e.visible_pixels);
  e.error_boundary = share(e.wrong_boundary, e.boundary_pixels);
  e.error_cast = share(e.wrong_cast, e.cast_pixels);
  e.error_self = share(e.wrong_self, e.self_pixels);
  if (options.class_mask) e.pixel_class = cls;
  return e;
}

}  // namespace geom
