#pragma once
// A normal prior from the geometry itself, for intrinsic training without a normal estimator's maps
// (`intrinsic_geometry_normals`). The paper's prior comes from a learned monocular estimator; this one is
// read off the warmed-up radiance model at the first shading iteration and then held fixed, so that the
// shading cannot turn a surface's normals to fake the reflections it sees:
//
//  - On a planar glossy surface (the plane the Gaussians over glossy pixels lie on, fitted as the glossy
//    plane constraint fits it: core/train/glossy_plane.h) every glossy pixel whose rendered surface point lies
//    on the plane (within 3 x its inlier tolerance) or beyond it (the warm-up's mirror world, seen through
//    the surface), and whose ray meets the plane inside the plane's footprint, gets the plane's normal.
//  - Every other covered pixel (alpha > 0.5) gets the normal of the rendered median depth (central
//    differences, depth_normal_loss.h's normal_from_depth), averaged over a 5 x 5 window of the pixels whose
//    depth lies within 2 % of the centre's (an edge-stopping smooth: depth normals of a splat model are
//    noisy at pixel scale, and a surface's prior should not bleed across silhouettes).
//  - Uncovered pixels carry no prior (zero), like the pixels of a loaded map without a normal.
//
// The maps are written to RUN/geometry_normals/normal_<view>.png (world space, n * 0.5 + 0.5, 16 bit: the
// format load_normal_priors reads) and become the run's `intrinsic_normals`, so a resumed run reads the
// same prior and the user can look at it.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/compute/device.h"
#include "core/scene/gaussian_view.h"
#include "core/train/trainer.h"
#include "render/raster/raster_types.h"

namespace goris {

struct GeometryNormals {
  std::vector<std::vector<float>> priors;  // per view: [3][H][W] camera space, facing the camera (TrainView::normal_prior)
  bool plane = false;                      // a glossy plane was found
  std::size_t plane_pixels = 0, depth_pixels = 0, covered = 0;  // over all views
  std::size_t beyond_pixels = 0;  // of plane_pixels: the depth showed a point beyond the plane (mirror world)
};

// The prior of every view from the model's geometry (the views' glossy masks select where the plane applies).
GeometryNormals geometry_normal_priors(const GaussianModel& model, const std::vector<TrainView>& views,
                                       const RasterSettings& raster, Device device);

// Writes each view's prior (camera space) as a world-space normal map DIR/normal_<view>.png.
void save_normal_prior_folder(const std::filesystem::path& dir, const std::vector<TrainView>& views,
                              const std::vector<std::vector<float>>& priors);

// At the first shading iteration of an intrinsic run with intrinsic_geometry_normals and no
// intrinsic_normals folder: computes the priors, writes them to RUN/geometry_normals, sets intrinsic_normals
// to that folder (config.json rewritten; later checkpoints store it) and gives them to the views. Returns a
// line for the log when it did; nullopt otherwise.
std::optional<std::string> apply_geometry_normals(Trainer& trainer, const std::filesystem::path& run_dir);

}  // namespace goris
