#pragma once
// Maths and passes of coarse tracing (coarse_tracing.h), written once with GORIS_HD and parallel_for and
// instantiated on the CPU (coarse_tracing.cpp) and on CUDA (coarse_tracing_cuda.cu). Every pass is a gather
// or writes only its own ray's / pixel's entries, so both backends give the same selection.
#include <cstddef>
#include <cstdint>

#include "core/compute/buffer.h"
#include "core/compute/hd.h"
#include "core/compute/memory.h"
#include "core/compute/parallel_for.h"
#include "core/compute/primitives.h"
#include "render/ssf/pyramid_kernels.h"

namespace goris::coarse {

constexpr std::uint32_t kNone = 0xffffffffu;  // a pixel without a (selected) ray
constexpr std::int32_t kNoRayLevel = 1 << 20;  // level image entry of a pixel without a ray: never limits a block

// The finest pyramid level the filter reads at a pixel of screen roughness rs (the lower of the two blended
// levels, ssf::level_blend), capped at max_level: its ray can be shared by a 2^level x 2^level block.
GORIS_HDI std::int32_t read_level(float rs, int levels, int max_level) {
  const int k = ssf::level_blend(rs, levels).k0;
  return k < max_level ? k : max_level;
}

// Size 2^s of the largest aligned block (s <= max_level) around pixel (y, x) in which every ray pixel reads
// level s or coarser; lvl: per pixel read_level, kNoRayLevel where there is no ray. Blocks nest, so every
// pixel of such a block gets the same s.
GORIS_HDI int block_level(const std::int32_t* lvl, int W, int H, int y, int x, int max_level) {
  for (int s = max_level; s >= 1; --s) {
    const int y0 = (y >> s) << s, x0 = (x >> s) << s;
    const int y1 = y0 + (1 << s) < H ? y0 + (1 << s) : H, x1 = x0 + (1 << s) < W ? x0 + (1 << s) : W;
    bool ok = true;
    for (int yy = y0; yy < y1 && ok; ++yy)
      for (int xx = x0; xx < x1; ++xx)
        if (lvl[std::size_t(yy) * W + xx] < s) {
          ok = false;
          break;
        }
    if (ok) return s;
  }
  return 0;
}

// First pixel in raster order of the aligned 2^s block around (y, x) whose entry in img is not `none`, or kNone.
template <class V>
GORIS_HDI std::uint32_t first_in_block(const V* img, V none, int W, int H, int y, int x, int s) {
  const int y0 = (y >> s) << s, x0 = (x >> s) << s;
  const int y1 = y0 + (1 << s) < H ? y0 + (1 << s) : H, x1 = x0 + (1 << s) < W ? x0 + (1 << s) : W;
  for (int yy = y0; yy < y1; ++yy)
    for (int xx = x0; xx < x1; ++xx) {
      const std::size_t p = std::size_t(yy) * W + xx;
      if (img[p] != none) return std::uint32_t(p);
    }
  return kNone;
}

// A well-mixed 32-bit key of pixel p for frame seed `seed`: each block traces the ray pixel of smallest key,
// so the representative moves around the block from one iteration to the next (every pixel's ray gets
// traced now and then; a fixed lattice would never trace the others). Ties cannot happen: p breaks them.
GORIS_HDI std::uint64_t pixel_key(std::uint32_t p, std::uint32_t seed) {
  std::uint32_t h = p * 0x9E3779B1u ^ (seed + 0x7F4A7C15u) * 0x85EBCA77u;
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  h *= 0x846CA68Bu;
  h ^= h >> 16;
  return (std::uint64_t(h) << 32) | p;
}

// The ray pixel (lvl entry != kNoRayLevel) of smallest pixel_key in the aligned 2^s block around (y, x).
GORIS_HDI std::uint32_t representative(const std::int32_t* lvl, int W, int H, int y, int x, int s, std::uint32_t seed) {
  const int y0 = (y >> s) << s, x0 = (x >> s) << s;
  const int y1 = y0 + (1 << s) < H ? y0 + (1 << s) : H, x1 = x0 + (1 << s) < W ? x0 + (1 << s) : W;
  std::uint64_t best = ~std::uint64_t(0);
  for (int yy = y0; yy < y1; ++yy)
    for (int xx = x0; xx < x1; ++xx) {
      const std::uint32_t p = std::uint32_t(yy) * std::uint32_t(W) + std::uint32_t(xx);
      if (lvl[p] == kNoRayLevel) continue;
      const std::uint64_t k = pixel_key(p, seed);
      if (k < best) best = k;
    }
  return std::uint32_t(best & 0xffffffffu);
}

// Hit distance of a traced ray in scene extents (the roughness net's second input), 0 for rays that hit
// (almost) nothing.
GORIS_HDI float reflection_distance(float depth, float alpha, float extent) {
  return alpha > 1e-4f ? depth / alpha / extent : 0.0f;
}

// Number of flags set (flags[] 0/1, slot = exclusive scan of them).
inline std::size_t scan_count(const Buffer<std::uint32_t>& flags, Buffer<std::uint32_t>& slot) {
  const std::size_t n = flags.size();
  if (n == 0) return 0;
  exclusive_scan(flags, slot);
  std::uint32_t last[2] = {0, 0};
  device_copy(&last[0], Device::CPU, slot.data() + (n - 1), flags.device(), sizeof(std::uint32_t));
  device_copy(&last[1], Device::CPU, flags.data() + (n - 1), flags.device(), sizeof(std::uint32_t));
  return std::size_t(last[0]) + last[1];
}

// keep[i] for the n rays at `pixels`: ray i is traced when its pixel represents its block (block_level from
// rs, or max_level everywhere when rs is null). The smallest key of a block is also the smallest of every
// sub-block holding it, so the rs-less selection is part of every selection with the same seed. lvl: [W H]
// scratch.
template <Device D>
void select(const std::uint32_t* pixels, std::size_t n, int W, int H, const float* rs, int levels, int max_level,
            std::uint32_t seed, std::int32_t* lvl, std::uint32_t* keep) {
  const std::size_t P = std::size_t(W) * H;
  parallel_for(D, P, [=] GORIS_HD(std::size_t p) { lvl[p] = kNoRayLevel; }, 4096);
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) {
    const std::uint32_t p = pixels[i];
    lvl[p] = rs ? read_level(rs[p], levels, max_level) : max_level;
  }, 2048);
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) {
    const std::uint32_t p = pixels[i];
    const int y = int(p / std::uint32_t(W)), x = int(p % std::uint32_t(W));
    const int s = block_level(lvl, W, H, y, x, max_level);
    keep[i] = s == 0 || representative(lvl, W, H, y, x, s, seed) == p ? 1u : 0u;
  }, 256);
}

// out[i] = a[i] && !b[i].
template <Device D>
void difference(const std::uint32_t* a, const std::uint32_t* b, std::size_t n, std::uint32_t* out) {
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) { out[i] = a[i] && !b[i] ? 1u : 0u; }, 4096);
}

// The kept rays (pixels, origins, directions) written at offset + slot[i] of the output lists.
template <Device D>
void gather(const std::uint32_t* pixels, const float* origins, const float* directions, std::size_t n,
            const std::uint32_t* keep, const std::uint32_t* slot, std::size_t offset, std::uint32_t* out_pixels,
            float* out_origins, float* out_directions) {
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) {
    if (!keep[i]) return;
    const std::size_t j = offset + slot[i];
    out_pixels[j] = pixels[i];
    for (int c = 0; c < 3; ++c) {
      out_origins[3 * j + c] = origins[3 * i + c];
      out_directions[3 * j + c] = directions[3 * i + c];
    }
  }, 2048);
}

// Per pixel of a ray of the full list: the distance traced by the (first, in raster order) selected ray of
// its aligned 2^block_level block (its own ray at block level 0); 0 elsewhere. keep/slot null: every ray is selected and
// ray i's outputs sit at index i. index: [W H] scratch.
template <Device D>
void representative_distance(const std::uint32_t* pixels, std::size_t n, int W, int H, const std::uint32_t* keep,
                             const std::uint32_t* slot, const float* depth, const float* alpha, int block_level,
                             float extent, std::uint32_t* index, float* out) {
  const std::size_t P = std::size_t(W) * H;
  parallel_for(D, P, [=] GORIS_HD(std::size_t p) {
    index[p] = kNone;
    out[p] = 0.0f;
  }, 4096);
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) {
    if (!keep || keep[i]) index[pixels[i]] = slot ? slot[i] : std::uint32_t(i);
  }, 2048);
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) {
    const std::uint32_t p = pixels[i];
    const std::uint32_t r =
        first_in_block(index, kNone, W, H, int(p / std::uint32_t(W)), int(p % std::uint32_t(W)), block_level);
    if (r == kNone) return;
    const std::uint32_t j = index[r];
    out[p] = reflection_distance(depth[j], alpha[j], extent);
  }, 1024);
}

// The filter's mass image: 1, except 0 at pixels whose ray was not selected.
template <Device D>
void mass(const std::uint32_t* pixels, std::size_t n, const std::uint32_t* keep, std::size_t P, float* out) {
  parallel_for(D, P, [=] GORIS_HD(std::size_t p) { out[p] = 1.0f; }, 4096);
  parallel_for(D, n, [=] GORIS_HD(std::size_t i) {
    if (!keep[i]) out[pixels[i]] = 0.0f;
  }, 2048);
}

}  // namespace goris::coarse
