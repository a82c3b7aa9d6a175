// --mode auto: the photo-consistency criterion on ray-cast synthetic views (a Lambertian plane, the same
// plane with a view-dependent colour, an occluder handled by the depth test), the glossy-mask fraction
// rule, and the switch of a running trainer on the embedded default scene (masks hidden) with resume.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/io/image.h"
#include "core/train/checkpoint.h"
#include "core/train/run_folder.h"
#include "core/util/error.h"
#include "render/export/camera_path.h"
#include "render/train/intrinsic_renderer.h"
#include "render/train/auto_mode.h"
#include "render/train/glossy_detection.h"
#include "render/train/run_renderer.h"
#include "render/train/training_setup.h"
#include "tests/support/test_support.h"

namespace goris {
namespace {

namespace fs = std::filesystem;

// Ray-cast views of a textured disc (radius 1.5) in the plane z = 0, and optionally an opaque red square
// floating above it.
struct SyntheticScene {
  bool view_dependent = false;  // the plane reflects a striped environment
  bool occluder = false;        // red square [-0.3, 0.3]^2 at z = 1.5
  bool floor = false;           // a Lambertian floor at z = -1 around the disc
};

struct SyntheticView {
  Camera camera;
  std::vector<float> image, depth, alpha;
};

glm::vec3 plane_texture(glm::vec3 p) {
  return {0.5f + 0.3f * std::sin(4.0f * p.x), 0.5f + 0.3f * std::cos(3.0f * p.y), 0.4f + 0.2f * std::sin(2.0f * p.x + 3.0f * p.y)};
}

SyntheticView cast(const SyntheticScene& s, const Camera& cam) {
  SyntheticView v{cam, {}, {}, {}};
  const int w = cam.width, h = cam.height;
  const size_t hw = size_t(w) * size_t(h);
  v.image.assign(3 * hw, 0.0f);
  v.depth.assign(hw, 0.0f);
  v.alpha.assign(hw, 0.0f);
  const glm::vec3 eye = cam.center();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3 d = cam.ray_direction(float(x) + 0.5f, float(y) + 0.5f);
      glm::vec3 hit, color;
      bool found = false;
      if (s.occluder && d.z < 0) {
        const float t = (1.5f - eye.z) / d.z;
        const glm::vec3 p = eye + t * d;
        if (t > 0 && std::abs(p.x) <= 0.3f && std::abs(p.y) <= 0.3f) {
          hit = p;
          color = {0.9f, 0.1f, 0.1f};
          found = true;
        }
      }
      if (!found && d.z < 0 && glm::length(glm::vec2(eye + (-eye.z / d.z) * d)) <= 1.5f) {
        hit = eye + (-eye.z / d.z) * d;
        color = plane_texture(hit);
        if (s.view_dependent) {
          const glm::vec3 r(d.x, d.y, -d.z);  // mirror direction about the plane's normal
          const float az = std::atan2(r.y, r.x);
          const glm::vec3 env(0.5f + 0.5f * std::sin(8 * az), 0.5f + 0.5f * std::sin(8 * az + 2), 0.5f + 0.5f * std::sin(8 * az + 4));
          color = 0.3f * color + 0.7f * env;
        }
        found = true;
      }
      if (!found && s.floor && d.z < 0) {
        hit = eye + ((-1.0f - eye.z) / d.z) * d;
        color = 0.8f * plane_texture(2.0f * hit + 1.0f);
        found = true;
      }
      if (!found) continue;
      const size_t p = size_t(y) * w + x;
      for (int c = 0; c < 3; ++c) v.image[c * hw + p] = color[c];
      v.depth[p] = cam.to_camera(hit).z;
      v.alpha[p] = 1.0f;
    }
  return v;
}

Camera base_camera(int size) {
  Camera c;
  c.width = c.height = size;
  c.fx = c.fy = 1.1f * float(size);
  c.cx = c.cy = 0.5f * float(size);
  return c;
}

// Eight cameras on a ring around the origin, looking at it from 40 degrees above the plane.
std::vector<SyntheticView> ring_views(const SyntheticScene& s, int size = 48) {
  std::vector<SyntheticView> out;
  for (int k = 0; k < 8; ++k) {
    const float a = 2.0f * 3.14159265f * float(k) / 8.0f;
    const glm::vec3 eye(3.0f * std::cos(a), 3.0f * std::sin(a), 2.5f);
    out.push_back(cast(s, look_at_camera(base_camera(size), eye, glm::vec3(0.0f), glm::vec3(0, 0, 1))));
  }
  return out;
}

// Five cameras on a line 3 units above the plane looking straight down: from the last one, the plane
// beside the occluder is hidden behind it in every other view.
std::vector<SyntheticView> rig_views(const SyntheticScene& s) {
  std::vector<SyntheticView> out;
  for (int k = 0; k < 5; ++k) {
    const glm::vec3 eye(-0.6f + 0.3f * float(k), 0.0f, 3.0f);
    out.push_back(cast(s, look_at_camera(base_camera(48), eye, eye - glm::vec3(0, 0, 1), glm::vec3(0, 1, 0))));
  }
  return out;
}

GlossyDetection detect(const std::vector<SyntheticView>& views, const GlossyDetectionSettings& s = {}) {
  std::vector<ConsistencyView> cv;
  for (const SyntheticView& v : views) cv.push_back({v.camera, v.image.data(), v.depth.data(), v.alpha.data()});
  return detect_glossy_regions(cv, s);
}

TEST(GlossyDetection, LambertianPlaneIsConsistent) {
  const GlossyDetection d = detect(ring_views({}));
  EXPECT_GT(d.covered, 8u * 48u * 48u / 4);
  EXPECT_GT(d.scored, d.covered / 2);
  EXPECT_EQ(d.detected, 0u) << "fraction " << d.fraction;
  EXPECT_FALSE(d.glossy);
}

TEST(GlossyDetection, ViewDependentPlaneIsDetected) {
  const GlossyDetection d = detect(ring_views({/*view_dependent=*/true, false}));
  // Not all of it: where the stripes repeat along a pixel's epipolar depth search the colour matches.
  EXPECT_GT(d.fraction, 0.3);
  EXPECT_TRUE(d.glossy);
  ASSERT_EQ(d.masks.size(), 8u);
  ASSERT_EQ(d.masks[0].size(), 48u * 48u);
}

TEST(GlossyDetection, OccludedPointsAreSkippedByTheDepthTest) {
  const std::vector<SyntheticView> views = rig_views({false, /*occluder=*/true});
  const GlossyDetection d = detect(views);
  EXPECT_EQ(d.detected, 0u) << "fraction " << d.fraction;
  EXPECT_FALSE(d.glossy);
  // Without the depth test the plane next to the square compares with the square's red in the other views.
  GlossyDetectionSettings no_test;
  no_test.depth_tolerance = 1e6f;
  const GlossyDetection bad = detect(views, no_test);
  EXPECT_GT(bad.detected, 50u);
  EXPECT_GT(bad.detected, d.detected);
}

// A checkerboard plane whose model depth is 7 % too far everywhere (an unsettled warm-up): every pixel
// reprojects a few pixels off, so the checker's edges disagree between views although nothing is glossy.
std::vector<SyntheticView> misregistered_checker_views() {
  std::vector<SyntheticView> views = ring_views({});
  for (SyntheticView& v : views) {
    const Camera& c = v.camera;
    const size_t hw = size_t(c.width) * c.height;
    for (size_t p = 0; p < hw; ++p) {
      if (!(v.alpha[p] > 0.5f)) continue;
      const glm::vec3 d = c.ray_direction(float(p % c.width) + 0.5f, float(p / c.width) + 0.5f);
      const glm::vec3 x = c.center() + (v.depth[p] / glm::dot(d, c.forward())) * d;
      const float k = ((int(std::floor(x.x / 0.6f)) + int(std::floor(x.y / 0.6f))) & 1) ? 0.8f : 0.2f;
      for (int ch = 0; ch < 3; ++ch) v.image[ch * hw + p] = k;
      v.depth[p] *= 1.07f;
    }
  }
  return views;
}

TEST(GlossyDetection, TheDepthWindowAbsorbsMisregisteredGeometry) {
  GlossyDetectionSettings off;
  off.depth_tolerance = 0.1f;  // the views still see "the same point"
  off.depth_window = 0;
  off.morph_radius = 0;  // the disagreement is a thin line along each edge
  GlossyDetectionSettings on = off;
  on.depth_window = 1;
  const std::vector<SyntheticView> views = misregistered_checker_views();
  const GlossyDetection blurred = detect(views, off), searched = detect(views, on);
  EXPECT_GT(blurred.fraction, 0.005) << "the misregistered checker should look view-dependent without the search";
  EXPECT_LT(searched.detected * 10, blurred.detected) << searched.detected << " vs " << blurred.detected;
  // A reflection sits far behind the plane: the search around its depth leaves it detected.
  const GlossyDetection glossy = detect(ring_views({true, false}), on);
  EXPECT_GT(glossy.fraction, 0.3);
}

TEST(GlossyDetection, DetectionsOnNoPlaneStayRadiance) {
  // The view-dependent plane, with plane fitting unable to find it (too few points asked for): the
  // detections lie on no plane, so the scene is left to the radiance model - unless a plane is not required.
  GlossyDetectionSettings s;
  s.plane_min_points = 1 << 30;
  const GlossyDetection d = detect(ring_views({/*view_dependent=*/true, false}), s);
  EXPECT_GT(d.fraction, 0.3);
  EXPECT_EQ(d.planes, 0);
  EXPECT_FALSE(d.glossy);
  s.require_plane = false;
  EXPECT_TRUE(detect(ring_views({true, false}), s).glossy);
}

TEST(GlossyDetection, MasksGrowOverThePlaneOfTheDetections) {
  // The plane is glossy only where x > 0 (the reflection); the grown masks cover all of it but not the
  // Lambertian square floating above it.
  SyntheticScene scene{true, true};
  std::vector<SyntheticView> views = ring_views(scene);
  const std::vector<SyntheticView> lambertian = ring_views({false, true});
  std::vector<std::vector<std::uint8_t>> on_square(views.size());
  for (size_t i = 0; i < views.size(); ++i) {
    const Camera& c = views[i].camera;
    const size_t hw = size_t(c.width) * c.height;
    on_square[i].assign(hw, 0);
    for (size_t p = 0; p < hw; ++p) {
      const glm::vec3 d = c.ray_direction(float(p % c.width) + 0.5f, float(p / c.width) + 0.5f);
      const glm::vec3 x = c.center() + (views[i].depth[p] / glm::dot(d, c.forward())) * d;
      on_square[i][p] = x.z > 0.5f;
      if (x.x < 0 || x.z > 0.5f)
        for (int ch = 0; ch < 3; ++ch) views[i].image[ch * hw + p] = lambertian[i].image[ch * hw + p];
    }
  }
  GlossyDetectionSettings s;
  s.grow_planes = false;
  const GlossyDetection seeds = detect(views, s);
  const GlossyDetection grown = detect(views);
  EXPECT_TRUE(grown.glossy);
  EXPECT_EQ(grown.detected, seeds.detected) << "the decision must not see the growing";
  EXPECT_EQ(grown.planes, 1);
  size_t plane = 0, plane_marked = 0, square = 0, square_marked = 0, seed_plane = 0, seed_square = 0;
  for (size_t i = 0; i < views.size(); ++i)
    for (size_t p = 0; p < views[i].depth.size(); ++p) {
      if (!(views[i].alpha[p] > 0.5f)) continue;
      const bool sq = on_square[i][p] != 0;
      (sq ? square : plane) += 1;
      (sq ? square_marked : plane_marked) += grown.masks[i][p];
      seed_plane += !sq && seeds.masks[i][p];
      seed_square += sq && seeds.masks[i][p];
    }
  EXPECT_LT(double(seed_plane), 0.7 * double(plane));
  EXPECT_GT(double(plane_marked), 0.97 * double(plane));
  EXPECT_EQ(square_marked, seed_square) << "the square 1.5 above the plane was grown over";
  EXPECT_GT(square, 100u);
}

TEST(GlossyDetection, MasksGrowOverReflectionsTheModelPutsBehindThePlane) {
  // A radiance model shows a mirror's reflections as geometry behind it: where the disc shows a patch of
  // such virtual geometry (depth as if at z = -0.8), the surface points lie off the plane, but the views see
  // them through the disc - they are glossy. The floor around the disc also lies behind the plane, but is
  // seen beside it, not through it.
  std::vector<SyntheticView> views = ring_views({true, true, true});
  const std::vector<SyntheticView> lambertian = ring_views({false, true, true});
  enum Kind { kOther, kPlane, kPatch, kFloor };
  std::vector<std::vector<Kind>> kind(views.size());
  for (size_t i = 0; i < views.size(); ++i) {
    const Camera& c = views[i].camera;
    const size_t hw = size_t(c.width) * c.height;
    kind[i].assign(hw, kOther);
    for (size_t p = 0; p < hw; ++p) {
      if (!(views[i].alpha[p] > 0.5f)) continue;
      const glm::vec3 d = c.ray_direction(float(p % c.width) + 0.5f, float(p / c.width) + 0.5f);
      const float t = views[i].depth[p] / glm::dot(d, c.forward());
      const glm::vec3 x = c.center() + t * d;
      if (x.x < 0 || x.z > 0.5f)  // the glossy half of the disc only
        for (int ch = 0; ch < 3; ++ch) views[i].image[ch * hw + p] = lambertian[i].image[ch * hw + p];
      if (x.z < -0.5f) {
        kind[i][p] = kFloor;
      } else if (std::abs(x.z) < 1e-3f) {
        kind[i][p] = kPlane;
        if (std::abs(x.x - 0.5f) < 0.3f && std::abs(x.y) < 0.3f) {
          kind[i][p] = kPatch;
          views[i].depth[p] *= (-0.8f - c.center().z) / (x.z - c.center().z);
        }
      }
    }
  }
  const GlossyDetection grown = detect(views);
  ASSERT_TRUE(grown.glossy);
  ASSERT_EQ(grown.planes, 1);
  size_t count[4] = {}, marked[4] = {};
  for (size_t i = 0; i < views.size(); ++i)
    for (size_t p = 0; p < views[i].depth.size(); ++p) {
      count[kind[i][p]] += 1;
      marked[kind[i][p]] += grown.masks[i][p];
    }
  EXPECT_GT(count[kPatch], 200u);
  EXPECT_GT(count[kFloor], 1000u);
  EXPECT_GT(double(marked[kPlane]), 0.97 * double(count[kPlane]));
  EXPECT_GT(double(marked[kPatch]), 0.97 * double(count[kPatch])) << "the reflections behind the plane";
  EXPECT_LT(double(marked[kFloor]), 0.03 * double(count[kFloor])) << "the floor beside the disc";
  // The counts of what the growing added: the plane's pixels on it, the patch's behind it, the plane's normal z.
  EXPECT_EQ(grown.in_masks, grown.detected + grown.on_planes + grown.behind_planes);
  EXPECT_GT(grown.behind_planes, count[kPatch] / 4) << "the patch is seen through the plane";
  EXPECT_GT(grown.on_planes, grown.behind_planes);
  ASSERT_EQ(grown.plane_normals.size(), 1u);
  EXPECT_GT(std::abs(grown.plane_normals[0].z), 0.99f);
}

// The disc at 96 px, view-dependent only on a patch [0.1, 0.9] x [-0.4, 0.4] (9 % of it) whose surface stands
// `height` above the disc (depths moved along each pixel's ray; the colours stay those of the patch on it).
std::vector<SyntheticView> patch_views(float height) {
  std::vector<SyntheticView> views = ring_views({true, false}, 96);
  const std::vector<SyntheticView> lambertian = ring_views({}, 96);
  for (size_t i = 0; i < views.size(); ++i) {
    const Camera& c = views[i].camera;
    const size_t hw = size_t(c.width) * c.height;
    for (size_t p = 0; p < hw; ++p) {
      if (!(views[i].alpha[p] > 0.5f)) continue;
      const glm::vec3 d = c.ray_direction(float(p % c.width) + 0.5f, float(p / c.width) + 0.5f);
      const glm::vec3 x = c.center() + (views[i].depth[p] / glm::dot(d, c.forward())) * d;
      if (std::abs(x.x - 0.5f) < 0.4f && std::abs(x.y) < 0.4f) {
        views[i].depth[p] *= (height - c.center().z) / (x.z - c.center().z);
      } else {
        for (int ch = 0; ch < 3; ++ch) views[i].image[ch * hw + p] = lambertian[i].image[ch * hw + p];
      }
    }
  }
  return views;
}

TEST(GlossyDetection, ViewDependenceInFrontOfAPlaneIsNotItsReflection) {
  // On the disc's surface the patch is a reflection of the disc: the plane is kept and grown over.
  const GlossyDetection on = detect(patch_views(0.0f));
  ASSERT_TRUE(on.glossy) << on.detected << " detected, " << on.planes << " planes, fraction " << on.fraction;
  EXPECT_EQ(on.planes, 1);
  ASSERT_EQ(on.plane_in_front.size(), 1u);
  EXPECT_LT(on.plane_in_front[0], 0.05f);
  EXPECT_GT(on.on_planes, on.detected);
  // Standing 0.12 in front of it (inside the plane fit's tolerance, beyond the disc's thickness), the
  // view dependence belongs to something before the disc (fur before a papered wall): no plane, radiance.
  const GlossyDetection front = detect(patch_views(0.12f));
  EXPECT_GT(front.detected, 200u);
  ASSERT_EQ(front.plane_in_front.size(), 1u);
  EXPECT_GT(front.plane_in_front[0], 0.5f);
  EXPECT_EQ(front.rejected_planes, std::vector<bool>{true});
  EXPECT_EQ(front.planes, 0);
  EXPECT_EQ(front.on_planes + front.behind_planes, 0u);
  EXPECT_FALSE(front.glossy);
  // The same with the test off: the backdrop would be grown over and the scene called glossy.
  GlossyDetectionSettings s;
  s.plane_max_in_front = 1.0f;
  const GlossyDetection without = detect(patch_views(0.12f), s);
  EXPECT_EQ(without.planes, 1);
  EXPECT_TRUE(without.glossy);
}

TEST(GlossyDetection, NearestViewsFollowTheCameraDirection) {
  const std::vector<SyntheticView> views = ring_views({});
  std::vector<Camera> cams;
  for (const auto& v : views) cams.push_back(v.camera);
  const std::vector<int> n = nearest_views(cams, 0, 4);
  ASSERT_EQ(n.size(), 4u);
  // Ring neighbours first (1 and 7, 45 degrees), then 2 and 6 (90 degrees).
  EXPECT_TRUE((n[0] == 1 && n[1] == 7) || (n[0] == 7 && n[1] == 1));
  EXPECT_TRUE((n[2] == 2 && n[3] == 6) || (n[2] == 6 && n[3] == 2));
  EXPECT_EQ(nearest_views(cams, 3, 20).size(), 7u);
}

TEST(GlossyDetection, BadInputIsAnError) {
  std::vector<ConsistencyView> cv(1);
  EXPECT_THROW(detect_glossy_regions(cv, {}), Error);
  GlossyDetectionSettings s;
  s.neighbours = 0;
  EXPECT_THROW(detect_glossy_regions({}, s), Error);
}

TEST(GlossyDetection, MaskAgreement) {
  const MaskAgreement a = compare_masks({1, 1, 0, 0}, {1.0f, 0.0f, 1.0f, 0.0f});
  EXPECT_DOUBLE_EQ(a.iou(), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(a.recall(), 0.5);
  EXPECT_DOUBLE_EQ(a.precision(), 0.5);
  EXPECT_THROW(compare_masks({1}, {}), Error);
}

// --- the mask-fraction rule --------------------------------------------------------------------------

std::vector<TrainView> views_with_masks(int n_views, int glossy_pixels_per_view, bool masks = true) {
  std::vector<TrainView> out;
  for (int i = 0; i < n_views; ++i) {
    TrainView v;
    v.name = "v" + std::to_string(i);
    v.camera = base_camera(10);
    v.image.assign(300, 0.5f);
    if (masks) {
      v.glossy_mask.assign(100, 0.0f);
      for (int p = 0; p < glossy_pixels_per_view; ++p) v.glossy_mask[size_t(p)] = 0.8f;
    }
    out.push_back(std::move(v));
  }
  return out;
}

TEST(AutoMode, MaskFractionRule) {
  TrainConfig c;
  c.mode = "auto";
  EXPECT_NE(resolve_auto_mode(c, views_with_masks(4, 0)).find("empty"), std::string::npos);
  EXPECT_EQ(c.mode, "radiance");
  EXPECT_FALSE(c.auto_detect_glossy);

  c.mode = "auto";  // 1 % of the pixels: above the 0.5 % default
  EXPECT_NE(resolve_auto_mode(c, views_with_masks(4, 1)).find("mark"), std::string::npos);
  EXPECT_EQ(c.mode, "intrinsic");

  c.mode = "auto";
  c.intrinsic.auto_mask_fraction = 0.02f;
  resolve_auto_mode(c, views_with_masks(4, 1));
  EXPECT_EQ(c.mode, "radiance");
  EXPECT_DOUBLE_EQ(*glossy_mask_fraction(views_with_masks(4, 1)), 0.01);

  c.mode = "auto";
  c.iterations = 30000;
  const std::string long_run = resolve_auto_mode(c, views_with_masks(4, 0, false));
  EXPECT_NE(long_run.find("no glossy masks"), std::string::npos);
  EXPECT_EQ(long_run.find("caution"), std::string::npos);
  EXPECT_EQ(c.mode, "radiance");
  EXPECT_TRUE(c.auto_detect_glossy);
  c.mode = "auto";  // a run that ends before the geometry has settled decides anyway, with a caution
  c.iterations = 500;
  EXPECT_NE(resolve_auto_mode(c, views_with_masks(4, 0, false)).find("caution"), std::string::npos);
  EXPECT_FALSE(glossy_mask_fraction(views_with_masks(2, 0, false)).has_value());

  TrainConfig given;
  given.mode = "intrinsic";
  EXPECT_EQ(resolve_auto_mode(given, views_with_masks(2, 0)), "");
  EXPECT_EQ(given.mode, "intrinsic");
}

TEST(AutoMode, DetectionWaitsForTheGeometry) {
  TrainConfig c;
  c.intrinsic.detect_settled = 0;  // the planned start alone (the settled floor: the next test)
  c.iterations = 30000;
  EXPECT_EQ(auto_detection_iteration(c), 4000);  // the warm-up
  c.iterations = 4000;  // warm-up 533, but the geometry needs longer: half the run
  EXPECT_EQ(auto_detection_iteration(c), 2000);
  c.intrinsic.detect_after = 0;
  EXPECT_EQ(auto_detection_iteration(c), 2000);  // the warm-up keeps half of a short run too
  c.intrinsic.warmup_min_fraction = 0;
  EXPECT_EQ(auto_detection_iteration(c), 533);
  c.intrinsic.detect_after = 4000;
  c.intrinsic.warmup = 20000;  // a longer warm-up wins
  EXPECT_EQ(auto_detection_iteration(c), 2667);
}

TEST(AutoMode, ShortRunsDecideOnceTheGeometryHasSettledAndKeepTheirShadingPhase) {
  TrainConfig c;
  c.intrinsic.detect_settled = 2000;
  c.iterations = 2000;  // planned: half the run; the geometry settles only at 2000, the run's end
  EXPECT_EQ(planned_shading_start(c), 1000);
  EXPECT_EQ(auto_detection_iteration(c), 2000);
  TrainConfig l = lengthened_for_late_decision(c, 2000);
  EXPECT_EQ(l.iterations, 3000);  // the planned 1000 shading iterations follow the decision
  c.iterations = 3000;
  EXPECT_EQ(auto_detection_iteration(c), 2000);
  EXPECT_EQ(lengthened_for_late_decision(c, 2000).iterations, 3500);
  c.iterations = 500;  // too short to settle: decided at the end
  EXPECT_EQ(auto_detection_iteration(c), 500);
  EXPECT_EQ(lengthened_for_late_decision(c, 500).iterations, 750);
  c.iterations = 4000;  // long enough: as planned, nothing lengthened
  EXPECT_EQ(auto_detection_iteration(c), 2000);
  const TrainConfig same = lengthened_for_late_decision(c, 2000);
  EXPECT_EQ(same.iterations, 4000);
  c.intrinsic.detect_settled = TrainConfig().intrinsic.detect_settled;  // the default, 4000: a 4K run
  EXPECT_EQ(auto_detection_iteration(c), 4000);                         // decides at its end ...
  EXPECT_EQ(lengthened_for_late_decision(c, 4000).iterations, 6000);   // ... and adds its 2K of shading
  c.iterations = 30000;  // the full schedule: at the warm-up's end, as planned
  EXPECT_EQ(auto_detection_iteration(c), 4000);
  c.iterations = 4000;
  c.iterations = 2000;
  c.intrinsic.detect_settled = 0;  // off: the planned start
  EXPECT_EQ(auto_detection_iteration(c), 1000);
}

TEST(AutoMode, MaskFolderErrorsNameTheFile) {
  const fs::path dir = test::scratch_dir("auto_mode_mask_folder");
  std::vector<TrainView> views = views_with_masks(1, 0, false);
  try {
    load_glossy_mask_folder(dir, views);
    FAIL() << "a missing mask was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("gloss_v0.png"), std::string::npos) << e.what();
  }
  save_png(dir / "gloss_v0.png", Image(12, 10, 1));
  EXPECT_THROW(load_glossy_mask_folder(dir, views), Error);
  Image ok(10, 10, 1);
  ok.pixels.fill_zero();
  ok.pixels[3] = 1.0f;
  save_png(dir / "gloss_v0.png", ok);
  load_glossy_mask_folder(dir, views);
  EXPECT_FLOAT_EQ(views[0].glossy_mask[3], 1.0f);
  EXPECT_THROW(load_glossy_mask_folder(dir / "absent", views), Error);
}

// --- the switch on the default scene ----------------------------------------------------------------

// A tiny auto run on the default scene with its glossy masks hidden: 32 px, 40 iterations, detection
// after 20 (the warm-up set to 15000 of 30000, scaled).
TrainConfig tiny_auto_config() {
  TrainConfig c;
  c.mode = "auto";
  c.data = (test::resource_dir() / "default_scene").string();
  c.device = "cpu";
  c.resolution = 32;
  c.iterations = 40;
  c.random_init_points = 4000;
  c.use_glossy_masks = false;
  c.intrinsic.warmup = 15000;
  c.intrinsic.env_resolution = 8;
  c.intrinsic.net_hidden_layers = 1;
  c.intrinsic.detect_settled = 0;  // decide at the planned shading start (the late decision has its own test)
  c.checkpoint_interval = 10;
  c.keep_checkpoints = 10;
  return c;
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f);
}

TEST(AutoMode, SwitchesToIntrinsicWithTheDetectedMasksAndResumes) {
  const fs::path run = test::scratch_dir("auto_mode_switch");
  TrainConfig c = tiny_auto_config();
  c.intrinsic.detect_threshold = 0.0f;  // every scored pixel: the decision is forced to "glossy"
  c.intrinsic.detect_fraction = 0.0f;
  PreparedTraining p = prepare_training(run, c, std::nullopt);
  Trainer& t = *p.trainer;
  EXPECT_EQ(p.config.mode, "radiance");
  EXPECT_TRUE(p.config.auto_detect_glossy);
  EXPECT_NE(p.auto_mode_reason.find("no glossy masks"), std::string::npos);
  EXPECT_EQ(auto_detection_iteration(p.config), 20);
  for (const TrainView& v : t.views()) EXPECT_TRUE(v.glossy_mask.empty());

  // Step by hand up to the end of the warm-up: nothing happens before it.
  while (t.state().iteration < 20) {
    EXPECT_FALSE(apply_auto_mode(t, run).has_value());
    t.step();
    if (t.state().iteration == 10) t.save_checkpoint(checkpoint_path(run, 10));
  }
  EXPECT_FALSE(t.intrinsic());
  const std::array<int, kGroupCount> steps_before = t.state().adam.steps;
  EXPECT_EQ(steps_before[size_t(ParamGroup::Region)], 0);
  const float init_region = std::log(0.9f / 0.1f);  // the material extras never trained in radiance mode
  EXPECT_NEAR(t.model().values(Param::ExtraLogit)[extra::kRegion], init_region, 1e-5f);

  const std::optional<AutoDecision> d = apply_auto_mode(t, run);
  ASSERT_TRUE(d.has_value());
  EXPECT_TRUE(d->glossy) << d->message();
  EXPECT_GT(d->covered, 0u);
  EXPECT_EQ(d->iteration, 20);
  EXPECT_TRUE(t.intrinsic());
  EXPECT_NE(as_intrinsic(t.renderer().get()), nullptr);
  EXPECT_FALSE(t.config().auto_detect_glossy);
  EXPECT_EQ(fs::path(t.config().glossy_mask_dir), run / "detected_gloss");
  EXPECT_EQ(t.config().shading_from(), 20) << "shading starts at the switch";
  EXPECT_FALSE(apply_auto_mode(t, run).has_value()) << "decided twice";
  // Masks: files at the training size, the views' glossy masks, the summary, config.json.
  for (const TrainView& v : t.views()) {
    ASSERT_EQ(v.glossy_mask.size(), size_t(v.camera.width) * v.camera.height);
    const Image m = load_mask(run / "detected_gloss" / ("gloss_" + v.name + ".png"));
    ASSERT_EQ(m.pixel_count(), v.glossy_mask.size());
    for (size_t q = 0; q < m.pixel_count(); ++q) ASSERT_EQ(m.pixels[q], v.glossy_mask[q]);
  }
  const nlohmann::json summary = read_json(run / "detected_gloss" / "summary.json");
  EXPECT_EQ(summary["decision"], "intrinsic");
  EXPECT_EQ(summary["iteration"], 20);
  EXPECT_TRUE(summary.contains("seconds") && summary.contains("fraction") && summary.contains("threshold"));
  EXPECT_EQ(read_run_config(run).mode, "intrinsic");
  // The extras' groups start fresh; the others keep their step counts.
  for (ParamGroup g : {ParamGroup::Materials, ParamGroup::Region, ParamGroup::Label})
    EXPECT_EQ(t.state().adam.steps[size_t(g)], 0) << group_name(g);
  const std::vector<float> m = t.model().tensor(Param::ExtraLogit).adam_m.to_host();
  for (float x : m) ASSERT_EQ(x, 0.0f);

  t.step();
  EXPECT_EQ(t.state().adam.steps[size_t(ParamGroup::Region)], 1);
  EXPECT_EQ(t.state().adam.steps[size_t(ParamGroup::Position)], steps_before[size_t(ParamGroup::Position)] + 1);

  // Through run(): the checkpoints after the switch carry the intrinsic configuration.
  Trainer::RunOptions ro;
  ro.run_dir = run;
  ro.before_step = [&](Trainer& tr) { apply_auto_mode(tr, run); };
  t.run(ro);
  write_trained_run(run, t, *t.renderer());
  EXPECT_TRUE(fs::exists(run / "environment.png"));
  const std::vector<std::uint8_t> mask0(t.views()[0].glossy_mask.begin(), t.views()[0].glossy_mask.end());

  // Resumed with more iterations: intrinsic again, with the same masks.
  std::optional<ResumePoint> r = read_latest_checkpoint(run);
  ASSERT_TRUE(r.has_value());
  TrainConfig rc = r->checkpoint.config;
  EXPECT_EQ(rc.mode, "intrinsic");
  rc.iterations = 45;
  PreparedTraining p2 = prepare_training(run, rc, std::move(r));
  EXPECT_TRUE(p2.trainer->intrinsic());
  EXPECT_EQ(p2.auto_mode_reason, "");
  EXPECT_EQ(p2.glossy_views, p2.trainer->views().size());
  const std::vector<float>& g0 = p2.trainer->views()[0].glossy_mask;
  ASSERT_EQ(g0.size(), mask0.size());
  for (size_t q = 0; q < g0.size(); ++q) ASSERT_EQ(g0[q], float(mask0[q]));
  p2.trainer->step();

  // A checkpoint written before the decision resumes in radiance mode with the detection still to come.
  const Checkpoint early = read_checkpoint(checkpoint_path(run, 10), Device::CPU);
  EXPECT_EQ(early.config.mode, "radiance");
  EXPECT_TRUE(early.config.auto_detect_glossy);
}

TEST(AutoMode, StaysRadianceWhenNothingIsGlossy) {
  const fs::path run = test::scratch_dir("auto_mode_radiance");
  TrainConfig c = tiny_auto_config();
  c.iterations = 24;
  c.intrinsic.warmup = 25000;  // detection after 20
  c.intrinsic.detect_threshold = 1e6f;  // nothing is glossy
  PreparedTraining p = prepare_training(run, c, std::nullopt);
  Trainer& t = *p.trainer;
  const auto renderer_before = t.renderer();
  std::vector<AutoDecision> decisions;
  Trainer::RunOptions ro;
  ro.run_dir = run;
  ro.before_step = [&](Trainer& tr) {
    if (auto d = apply_auto_mode(tr, run)) decisions.push_back(*d);
  };
  t.run(ro);
  ASSERT_EQ(decisions.size(), 1u);
  EXPECT_FALSE(decisions[0].glossy);
  EXPECT_EQ(decisions[0].detected, 0u);
  EXPECT_NE(decisions[0].message().find("radiance to the end"), std::string::npos);
  EXPECT_FALSE(t.intrinsic());
  EXPECT_EQ(t.renderer(), renderer_before);
  EXPECT_FALSE(t.config().auto_detect_glossy);
  EXPECT_TRUE(t.config().glossy_mask_dir.empty());
  for (ParamGroup g : {ParamGroup::Materials, ParamGroup::Region, ParamGroup::Label})
    EXPECT_EQ(t.state().adam.steps[size_t(g)], 0) << group_name(g);
  write_trained_run(run, t, *t.renderer());
  EXPECT_FALSE(fs::exists(run / "environment.png"));
  EXPECT_EQ(read_json(run / "detected_gloss" / "summary.json")["decision"], "radiance");
  const TrainConfig saved = read_run_config(run);
  EXPECT_EQ(saved.mode, "radiance");
  EXPECT_FALSE(saved.auto_detect_glossy);
  const Checkpoint last = read_checkpoint(checkpoint_path(run, 24), Device::CPU);
  EXPECT_FALSE(last.config.auto_detect_glossy);
}

TEST(AutoMode, ALateGlossyDecisionAtTheEndLengthensTheRun) {
  // 40 iterations, shading planned from 20, but the geometry "settles" only at 40: run() decides after
  // the last iteration and goes on for the planned 20 shading iterations.
  const fs::path run = test::scratch_dir("auto_mode_late");
  TrainConfig c = tiny_auto_config();
  c.intrinsic.detect_settled = 40;
  c.intrinsic.detect_threshold = 0.0f;  // forced "glossy"
  c.intrinsic.detect_fraction = 0.0f;
  c.checkpoint_interval = 100;
  PreparedTraining p = prepare_training(run, c, std::nullopt);
  Trainer& t = *p.trainer;
  EXPECT_EQ(auto_detection_iteration(p.config), 40);
  std::vector<AutoDecision> decisions;
  Trainer::RunOptions ro;
  ro.run_dir = run;
  ro.before_step = [&](Trainer& tr) {
    if (auto d = apply_auto_mode(tr, run)) decisions.push_back(*d);
  };
  EXPECT_EQ(t.run(ro), Trainer::RunResult::Finished);
  ASSERT_EQ(decisions.size(), 1u);
  EXPECT_TRUE(decisions[0].glossy);
  EXPECT_EQ(decisions[0].iteration, 40);
  EXPECT_EQ(decisions[0].extended_by, 20);
  EXPECT_NE(decisions[0].message().find("grows by 20 iterations"), std::string::npos) << decisions[0].message();
  EXPECT_TRUE(t.intrinsic());
  EXPECT_EQ(t.state().iteration, 60);
  EXPECT_EQ(t.config().iterations, 60);
  EXPECT_EQ(t.config().shading_from(), 40);
  EXPECT_GT(t.state().adam.steps[size_t(ParamGroup::Region)], 0);
  const TrainConfig saved = read_run_config(run);
  EXPECT_EQ(saved.iterations, 60);
  EXPECT_EQ(saved.mode, "intrinsic");

  // The same run on a scene with nothing glossy keeps its length.
  const fs::path run2 = test::scratch_dir("auto_mode_late_radiance");
  c.intrinsic.detect_threshold = 1e6f;
  c.intrinsic.detect_fraction = 0.0008f;
  PreparedTraining p2 = prepare_training(run2, c, std::nullopt);
  decisions.clear();
  ro.run_dir = run2;
  ro.before_step = [&](Trainer& tr) {
    if (auto d = apply_auto_mode(tr, run2)) decisions.push_back(*d);
  };
  p2.trainer->run(ro);
  ASSERT_EQ(decisions.size(), 1u);
  EXPECT_FALSE(decisions[0].glossy);
  EXPECT_EQ(decisions[0].extended_by, 0);
  EXPECT_EQ(p2.trainer->state().iteration, 40);
  EXPECT_FALSE(p2.trainer->intrinsic());
}

TEST(AutoMode, EmbeddedSceneMasksChooseIntrinsic) {
  TrainConfig c = tiny_auto_config();
  c.use_glossy_masks = true;
  c.iterations = 1;
  PreparedTraining p = prepare_training(test::scratch_dir("auto_mode_masks"), c, std::nullopt);
  EXPECT_EQ(p.config.mode, "intrinsic");
  EXPECT_FALSE(p.config.auto_detect_glossy);
  EXPECT_NE(p.auto_mode_reason.find("mark"), std::string::npos) << p.auto_mode_reason;
}

}  // namespace
}  // namespace goris
