#pragma once
// Coarse tracing: fewer reflection rays where the screen-space glossy filter blurs anyway.
//
// A pixel whose screen roughness R_s makes the filter read pyramid level k >= 1 or coarser (never level 0)
// only matters through blurred texels, so one ray per aligned 2^k x 2^k block of such pixels is enough. One
// glossy pixel of the block, picked by a hash of the pixel and a per-frame seed (so that it moves from one
// iteration to the next), is traced; the others get mass 0 in the filter's weighted pyramid
// (ssf::GlossyFilter with a mass image), which then averages only traced pixels. A block of size 2^s is
// used when every glossy pixel in it reads level s or coarser (s <= max_level); blocks nest, so the image
// splits into disjoint blocks with one ray each, and pixels that read level 0 always keep their ray.
//
// R_s comes from the roughness net, whose input needs the traced hit distance, so a frame is traced in two
// passes: first the representatives of every 2^max_level block (select_block_rays with no R_s), whose
// distances stand in for their whole block in the net's input (representative_distance); then, after the
// net, the rays the final selection adds (select_block_rays with R_s, minus the first pass). The first
// pass is always part of the final selection. The selection is a constant of the frame: the renderer's
// forward and backward are exact for the rays it traced.
//
// All buffers live on one device (CPU or CUDA, the same maths: coarse_tracing_ops.h).
#include <cstdint>

#include "core/compute/buffer.h"
#include "render/shading/shading_types.h"

namespace goris {

struct CoarseTracingSettings {
  int max_level = 2;  // largest block 2^max_level pixels wide (0 = every glossy pixel traced)
  int levels = 5;     // pyramid levels of the filter: the continuous level is R_s (levels - 1)
  std::uint32_t seed = 0;  // which pixel of a block is traced (the same seed for both passes of a frame)
};

// A subset of a ray list: keep[i] (0/1) per ray and slot[i] = the kept ray's index in the subset.
struct RaySelection {
  Buffer<std::uint32_t> keep, slot;
  std::size_t count = 0;
};

// Rays of `rays` (one per glossy pixel of a width x height image) that represent their block: with rs
// ([H][W] screen roughness) blocks follow the levels the filter reads; with rs null every ray pixel counts
// as reading level max_level (one ray per aligned 2^max_level block). Throws goris::Error on bad sizes or
// settings.
RaySelection select_block_rays(const ReflectionRays& rays, int width, int height, const Buffer<float>* rs,
                               const CoarseTracingSettings& settings);

// Rays kept by `a` and not by `b` (same ray list).
RaySelection selection_difference(const RaySelection& a, const RaySelection& b);

// The selected rays of `rays` written into `out` from ray index `offset` on (out's lists must hold them).
void gather_rays(const ReflectionRays& rays, const RaySelection& selection, ReflectionRays& out, std::size_t offset);

// The roughness net's hit-distance input ([H][W], scene extents, 0 where no ray): each ray pixel gets the
// distance depth / alpha / extent traced by the selected ray of its aligned 2^block_level block (the first in
// raster order if there are several; its own at block level 0). depth, alpha: the selected rays' outputs in selection order (selection null: every
// ray, outputs indexed like `rays`).
Buffer<float> representative_distance(const ReflectionRays& rays, const RaySelection* selection,
                                      const Buffer<float>& depth, const Buffer<float>& alpha, int width, int height,
                                      int block_level, float extent);

// The filter's mass image ([H][W]): 1, and 0 at the pixels whose ray the selection leaves out.
Buffer<float> selection_mass(const ReflectionRays& rays, const RaySelection& selection, int width, int height);

}  // namespace goris
