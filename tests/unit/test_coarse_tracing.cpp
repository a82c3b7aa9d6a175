// Coarse tracing's ray selection (train/intrinsic/coarse_tracing.h) on synthetic glossy masks and screen
// roughness: one ray per aligned block in the first pass (a pixel that moves with the seed), every pixel that reads pyramid level 0 keeps its
// ray, untraced pixels share a block with a traced one whose pixels all blur at least that much, the first
// pass is part of the final selection, the gathered lists, the net's distance input, the filter's mass
// image, and bad input.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "core/util/error.h"
#include "render/ssf/pyramid_kernels.h"
#include "tests/support/test_support.h"
#include "train/intrinsic/coarse_tracing.h"
#include "train/intrinsic/coarse_tracing_ops.h"

namespace goris {
namespace {

constexpr int kLevels = 5;

struct Scene {
  int W = 0, H = 0;
  std::vector<bool> glossy;  // [H][W]
  ReflectionRays rays;       // one per glossy pixel, in pixel order; origin = (p, 2p, 3p), direction = -origin
};

// A glossy disk with holes (non-glossy pixels inside blocks), odd sizes so that edge blocks are cut.
Scene make_scene(int W, int H, unsigned seed) {
  Scene s;
  s.W = W;
  s.H = H;
  s.glossy.assign(std::size_t(W) * H, false);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> hole(0, 9);
  std::vector<std::uint32_t> pix;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double dx = (x - 0.45 * W) / (0.45 * W), dy = (y - 0.5 * H) / (0.48 * H);
      const std::size_t p = std::size_t(y) * W + x;
      if (dx * dx + dy * dy < 1.0 && hole(rng) != 0) {
        s.glossy[p] = true;
        pix.push_back(std::uint32_t(p));
      }
    }
  const std::size_t n = pix.size();
  std::vector<float> o(3 * n), d(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) o[3 * i + c] = float(pix[i]) * float(c + 1), d[3 * i + c] = -o[3 * i + c];
  s.rays.pixels = Buffer<std::uint32_t>(pix, Device::CPU);
  s.rays.origins = Buffer<float>(o, Device::CPU);
  s.rays.directions = Buffer<float>(d, Device::CPU);
  s.rays.count = n;
  return s;
}

// Screen roughness in patches of 5x7 pixels, each patch at one random continuous level (away from integers).
std::vector<float> patchy_rs(int W, int H, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> level(0, kLevels - 2);
  std::uniform_real_distribution<float> frac(0.1f, 0.9f);
  const int pw = (W + 4) / 5, ph = (H + 6) / 7;
  std::vector<float> patch(std::size_t(pw) * ph);
  for (float& v : patch) v = (float(level(rng)) + frac(rng)) / float(kLevels - 1);
  std::vector<float> rs(std::size_t(W) * H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) rs[std::size_t(y) * W + x] = patch[std::size_t(y / 7) * pw + x / 5];
  return rs;
}

int read_level(float rs) { return ssf::level_blend(rs, kLevels).k0; }

std::vector<bool> traced_pixels(const Scene& s, const RaySelection& sel) {
  std::vector<bool> t(s.glossy.size(), false);
  const std::vector<std::uint32_t> keep = sel.keep.to_host(), pix = s.rays.pixels.to_host();
  for (std::size_t i = 0; i < pix.size(); ++i) t[pix[i]] = keep[i] != 0;
  return t;
}

// Pixels of the aligned 2^s block around (y, x), cut at the image border.
template <class F>
void for_block(const Scene& s, int y, int x, int level, F f) {
  const int y0 = (y >> level) << level, x0 = (x >> level) << level;
  for (int yy = y0; yy < std::min(y0 + (1 << level), s.H); ++yy)
    for (int xx = x0; xx < std::min(x0 + (1 << level), s.W); ++xx) f(std::size_t(yy) * s.W + xx);
}

TEST(CoarseTracing, FirstPassTracesOneGlossyPixelPerBlockThatMovesWithTheSeed) {
  const Scene s = make_scene(37, 29, 1);
  for (int max_level : {0, 1, 2, 3}) {
    std::size_t moved = 0;
    for (std::uint32_t seed : {0u, 1u}) {
      const RaySelection sel = select_block_rays(s.rays, s.W, s.H, nullptr, {max_level, kLevels, seed});
      const RaySelection other = select_block_rays(s.rays, s.W, s.H, nullptr, {max_level, kLevels, seed + 7});
      const std::vector<bool> t = traced_pixels(s, sel), t_other = traced_pixels(s, other);
      std::size_t blocks = 0;
      for (int by = 0; by < s.H; by += 1 << max_level)
        for (int bx = 0; bx < s.W; bx += 1 << max_level) {
          long best = -1;  // the glossy pixel of smallest key
          int traced = 0;
          for_block(s, by, bx, max_level, [&](std::size_t p) {
            if (s.glossy[p] && (best < 0 || coarse::pixel_key(std::uint32_t(p), seed) <
                                                coarse::pixel_key(std::uint32_t(best), seed)))
              best = long(p);
            traced += t[p];
            moved += t[p] && !t_other[p];
          });
          if (best < 0) {
            EXPECT_EQ(traced, 0);
            continue;
          }
          ++blocks;
          EXPECT_EQ(traced, 1) << "block " << by << "," << bx;
          EXPECT_TRUE(t[std::size_t(best)]);
        }
      EXPECT_EQ(sel.count, blocks) << "max level " << max_level;
      EXPECT_EQ(other.count, blocks) << "max level " << max_level;
      if (max_level == 0) {
        EXPECT_EQ(sel.count, s.rays.count);
      }
    }
    if (max_level > 0) {
      EXPECT_GT(moved, 10u) << "another seed should pick other pixels";
    }
  }
}

TEST(CoarseTracing, FinalSelectionFollowsTheBlurLevels) {
  for (unsigned seed : {2u, 3u, 4u}) {
    const Scene s = make_scene(45, 31, seed);
    const std::vector<float> rs = patchy_rs(s.W, s.H, seed + 10);
    const Buffer<float> rs_buf(rs, Device::CPU);
    const int max_level = 2;
    const RaySelection first = select_block_rays(s.rays, s.W, s.H, nullptr, {max_level, kLevels, seed});
    const RaySelection all = select_block_rays(s.rays, s.W, s.H, &rs_buf, {max_level, kLevels, seed});
    const std::vector<bool> t_first = traced_pixels(s, first), t = traced_pixels(s, all);
    std::size_t saved = 0;
    for (int y = 0; y < s.H; ++y)
      for (int x = 0; x < s.W; ++x) {
        const std::size_t p = std::size_t(y) * s.W + x;
        if (!s.glossy[p]) continue;
        EXPECT_TRUE(!t_first[p] || t[p]) << "first-pass ray left out at " << p;
        const int level = read_level(rs[p]);
        EXPECT_TRUE(level > 0 || t[p]) << "a pixel that reads level 0 lost its ray at " << p;
        if (t[p]) continue;
        ++saved;
        // Its block: some aligned 2^b block (1 <= b <= min(level, max)) holding exactly one traced pixel, with
        // every glossy pixel in it blurred at level b or coarser.
        bool found = false;
        for (int b = 1; b <= std::min(level, max_level) && !found; ++b) {
          int traced = 0;
          bool blurred = true;
          for_block(s, y, x, b, [&](std::size_t q) {
            traced += t[q];
            if (s.glossy[q] && read_level(rs[q]) < b) blurred = false;
          });
          found = traced == 1 && blurred;
        }
        EXPECT_TRUE(found) << "untraced pixel " << p << " at level " << level;
      }
    EXPECT_GT(saved, s.rays.count / 4) << "seed " << seed;
    EXPECT_EQ(all.count + saved, s.rays.count);

    const RaySelection added = selection_difference(all, first);
    EXPECT_EQ(added.count + first.count, all.count);
  }
}

TEST(CoarseTracing, UniformLevelsGiveRegularLattices) {
  const Scene s = make_scene(40, 24, 5);
  const std::size_t n = s.rays.count;
  for (float level : {0.5f, 1.5f, 2.5f, 3.5f}) {  // reads level 0, 1, 2, 3
    const Buffer<float> rs(std::vector<float>(std::size_t(s.W) * s.H, level / (kLevels - 1)), Device::CPU);
    const RaySelection sel = select_block_rays(s.rays, s.W, s.H, &rs, {2, kLevels});
    const RaySelection first = select_block_rays(s.rays, s.W, s.H, nullptr, {2, kLevels});
    if (level < 1)
      EXPECT_EQ(sel.count, n);
    else if (level >= 2)
      EXPECT_EQ(sel.count, first.count);  // capped at max level 2: one ray per 4x4 block
    else
      EXPECT_LT(sel.count, n / 3);
  }
  EXPECT_LT(select_block_rays(s.rays, s.W, s.H, nullptr, {2, kLevels}).count, n / 10);
}

TEST(CoarseTracing, GatherDistanceAndMass) {
  const Scene s = make_scene(33, 27, 6);
  const std::size_t n = s.rays.count;
  const RaySelection first = select_block_rays(s.rays, s.W, s.H, nullptr, {2, kLevels});
  ReflectionRays out;
  const std::size_t offset = 3;
  out.pixels = Buffer<std::uint32_t>(offset + first.count, Device::CPU);
  out.origins = Buffer<float>(3 * (offset + first.count), Device::CPU);
  out.directions = Buffer<float>(3 * (offset + first.count), Device::CPU);
  out.count = offset + first.count;
  gather_rays(s.rays, first, out, offset);
  const std::vector<bool> t = traced_pixels(s, first);
  std::uint32_t last = 0;
  for (std::size_t j = offset; j < out.count; ++j) {
    const std::uint32_t p = out.pixels[j];
    EXPECT_TRUE(t[p]);
    EXPECT_TRUE(j == offset || p > last) << "selection order = pixel order at " << j;
    last = p;
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(out.origins[3 * j + c], float(p) * float(c + 1));
      EXPECT_EQ(out.directions[3 * j + c], -float(p) * float(c + 1));
    }
  }

  // Outputs of the traced rays: depth = pixel index, alpha 0.5 (or ~0: no hit) -> distance = 2 p / extent.
  std::vector<float> depth(first.count), alpha(first.count);
  for (std::size_t j = 0; j < first.count; ++j) {
    depth[j] = float(out.pixels[offset + j]);
    alpha[j] = j % 5 == 4 ? 0.0f : 0.5f;
  }
  const float extent = 4.0f;
  const Buffer<float> dist = representative_distance(s.rays, &first, Buffer<float>(depth, Device::CPU),
                                                     Buffer<float>(alpha, Device::CPU), s.W, s.H, 2, extent);
  std::vector<std::uint32_t> slot_of(s.glossy.size(), 0);
  for (std::size_t j = 0; j < first.count; ++j) slot_of[out.pixels[offset + j]] = std::uint32_t(j);
  for (int y = 0; y < s.H; ++y)
    for (int x = 0; x < s.W; ++x) {
      const std::size_t p = std::size_t(y) * s.W + x;
      if (!s.glossy[p]) {
        EXPECT_EQ(dist[p], 0.0f);
        continue;
      }
      long rep = -1;  // the block's traced pixel
      for_block(s, y, x, 2, [&](std::size_t q) {
        if (t[q]) rep = long(q);
      });
      ASSERT_GE(rep, 0);
      const std::uint32_t j = slot_of[std::size_t(rep)];
      EXPECT_FLOAT_EQ(dist[p], alpha[j] > 0 ? float(rep) / 0.5f / extent : 0.0f) << p;
    }
  // Every ray traced, block level 0: each pixel its own distance.
  std::vector<float> own_depth(n), own_alpha(n, 0.25f);
  for (std::size_t i = 0; i < n; ++i) own_depth[i] = float(i);
  const Buffer<float> own = representative_distance(s.rays, nullptr, Buffer<float>(own_depth, Device::CPU),
                                                    Buffer<float>(own_alpha, Device::CPU), s.W, s.H, 0, 2.0f);
  for (std::size_t i = 0; i < n; ++i) EXPECT_FLOAT_EQ(own[s.rays.pixels[i]], float(i) / 0.25f / 2.0f);

  const Buffer<float> mass = selection_mass(s.rays, first, s.W, s.H);
  for (std::size_t p = 0; p < s.glossy.size(); ++p) EXPECT_EQ(mass[p], s.glossy[p] && !t[p] ? 0.0f : 1.0f) << p;
}

TEST(CoarseTracing, BadInputThrows) {
  using test::expect_error;
  Scene s = make_scene(20, 16, 7);
  const Buffer<float> short_rs(std::vector<float>(10, 0.5f), Device::CPU);
  expect_error([&] { select_block_rays(s.rays, s.W, s.H, &short_rs, {2, kLevels}); }, "screen roughness");
  expect_error([&] { select_block_rays(s.rays, s.W, s.H, nullptr, {4, kLevels}); }, "max_level");
  expect_error([&] { select_block_rays(s.rays, s.W, s.H, nullptr, {2, 1}); }, "levels");
  expect_error([&] { select_block_rays(s.rays, 0, s.H, nullptr, {2, kLevels}); }, "empty");
  expect_error([&] { select_block_rays(s.rays, s.W, s.H / 2, nullptr, {2, kLevels}); }, "outside");
  const RaySelection sel = select_block_rays(s.rays, s.W, s.H, nullptr, {2, kLevels});
  const Scene other = make_scene(21, 16, 8);
  expect_error([&] { selection_mass(other.rays, sel, other.W, other.H); }, "coarse tracing: ray selection");
  ReflectionRays small;
  small.pixels = Buffer<std::uint32_t>(1, Device::CPU);
  small.origins = Buffer<float>(3, Device::CPU);
  small.directions = Buffer<float>(3, Device::CPU);
  small.count = 1;
  expect_error([&] { gather_rays(s.rays, sel, small, 0); }, "needed");
  const Buffer<float> one(std::vector<float>(1, 1.0f), Device::CPU);
  expect_error([&] { representative_distance(s.rays, &sel, one, one, s.W, s.H, 2, 1.0f); }, "depth / alpha");
  s.rays.count += 1;
  expect_error([&] { select_block_rays(s.rays, s.W, s.H, nullptr, {2, kLevels}); }, "other lengths");
}

}  // namespace
}  // namespace goris
