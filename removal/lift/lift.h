#pragma once
// Lifting the inpainted reference views into 3D (the paper's S1.4 "scene
// inpainting initialization" after 3DGIC): new Gaussians at the back-projected inpainted depth, and the
// reference point cloud the fine-tune projects into the other views.
//
// For each reference view (camera, inpainting mask, inpainted maps):
//  - pixels: every k-th pixel in x and y of the mask, (x % k == 0 and y % k == 0); a non-empty mask the
//    grid misses still gets its pixel nearest the mask's centroid. Pixels whose inpainted depth is not
//    > 0 are skipped. k is settings.stride, or when 0 chosen per view so that the sample spacing matches
//    the scale of the existing Gaussians near the hole: k = clamp(round(s / f), 1, max_stride), s = the
//    median over up to 512 masked pixels of the nearest existing Gaussian's in-plane size (mean of its
//    two largest scales), f = the median pixel footprint z / ((fx + fy) / 2). No existing Gaussian: k = 1.
//  - position: the pixel centre back-projected at the inpainted depth z (camera z):
//    X = R^T (z ((x + 0.5 - cx) / fx, (y + 0.5 - cy) / fy, 1) - t), as the rasterizer and the shading
//    back-project.
//  - scale and rotation: copied from the nearest existing Gaussian when its centre lies within
//    neighbour_distance x the sample spacing (k z / f); otherwise isotropic with scale = the sample
//    spacing and identity rotation.
//  - colour: SH DC = kernels::sh_dc_from_colour(rgb) from the inpainted rgb, higher SH zero.
//  - materials (logits of values clamped to [1e-3, 1 - 1e-3]): diffuse, F0, roughness, region from the
//    inpainted maps; settings' defaults (0.5, as the paper) for absent maps; label = settings.label.
//  - opacity: logit(settings.opacity) (0.1); gradients and Adam moments zero; when the model has a 3D
//    filter, variance 0.2 (z / fx)^2 from the reference camera (recompute with compute_filter3d() over
//    all training cameras when convenient).
// The reference points are EVERY masked pixel with a valid depth (no stride), with world position,
// inpainted colour, materials, world-space normal (zero without a normal map), view index and pixel.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/inpaint/map_set.h"
#include "core/inpaint/mask.h"
#include "core/io/camera.h"
#include "core/scene/gaussians.h"

namespace goris {

struct LiftSettings {
  int stride = 0;                  // k; 0 = automatic (see above)
  int max_stride = 8;
  float opacity = 0.1f;
  float neighbour_distance = 3.0f; // in sample spacings
  float diffuse = 0.5f, fresnel = 0.5f, roughness = 0.5f, region = 0.5f;  // where a map is absent
  float label = 0.01f;             // the new Gaussians are background, not the removed object
};

// One inpainted reference view. The pointers are not owned and must outlive the call.
struct LiftView {
  int view_index = -1;           // the caller's index of this view (stored with the reference points)
  Camera camera;
  const Mask* mask = nullptr;    // the inpainting mask (pixels to lift)
  const MapSet* maps = nullptr;  // the inpainted maps: depth and rgb required, the others optional
};

struct ReferencePoints {
  std::vector<glm::vec3> position, color, normal, diffuse, fresnel;
  std::vector<float> roughness, region;
  std::vector<int> view;          // LiftView::view_index
  std::vector<glm::ivec2> pixel;  // in that view
  std::size_t size() const { return position.size(); }
};

struct LiftResult {
  std::size_t first_new = 0;        // index of the first added Gaussian (the old count)
  std::size_t added = 0;
  std::vector<int> stride;          // per LiftView: the k used
  std::size_t from_neighbour = 0;   // added Gaussians whose scale/rotation came from a neighbour
  std::size_t skipped_no_depth = 0; // sampled pixels without a valid inpainted depth
  ReferencePoints points;
};

// Appends the lifted Gaussians to `model` (any device) and returns the reference points. Throws
// goris::Error when a view lacks its mask, depth or rgb, or a map's size differs from its camera's.
LiftResult lift_reference_views(GaussianModel& model, const std::vector<LiftView>& views,
                                const LiftSettings& settings = {});

// New Gaussians in the model's layout (before activation), on the host: [M][3] position, [M][3]
// log_scale, [M][4] rotation, [M] opacity_logit, [M][16][3] sh, [M][extra::kCount] extra_logit, and
// [M] filter3d_var (used only when the model has a 3D filter).
struct GaussianRows {
  std::size_t count = 0;
  std::vector<float> position, log_scale, rotation, opacity_logit, sh, extra_logit, filter3d_var;
};

// Appends rows to the model: existing values, gradients and moments are kept, the new ones have zero
// gradients and moments. Throws goris::Error when the row arrays have the wrong lengths.
void append_gaussians(GaussianModel& model, const GaussianRows& rows);

}  // namespace goris
