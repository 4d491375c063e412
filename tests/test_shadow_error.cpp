// geom/shadow_error.h and the reference's per-pixel objects and classes
// (geom/shadow_reference.h): laws on constructed references (random class maps,
// masks and uncertain bands) and on the real ray-cast reference of a box over a
// ground (Embree).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <random>

#include "geom/shadow_error.h"
#include "geom/shadow_reference.h"

namespace {

using geom::ShadowClass;

// A reference built by hand: classes drawn at random, the mask and the band from them.
geom::ShadowReference random_reference(std::mt19937& rng, int w, int h, double p_uncertain) {
  geom::ShadowReference r;
  r.ok = true, r.width = w, r.height = h;
  const size_t n = size_t(w) * h;
  r.mask.resize(n), r.uncertain.resize(n), r.pixel_class.resize(n);
  r.object.assign(n, geom::kNoObject), r.blocker.assign(n, geom::kNoObject);
  std::uniform_int_distribution<int> cls(0, 9);
  std::uniform_real_distribution<double> U(0, 1);
  // Blobs: each pixel copies its left or upper neighbour's class most of the time.
  for (size_t i = 0; i < n; ++i) {
    const int x = int(i % w), y = int(i / w);
    ShadowClass c;
    if (U(rng) < 0.8 && x > 0)
      c = ShadowClass(r.pixel_class[i - 1]);
    else if (U(rng) < 0.5 && y > 0)
      c = ShadowClass(r.pixel_class[i - w]);
    else {
      const int k = cls(rng);
      c = k < 1   ? ShadowClass::None
          : k < 6 ? ShadowClass::Lit
          : k < 8 ? ShadowClass::Cast
          : k < 9 ? ShadowClass::Self
                  : ShadowClass::Unlit;
    }
    r.pixel_class[i] = uint8_t(c);
    r.mask[i] = c == ShadowClass::None ? 128 : c == ShadowClass::Lit ? 255 : 0;
    r.uncertain[i] = U(rng) < p_uncertain;
  }
  return r;
}

bool is_shadow_class(uint8_t c) { return c == uint8_t(ShadowClass::Cast) || c == uint8_t(ShadowClass::Self); }

TEST(ShadowError, LawsOnRandomReferencesAndMasks) {
  std::mt19937 rng(18);
  std::uniform_real_distribution<double> U(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const int w = 1 + int(rng() % 40), h = 1 + int(rng() % 30);
    const geom::ShadowReference ref = random_reference(rng, w, h, trial % 4 == 0 ? 0.0 : 0.2);
    const size_t n = size_t(w) * h;
    // The exact mask scores zero everywhere.
    const geom::ShadowError exact = geom::shadow_error(ref.mask, ref);
    EXPECT_EQ(exact.wrong_visible + exact.wrong_boundary + exact.wrong_cast + exact.wrong_self, 0u);
    // A random technique's mask.
    std::vector<uint8_t> mask = ref.mask;
    const double flip = U(rng);
    for (size_t i = 0; i < n; ++i)
      if (U(rng) < flip) mask[i] = mask[i] == 0 ? 255 : 0;
    geom::ShadowErrorOptions opt;
    opt.wrong_mask = opt.class_mask = true;
    const geom::ShadowError e = geom::shadow_error(mask, ref, opt);
    ASSERT_EQ(e.wrong.size(), n);
    ASSERT_EQ(e.pixel_class.size(), n);
    // Brute force: counts, the band, the classes of lit pixels.
    size_t vis = 0, wv = 0, bnd = 0, wb = 0, cast = 0, wc = 0, self = 0, ws = 0, other = 0;
    for (size_t i = 0; i < n; ++i) {
      const int x = int(i % w), y = int(i / w);
      const bool wrong = (mask[i] == 0) != (ref.mask[i] == 0);
      if (ref.mask[i] == 128) {
        EXPECT_EQ(e.wrong[i], uint8_t(geom::WrongPixel::Right));
        continue;
      }
      if (ref.uncertain[i]) {
        EXPECT_EQ(e.wrong[i], uint8_t(wrong ? geom::WrongPixel::Uncertain : geom::WrongPixel::Right));
        continue;
      }
      ++vis, wv += wrong;
      // band: within 3 (Chebyshev) of a non-empty pixel with a non-empty neighbour of the other state
      bool in_band = false;
      for (int t = std::max(0, y - 3); t <= std::min(h - 1, y + 3) && !in_band; ++t)
        for (int u = std::max(0, x - 3); u <= std::min(w - 1, x + 3) && !in_band; ++u) {
          const uint8_t v = ref.mask[size_t(t) * w + u];
          if (v == 128) continue;
          for (int dy = -1; dy <= 1 && !in_band; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int uu = u + dx, tt = t + dy;
              if (uu < 0 || tt < 0 || uu >= w || tt >= h) continue;
              const uint8_t m = ref.mask[size_t(tt) * w + uu];
              if (m != 128 && m != v) in_band = true;
            }
        }
      if (in_band) ++bnd, wb += wrong;
      // class: a shadowed pixel's own; a lit one's that of a nearest shadowed pixel
      const uint8_t c = ref.pixel_class[i];
      uint8_t expect = c;
      if (c == uint8_t(ShadowClass::Lit)) {
        int best = 1 << 30;
        bool cast_at_best = false, self_at_best = false;
        for (size_t j = 0; j < n; ++j) {
          if (!is_shadow_class(ref.pixel_class[j])) continue;
          const int d = std::max(std::abs(int(j % w) - x), std::abs(int(j / w) - y));
          if (d < best) best = d, cast_at_best = self_at_best = false;
          if (d == best) (ref.pixel_class[j] == uint8_t(ShadowClass::Cast) ? cast_at_best : self_at_best) = true;
        }
        if (best == 1 << 30)
          expect = uint8_t(ShadowClass::Lit);
        else {
          ASSERT_TRUE(e.pixel_class[i] == uint8_t(ShadowClass::Cast) || e.pixel_class[i] == uint8_t(ShadowClass::Self));
          EXPECT_TRUE(e.pixel_class[i] == uint8_t(ShadowClass::Cast) ? cast_at_best : self_at_best)
              << "pixel " << x << "," << y << " took a class not at the nearest distance " << best;
          expect = e.pixel_class[i];
        }
      }
      EXPECT_EQ(e.pixel_class[i], expect);
      if (expect == uint8_t(ShadowClass::Cast))
        ++cast, wc += wrong;
      else if (expect == uint8_t(ShadowClass::Self))
        ++self, ws += wrong;
      else
        other += wrong;
      const geom::WrongPixel k = !wrong                                 ? geom::WrongPixel::Right
                                 : expect == uint8_t(ShadowClass::Cast) ? geom::WrongPixel::Cast
                                 : expect == uint8_t(ShadowClass::Self) ? geom::WrongPixel::Self
                                                                        : geom::WrongPixel::Other;
      EXPECT_EQ(e.wrong[i], uint8_t(k));
    }
    EXPECT_EQ(e.visible_pixels, vis);
    EXPECT_EQ(e.wrong_visible, wv);
    EXPECT_EQ(e.boundary_pixels, bnd);
    EXPECT_EQ(e.wrong_boundary, wb);
    EXPECT_EQ(e.cast_pixels, cast);
    EXPECT_EQ(e.wrong_cast, wc);
    EXPECT_EQ(e.self_pixels, self);
    EXPECT_EQ(e.wrong_self, ws);
    EXPECT_EQ(e.wrong_cast + e.wrong_self + other, e.wrong_visible);  // the classes partition the errors
    EXPECT_DOUBLE_EQ(e.error_visible, vis ? double(wv) / vis : 0.0);
    EXPECT_DOUBLE_EQ(e.error_cast, cast ? double(wc) / cast : 0.0);
    EXPECT_DOUBLE_EQ(e.error_self, self ? double(ws) / self : 0.0);
    // The inverted mask is wrong on every scored pixel of every class.
    std::vector<uint8_t> inv = ref.mask;
    for (uint8_t& v : inv) v = v == 0 ? 255 : 0;
    const geom::ShadowError all = geom::shadow_error(inv, ref);
    EXPECT_EQ(all.wrong_visible, all.visible_pixels);
    EXPECT_EQ(all.wrong_cast, all.cast_pixels);
    EXPECT_EQ(all.wrong_self, all.self_pixels);
    // A short mask: the missing pixels are wrong.
    if (n > 1) {
      std::vector<uint8_t> half(ref.mask.begin(), ref.mask.begin() + n / 2);
      const geom::ShadowError s = geom::shadow_error(half, ref);
      size_t missing = 0;
      for (size_t i = n / 2; i < n; ++i) missing += ref.mask[i] != 128 && !ref.uncertain[i];
      EXPECT_EQ(s.wrong_visible, missing);
    }
  }
}

TEST(ShadowError, InvalidReferenceScoresNothing) {
  geom::ShadowReference r;
  const geom::ShadowError e = geom::shadow_error(std::vector<uint8_t>(16, 0), r);
  EXPECT_EQ(e.visible_pixels, 0u);
  EXPECT_EQ(e.error_visible, 0.0);
}

// A unit box over a ground square (two objects), as in test_shadow_reference.cpp;
// the box's faces are unwelded quads: still one object.
void box_scene(std::vector<float>& p, std::vector<uint32_t>& idx) {
  auto quad = [&](std::array<float, 12> v) {
    const uint32_t base = uint32_t(p.size() / 3);
    p.insert(p.end(), v.begin(), v.end());
    idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  };
  quad({-4, 0, -4, -4, 0, 4, 4, 0, 4, 4, 0, -4});
  const float l = -0.5f, hx = 0.5f, ly = 1, hy = 2;
  quad({l, ly, l, l, ly, hx, l, hy, hx, l, hy, l});
  quad({hx, ly, l, hx, hy, l, hx, hy, hx, hx, ly, hx});
  quad({l, ly, l, hx, ly, l, hx, ly, hx, l, ly, hx});
  quad({l, hy, l, l, hy, hx, hx, hy, hx, hx, hy, l});
  quad({l, ly, l, l, hy, l, hx, hy, l, hx, ly, l});
  quad({l, ly, hx, hx, ly, hx, hx, hy, hx, l, hy, hx});
}

TEST(ShadowReference, ObjectsAndClassesOfABoxOverAGround) {
  std::vector<float> p;
  std::vector<uint32_t> idx;
  box_scene(p, idx);
  uint32_t count = 0;
  const std::vector<uint32_t> comp =
      geom::triangle_components(geom::positions_of(p.data(), p.size() / 3), idx.data(), idx.size(), count);
  ASSERT_EQ(count, 2u);
  EXPECT_EQ(comp[0], comp[1]);
  for (size_t t = 2; t < comp.size(); ++t) EXPECT_EQ(comp[t], comp[2]);
  EXPECT_NE(comp[0], comp[2]);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1, 1);
  size_t cast_total = 0, self_total = 0;
  for (int trial = 0; trial < 12; ++trial) {
    geom::Camera cam;
    cam.width = 48, cam.height = 36;
    const double a = U(rng) * M_PI;
    cam.eye[0] = float(6 * std::cos(a)), cam.eye[1] = float(3 + 2 * U(rng)), cam.eye[2] = float(6 * std::sin(a));
    cam.target[1] = 0.8f;
    const double h[4] = {2 * U(rng), 4 + U(rng), 2 * U(rng), trial % 2 ? 0.0 : 1.0};
    const geom::Light light = geom::light_from_homogeneous(h);
    const auto pos = geom::positions_of(p.data(), p.size() / 3);
    const geom::ShadowReference ref = geom::shadow_reference(pos, idx.data(), idx.size(), cam, light);
    ASSERT_TRUE(ref.ok) << ref.error;
    // One object for everything: the same mask, and no pixel is cast.
    const std::vector<uint32_t> one(idx.size() / 3, 7);
    const geom::ShadowReference single = geom::shadow_reference(pos, idx.data(), idx.size(), cam, light, one.data());
    ASSERT_TRUE(single.ok);
    EXPECT_EQ(single.mask, ref.mask);
    for (size_t i = 0; i < ref.mask.size(); ++i) {
      const ShadowClass c = ShadowClass(ref.pixel_class[i]);
      EXPECT_EQ(c == ShadowClass::None, ref.mask[i] == 128);
      EXPECT_EQ(c == ShadowClass::Lit, ref.mask[i] == 255);
      EXPECT_EQ(c == ShadowClass::None, ref.object[i] == geom::kNoObject);
      EXPECT_NE(ShadowClass(single.pixel_class[i]), ShadowClass::Cast);
      if (c == ShadowClass::Cast) {  // only the box shadows the ground
        ++cast_total;
        EXPECT_EQ(ref.object[i], comp[0]);
        EXPECT_EQ(ref.blocker[i], comp[2]);
      } else if (c == ShadowClass::Self) {  // the box's faces turned away (the ground faces every light here)
        ++self_total;
        EXPECT_EQ(ref.object[i], comp[2]);
        EXPECT_EQ(ref.blocker[i], ref.object[i]);
      } else {
        EXPECT_EQ(ref.blocker[i], geom::kNoObject);
      }
    }
  }
  EXPECT_GT(cast_total, 100u);
  EXPECT_GT(self_total, 100u);
}

}  // namespace
