// --mode auto's glossy detection: the photo-consistency criterion on ray-cast synthetic views (a Lambertian
// plane, the same plane with a view-dependent colour, an occluder handled by the depth test), the growing
// over planes, the planes set aside as backdrops, and a mirror world found without evidence in the photos. The decision's rules and the switch of a running
// trainer are in test_auto_mode.cpp.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/util/error.h"
#include "export/frames/camera_path.h"
#include "tests/support/test_support.h"
#include "train/setup/glossy_detection.h"

namespace goris {
namespace {

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

GlossyDetection detect(const std::vector<SyntheticView>& views, const GlossyDetectionSettings& s = {},
                       int model_gaussians = -1) {
  std::vector<ConsistencyView> cv;
  for (const SyntheticView& v : views) cv.push_back({v.camera, v.image.data(), v.depth.data(), v.alpha.data()});
  return detect_glossy_regions(cv, s, model_gaussians);
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

// A ball of radius 0.4 standing on the Lambertian disc, which mirrors it as a radiance model shows a mirror:
// where the disc's reflection of a ray meets the ball, the view sees the ball's colour at the virtual point
// behind the disc (the hit continued along the ray by the reflected distance). Every view sees that point at
// the same place with the same colour: the photos carry no evidence.
std::vector<SyntheticView> mirror_world_views() {
  const glm::vec3 ball(0.3f, 0.2f, 0.4f);
  const float radius = 0.4f;
  auto hit_ball = [&](const glm::vec3& o, const glm::vec3& d) {  // distance along the unit d, or -1
    const glm::vec3 oc = o - ball;
    const float b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - radius * radius);
    return disc < 0 ? -1.0f : -b - std::sqrt(disc);
  };
  std::vector<SyntheticView> views = ring_views({}, 64);
  for (SyntheticView& v : views) {
    const Camera& c = v.camera;
    const size_t hw = size_t(c.width) * c.height;
    const glm::vec3 eye = c.center();
    for (size_t p = 0; p < hw; ++p) {
      const glm::vec3 d = glm::normalize(c.ray_direction(float(p % c.width) + 0.5f, float(p / c.width) + 0.5f));
      const float t = hit_ball(eye, d);
      glm::vec3 x;
      if (t > 0) {
        x = eye + t * d;
      } else if (v.alpha[p] > 0.5f) {  // the disc: the ball's mirror image behind it, if the reflection meets it
        const glm::vec3 on = eye + (-eye.z / d.z) * d;
        const float t2 = hit_ball(on, glm::vec3(d.x, d.y, -d.z));
        if (!(t2 > 0)) continue;
        x = on + t2 * d;
      } else {
        continue;
      }
      const glm::vec3 colour = 0.8f * plane_texture(4.0f * (t > 0 ? x : glm::vec3(x.x, x.y, -x.z)) + 2.0f);
      for (int ch = 0; ch < 3; ++ch) v.image[ch * hw + p] = colour[ch];
      v.depth[p] = c.to_camera(x).z;
      v.alpha[p] = 1.0f;
    }
  }
  return views;
}

TEST(GlossyDetection, AMirrorWorldIsGlossyWithoutEvidenceInThePhotos) {
  const std::vector<SyntheticView> views = mirror_world_views();
  GlossyDetectionSettings s;
  s.mirror_world = false;
  const GlossyDetection photos_only = detect(views, s);
  EXPECT_FALSE(photos_only.glossy) << "the mirror world is photo-consistent";
  const GlossyDetection det = detect(views);
  ASSERT_TRUE(det.glossy) << det.mirror_world.summary;
  EXPECT_TRUE(det.by_mirror_world);
  EXPECT_GT(det.mirror_world.normal.z, 0.99f) << det.mirror_world.summary;
  EXPECT_NEAR(det.mirror_world.height, 0.0f, 0.05f) << det.mirror_world.summary;
  // The masks cover the disc and the ball's mirror image in it, not the ball.
  size_t disc = 0, disc_marked = 0, ball = 0, ball_marked = 0;
  for (size_t i = 0; i < views.size(); ++i) {
    const Camera& c = views[i].camera;
    for (size_t p = 0; p < views[i].depth.size(); ++p) {
      if (!(views[i].alpha[p] > 0.5f)) continue;
      const glm::vec3 d = c.ray_direction(float(p % c.width) + 0.5f, float(p / c.width) + 0.5f);
      const glm::vec3 x = c.center() + (views[i].depth[p] / glm::dot(d, c.forward())) * d;
      const bool on_ball = x.z > 0.02f;
      (on_ball ? ball : disc) += 1;
      (on_ball ? ball_marked : disc_marked) += det.masks[i][p];
    }
  }
  EXPECT_GT(double(disc_marked), 0.9 * double(disc));
  EXPECT_LT(double(ball_marked), 0.05 * double(ball));
}

TEST(GlossyDetection, AModelThatHasNotDensifiedHasNoMirrorWorld) {
  // The same geometry said to come from a model of a few hundred Gaussians (a run stopped before it
  // densified): its surfaces are blobs that mirror one another by chance, so the search is not run.
  const std::vector<SyntheticView> views = mirror_world_views();
  const int enough = GlossyDetectionSettings{}.mirror_world_min_gaussians;
  const GlossyDetection few = detect(views, {}, enough / 5);
  EXPECT_FALSE(few.glossy);
  EXPECT_FALSE(few.mirror_world.found);
  EXPECT_NE(few.mirror_world.summary.find("not searched"), std::string::npos) << few.mirror_world.summary;
  const GlossyDetection many = detect(views, {}, enough);
  EXPECT_TRUE(many.glossy && many.by_mirror_world) << many.mirror_world.summary;
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

}  // namespace
}  // namespace goris
