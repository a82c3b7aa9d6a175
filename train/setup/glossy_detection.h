#pragma once
// Finding glossy surfaces from the photos alone (for `goris train --mode auto` on data without glossy
// masks, train/setup/auto_mode.h), by multi-view photo-consistency of the INPUT photos.
//
// Why this criterion: a Lambertian surface sends the same radiance in every direction, so one surface
// point has the same colour in every photo that sees it - shadows and colour bleeding included, since they
// are baked into the surface's outgoing radiance. A glossy surface reflects its surroundings: the same
// point shows different colours from different directions. So for each training view i we take the
// geometry of the warmed-up radiance model (its rendered median depth; the model's colours are never
// compared, because a radiance model fits view-dependent colour too and would hide exactly what we look
// for), back-project every covered pixel to its surface point, project that point into the K views whose
// camera directions are nearest to i's, keep the views where the point is visible (inside the image,
// covered, and their rendered depth there agrees with the point's depth: occluded -> skipped), and ask how
// far photo_i(p) lies outside the colour range photo_j shows in a (2r+1)^2 window around the projection
// (per channel, bilinear; r = 1 absorbs the warmed-up geometry's pixel-sized misregistration at edges and
// textures, which is what makes a blurry early model look view-dependent), taking the best match along the
// epipolar segment of the depths the model shows near p (depth_window: a wide range where the geometry is
// unsure, a narrow one on a flat surface, whose reflections lie far behind it). The per-pixel score is the
// lower median of that distance over the visible views (mean over RGB; with K = 2 both views must
// disagree). Pixels above a threshold are cleaned by a morphological opening (specks) then a closing, and
// the scene counts as glossy when they cover at least a given fraction of the covered (alpha > 0.5) pixels.
//
// The detections are sparse: only reflections that change between nearby views show up (a dark table
// reflecting a dark room looks the same from everywhere, a rough surface's blurred reflections barely
// change), but they are precise (> 90 % inside the data sets' glossy masks). So the masks are then grown
// over the plane(s) most detections lie on (RANSAC on their surface points; a glossy table top or mirror
// is glossy all over); detections on a curved object, spread over no plane, stay as they are. Growing takes
// the pixels whose surface point lies on such a plane, and those whose point lies behind it, seen through
// the plane's extent (the area the views see on the plane, holes filled): a radiance model shows a mirror's
// reflections of objects as geometry behind the mirror, and those reflections are what a removal must find.
// The decision uses the detections before growing, and only a glossy scene's masks are grown; a scene whose
// detections lie on no plane stays radiance (require_plane).
//
// A radiance model explains mirror reflections by virtual geometry behind the surface, which is
// photo-consistent; the detection relies on the reflections the model has not (yet) turned into geometry.
// Where it has, that geometry is found instead: a mirror world (mirror_world_detection.h).
// Thresholds are in IntrinsicSettings (detect_*), tuned on the GOR-IS-style data sets
// (docs/lab/bench/NOTES.md, 2026-11-22).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/compute/device.h"
#include "core/io/camera.h"
#include "core/scene/gaussian_view.h"
#include "render/raster/raster_types.h"
#include "train/config/train_config.h"
#include "train/loop/trainer.h"
#include "train/setup/mirror_world_detection.h"

namespace goris {

// Defaults: those of IntrinsicSettings (detect_*), tuned on the GOR-IS-style data sets at 128 px.
struct GlossyDetectionSettings {
  int neighbours = 2;             // views each view is compared with (nearest camera directions)
  float threshold = 0.03f;        // per-pixel score above which a pixel is glossy (colour in [0, 1])
  float depth_tolerance = 0.03f;  // |z_j - depth_j| / z_j below which view j sees the same surface point
  int search_radius = 1;          // pixels: view j's colour range in a (2r+1)^2 window is a match
  // Depth search (0 = off): the colour must also lie outside what view j shows along the epipolar segment
  // of every depth the model puts within this many pixels of p (x (1 +- depth_tolerance)). Where the
  // warmed-up geometry is unsure (silhouettes, blur) that range is wide and absorbs the misregistration;
  // on a flat glossy surface it is narrow, while its reflections sit at a virtual depth far behind it.
  int depth_window = 2;
  int min_visible = 2;            // views that must see a pixel's point for it to be scored
  int morph_radius = 1;           // opening / closing radius in pixels (0 = no cleaning)
  float min_fraction = 0.0008f;   // scene glossy when the masks cover at least this fraction of covered pixels
  int work_width = 128;           // detection runs at this width at most (photos and cameras scaled down)
  // Growing the masks over the planes most detections lie on (a glossy table top, a mirror), RANSAC:
  bool grow_planes = true;
  float plane_tolerance = 0.05f;  // distance to the plane, times the median camera distance of the points
  float plane_min_share = 0.5f;   // a plane must hold this share of the detected points left (a further one
                                  // also a tenth of all)
  int plane_min_points = 50;      // fewer detected points: no growing
  // A plane is not grown over (nor counts as the glossy surface) when more than this share of its detections
  // stand in front of its surface: a table, floor or mirror shows its reflections on itself (0 - 6 % in
  // front on the GOR-IS-style suite), a textured wall behind a mounted fox shows the fox's fur and plaque
  // in front of it (39 %). See evidence_in_front in glossy_detection.cpp.
  float plane_max_in_front = 0.25f;
  bool require_plane = true;      // glossy only when the detections lie on a plane (with grow_planes)
  // Also glossy when the model holds a mirror world behind a plane (mirror_world_detection.h): a clear
  // mirror whose reflections the model has made photo-consistent geometry. The masks then cover that plane
  // and what is seen through it.
  bool mirror_world = true;
  // ... searched only in a model of at least this many Gaussians. A run stopped before it densified holds a
  // few hundred large blobs round its SfM points, whose smooth surfaces mirror each other through some plane
  // by chance (a 10-iteration run of a Lambertian lego capture: 192 Gaussians, 62 % of the points behind a
  // tilted plane mirrored); the suites' runs hold tens of thousands.
  int mirror_world_min_gaussians = 1000;

  // The settings of a run (IntrinsicSettings::detect_*).
  static GlossyDetectionSettings from_config(const TrainConfig& config);
};

// One view as the criterion reads it: host planar images at the camera's size.
struct ConsistencyView {
  Camera camera;
  const float* image = nullptr;  // [3][H][W] the photo
  const float* depth = nullptr;  // [H][W] camera z of the surface seen (read where alpha > 0.5)
  const float* alpha = nullptr;  // [H][W] coverage
};

struct GlossyDetection {
  std::vector<std::vector<std::uint8_t>> masks;  // per view [H][W]: 1 = glossy (cleaned, grown)
  std::vector<std::vector<float>> scores;        // per view [H][W]: the score, -1 = not scored
  std::vector<int> score_widths;                 // per view: W of `scores` (the working size)
  std::size_t covered = 0;   // pixels with alpha > 0.5, all views
  std::size_t scored = 0;    // covered pixels seen by at least min_visible other views
  std::size_t detected = 0;  // pixels in the cleaned masks (before growing): the evidence
  double fraction = 0;       // detected / covered
  bool glossy = false;       // fraction >= min_fraction (and something was detected)
  int planes = 0;            // planes the masks were grown over
  std::vector<glm::vec3> plane_normals;  // unit, of the planes grown over, in the order found
  // Every plane the fit found, in order: the share of its detections in front of its surface, and whether
  // it was rejected for it (plane_max_in_front).
  std::vector<float> plane_in_front;
  std::vector<bool> rejected_planes;
  std::size_t on_planes = 0;      // pixels the growing added because their surface point lies on a plane
  std::size_t behind_planes = 0;  // ... because it lies behind a plane, seen through it (a mirror world)
  std::size_t in_masks = 0;  // pixels in the final masks (grown)
  MirrorWorldPlane mirror_world;  // geometry behind a plane mirroring what stands in front (mirror_world_detection.h)
  bool by_mirror_world = false;   // glossy by the mirror world alone (the photos' evidence said radiance)
};

// The `k` views whose camera directions are nearest to view i's (largest dot product), nearest first.
std::vector<int> nearest_views(const std::vector<Camera>& cameras, int i, int k);

// The criterion on given photos and geometry (all views of one scene); `model_gaussians`: the size of the
// model the geometry comes from (s.mirror_world_min_gaussians; -1 = not a model's, no minimum). Throws
// goris::Error for views without images or with distorted cameras.
GlossyDetection detect_glossy_regions(const std::vector<ConsistencyView>& views, const GlossyDetectionSettings& s,
                                      int model_gaussians = -1);

// The same on a model: renders every view's median depth and alpha (rasterizer, `raster` settings, on
// `device`) at min(width, s.work_width) and compares the views' photos there; the masks come back at
// the views' own sizes (scores stay at the working size).
GlossyDetection detect_glossy_regions(const GaussianView& gaussians, const std::vector<TrainView>& views,
                                      const RasterSettings& raster, Device device, const GlossyDetectionSettings& s);

// Overlap of a detected mask with a reference mask (> 0.5 = inside) of the same size.
struct MaskAgreement {
  std::size_t detected = 0, reference = 0, both = 0;
  double iou() const;
  double recall() const;     // both / reference
  double precision() const;  // both / detected
};
MaskAgreement compare_masks(const std::vector<std::uint8_t>& detected, const std::vector<float>& reference);

}  // namespace goris
