#pragma once
// The inpainting mask of stage 2 (the paper's S1.4 after 3DGIC): per view, the pixels
// whose surface behind the removed object is seen by NO training view once the object is gone, i.e.
// what 2D inpainting has to invent. Pixels whose surface some other view does see are not in the mask:
// the fine-tune recovers them from that view's photo.
//
// Rule, for view i and pixel p:
//  1. Render the scene without the target ("removed", kept Gaussians only) and the target alone, once
//     per view. The removed surface depth is D_i = depth / alpha where alpha > surface_alpha (else none).
//  2. The target covers p when its alpha > target_alpha and it lies in front of the removed surface:
//     no surface, or z_target < D_i(p) (1 + depth_tolerance), with z_target = depth / alpha of the
//     target render.
//  3. A covered p is in the raw mask when the surface point X behind it (p's centre back-projected at
//     D_i(p)) is visible in no other view j: X is visible in j when it projects in front of j's near
//     plane, inside its image, onto a pixel q that the target does not cover in j, that has a removed
//     surface, and whose depth agrees: |z_j(X) - D_j(q)| <= depth_tolerance * z_j(X). A covered pixel
//     with no removed surface behind it (the target hid everything there) is in the raw mask when
//     empty_behind_is_hole is set.
//  4. Clean-up: mask = close(open(raw, open_radius), close_radius) AND covered (square structuring
//     elements; opening drops isolated pixels from depth noise, closing fills pinholes, and the mask
//     never leaves the target's footprint).
// Cost: two renders per view, then for every covered pixel a projection into the other views (stopping
// at the first that sees it), parallel over pixels (TBB).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/inpaint/mask.h"
#include "core/io/camera.h"
#include "core/io/image.h"
#include "core/scene/gaussians.h"
#include "render/raster/raster_types.h"

namespace goris {

struct InpaintMaskSettings {
  float surface_alpha = 0.5f;      // removed-scene alpha above which a pixel has a surface
  float target_alpha = 0.5f;       // target-only alpha above which the target covers a pixel
  float depth_tolerance = 0.03f;   // relative depth agreement between views (and target-in-front slack)
  bool empty_behind_is_hole = true;
  int open_radius = 1;             // clean-up, in pixels (0 = none)
  int close_radius = 1;
  RasterSettings raster;           // rasterizer settings of the renders (the background does not matter)
};

struct InpaintMaskStats {
  std::size_t covered = 0;       // pixels the target covers (rule 2)
  std::size_t empty_behind = 0;  // covered pixels with no removed surface behind
  std::size_t raw = 0;           // raw mask (rule 3)
  std::size_t masked = 0;        // final mask (rule 4)
};

struct InpaintMaskView {
  Mask mask;            // 255 = inpaint this pixel
  Mask covered;         // 255 = the target covers it (rule 2)
  Image removed_depth;  // 1 channel: D_i, camera z of the removed scene's surface; 0 = no surface
  Image removed_alpha;  // 1 channel: alpha of the removed scene
  Image target_depth;   // 1 channel: z of the target alone (depth / alpha); 0 where its alpha <= 1e-4
  InpaintMaskStats stats;
};

// Masks for every camera (all at their own resolution; no distortion). `kept` is the removed scene,
// `target` the object alone, both on the same device (the renders run there; the tests on the CPU).
// progress(done, total) is called after each view's renders and after each view's mask.
// Throws goris::Error for an empty camera list, invalid cameras, or models on different devices.
std::vector<InpaintMaskView> compute_inpaint_masks(const GaussianModel& kept, const GaussianModel& target,
                                                   const std::vector<Camera>& cameras,
                                                   const InpaintMaskSettings& settings = {},
                                                   const std::function<void(std::size_t, std::size_t)>& progress = {});

// The same from the full model and a per-Gaussian `removed` mask (1 = target), splitting it first.
// Throws goris::Error when nothing or everything is removed.
std::vector<InpaintMaskView> compute_inpaint_masks(const GaussianModel& model, const std::vector<std::uint8_t>& removed,
                                                   const std::vector<Camera>& cameras,
                                                   const InpaintMaskSettings& settings = {},
                                                   const std::function<void(std::size_t, std::size_t)>& progress = {});

// World position of pixel (x, y)'s centre at camera depth z: R^T (z K^-1 (x + 0.5, y + 0.5, 1) - t).
glm::vec3 back_project(const Camera& camera, int x, int y, float z);

}  // namespace goris
