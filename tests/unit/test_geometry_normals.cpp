// The normal prior read off the geometry (render/train/geometry_normals.h): on a glossy table of flat
// Gaussians seen from above, every glossy pixel gets the table's normal - also where a mirror-world copy of
// the object under the half-transparent top is what the depth shows - while the object standing on it gets
// its own (depth) normals; without glossy masks every covered pixel's prior comes from the depth; the maps
// written to a folder read back as the same prior; in a run, the prior is taken once, at the first shading
// iteration, and a resumed run reads the same maps.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include <unistd.h>

#include "core/train/checkpoint.h"
#include "core/train/normal_prior.h"
#include "core/train/run_folder.h"
#include "core/util/error.h"
#include "render/train/geometry_normals.h"
#include "render/train/training_setup.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_selection_scene.h"

namespace goris {
namespace {

constexpr int kSize = 64;
const glm::vec3 kObject(0.0f, 0.0f, 0.35f);
constexpr float kObjectRadius = 0.2f;

bool ray_hits_sphere(glm::vec3 o, glm::vec3 d, glm::vec3 c, float r) {
  const glm::vec3 oc = o - c;
  const float b = glm::dot(oc, d), q = glm::dot(oc, oc) - r * r;
  return b * b - q >= 0 && -b + std::sqrt(b * b - q) > 0;
}

struct Scene {
  std::vector<TrainView> views;
  GaussianModel model;
};

Scene table_scene(float top_opacity) {
  Scene s;
  std::vector<test::TestGaussian> gs;
  for (int i = 0; i < 25; ++i)
    for (int j = 0; j < 25; ++j)
      gs.push_back({{-0.96f + 0.08f * float(i), -0.96f + 0.08f * float(j), 0.0f}, 0.06f, top_opacity});
  const std::size_t table = gs.size();
  // The object: a ball of Gaussians; its mirror-world copy under the table.
  for (float z : {kObject.z, -kObject.z})
    for (int k = 0; k < 60; ++k) {
      const float a = 2.39996f * float(k), h = 1.0f - 2.0f * (float(k) + 0.5f) / 60.0f, r = std::sqrt(1 - h * h);
      gs.push_back({glm::vec3(std::cos(a) * r, std::sin(a) * r, h) * (kObjectRadius * 0.85f) + glm::vec3(0, 0, z), 0.05f});
    }
  s.model = test::make_model(gs);
  float* ls = s.model.values(Param::LogScale);
  for (std::size_t i = 0; i < table; ++i) ls[3 * i + 2] = std::log(0.004f);  // flat, normal +z
  for (glm::vec3 eye : {glm::vec3(2.0f, 1.5f, 2.5f), glm::vec3(-2.0f, 1.5f, 2.5f), glm::vec3(1.5f, -2.0f, 2.5f),
                        glm::vec3(-1.5f, -2.0f, 2.5f)}) {
    TrainView v;
    v.name = "r_" + std::to_string(s.views.size());
    v.camera = test::look_at(eye, {0.0f, 0.0f, 0.0f}, kSize, kSize, 70.0f);
    const Camera& c = v.camera;
    v.glossy_mask.assign(std::size_t(kSize) * kSize, 0.0f);
    const glm::mat3 to_world = glm::transpose(c.R);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const glm::vec3 d = glm::normalize(to_world * glm::vec3((x + 0.5f - c.cx) / c.fx, (y + 0.5f - c.cy) / c.fy, 1.0f));
        const float t = -eye.z / d.z;
        const glm::vec3 hit = eye + t * d;
        if (t > 0 && std::abs(hit.x) < 0.95f && std::abs(hit.y) < 0.95f && !ray_hits_sphere(eye, d, kObject, kObjectRadius))
          v.glossy_mask[std::size_t(y) * kSize + std::size_t(x)] = 1.0f;
      }
    s.views.push_back(std::move(v));
  }
  return s;
}

// The camera-space normal of world +z, facing view v's camera.
glm::vec3 up_in(const Camera& c) {
  glm::vec3 n = c.R * glm::vec3(0, 0, 1);
  return c.center().z > 0 ? n : -n;
}

glm::vec3 at(const std::vector<float>& prior, std::size_t hw, std::size_t p) {
  return {prior[p], prior[hw + p], prior[2 * hw + p]};
}

TEST(GeometryNormals, GlossyPixelsGetThePlaneNormalAndTheObjectItsOwn) {
  for (float top_opacity : {0.9f, 0.1f}) {  // 0.1: the depth shows the mirror world through the top
    const Scene s = table_scene(top_opacity);
    const GeometryNormals g = geometry_normal_priors(s.model, s.views, RasterSettings{}, Device::CPU);
    ASSERT_TRUE(g.plane) << "top opacity " << top_opacity;
    ASSERT_EQ(g.priors.size(), s.views.size());
    std::size_t glossy = 0, on_plane = 0, object = 0, object_off_plane = 0;
    for (std::size_t i = 0; i < s.views.size(); ++i) {
      const Camera& c = s.views[i].camera;
      const std::size_t hw = std::size_t(c.width) * c.height;
      const glm::vec3 up = up_in(c);
      const glm::mat3 to_world = glm::transpose(c.R);
      for (std::size_t p = 0; p < hw; ++p) {
        const glm::vec3 n = at(g.priors[i], hw, p);
        const int x = int(p % std::size_t(c.width)), y = int(p / std::size_t(c.width));
        const glm::vec3 d = glm::normalize(to_world * glm::vec3((x + 0.5f - c.cx) / c.fx, (y + 0.5f - c.cy) / c.fy, 1.0f));
        if (s.views[i].glossy_mask[p] > 0.5f) {
          // Away from the ball's splats (they reach beyond its radius) and from the footprint's margin.
          const glm::vec3 hit = c.center() - c.center().z / d.z * d;
          if (ray_hits_sphere(c.center(), d, kObject, 1.6f * kObjectRadius) || std::abs(hit.x) > 0.85f ||
              std::abs(hit.y) > 0.85f || glm::length(n) < 0.5f)  // (uncovered pixels carry no prior)
            continue;
          ++glossy;
          on_plane += glm::length(n - up) < 1e-3f;
          continue;
        }
        if (!ray_hits_sphere(c.center(), d, kObject, kObjectRadius * 0.7f) || glm::length(n) < 0.5f) continue;
        ++object;
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
        object_off_plane += glm::dot(n, up) < 0.95f;
      }
    }
    EXPECT_GT(glossy, top_opacity < 0.5f ? 200u : 2000u);
    if (top_opacity < 0.5f) EXPECT_GT(g.beyond_pixels, 200u) << "the mirror ball seen through the top";
    EXPECT_GE(double(on_plane), 0.99 * double(glossy)) << "top opacity " << top_opacity;
    EXPECT_GT(object, 100u);
    EXPECT_GE(double(object_off_plane), 0.5 * double(object)) << "the ball is not flat";
  }
}

TEST(GeometryNormals, WithoutGlossyMasksEveryCoveredPixelTakesTheDepthNormal) {
  Scene s = table_scene(0.9f);
  for (TrainView& v : s.views) v.glossy_mask.clear();
  const GeometryNormals g = geometry_normal_priors(s.model, s.views, RasterSettings{}, Device::CPU);
  EXPECT_FALSE(g.plane);
  EXPECT_EQ(g.plane_pixels, 0u);
  EXPECT_GT(g.depth_pixels, 0.9 * double(g.covered));
  // The flat table's depth normal is its normal away from the ball and the table's edge.
  const Camera& c = s.views[0].camera;
  const std::size_t hw = std::size_t(c.width) * c.height;
  std::size_t flat = 0, up = 0;
  for (std::size_t p = 0; p < hw; ++p) {
    const glm::vec3 n = at(g.priors[0], hw, p);
    if (glm::length(n) < 0.5f) continue;
    ++flat;
    up += glm::dot(n, up_in(c)) > 0.98f;
  }
  EXPECT_GT(double(up), 0.6 * double(flat));
}

TEST(GeometryNormals, TheWrittenMapsReadBackAsTheSamePrior) {
  Scene s = table_scene(0.9f);
  const GeometryNormals g = geometry_normal_priors(s.model, s.views, RasterSettings{}, Device::CPU);
  const auto dir = std::filesystem::temp_directory_path() / ("goris_geometry_normals_" + std::to_string(::getpid()));
  save_normal_prior_folder(dir, s.views, g.priors);
  load_normal_priors(dir, s.views);
  std::filesystem::remove_all(dir);
  for (std::size_t i = 0; i < s.views.size(); ++i) {
    const std::size_t hw = std::size_t(kSize) * kSize;
    ASSERT_EQ(s.views[i].normal_prior.size(), 3 * hw);
    for (std::size_t p = 0; p < hw; ++p) {
      const glm::vec3 a = at(g.priors[i], hw, p), b = at(s.views[i].normal_prior, hw, p);
      if (glm::length(a) < 0.5f) {
        EXPECT_LT(glm::length(b), 1e-3f) << "view " << i << " pixel " << p << ": no prior must stay none";
      } else {
        EXPECT_LT(glm::length(a - b), 2e-4f) << "view " << i << " pixel " << p;
      }
    }
  }
  EXPECT_THROW(save_normal_prior_folder(dir, s.views, {}), Error);
}

TEST(GeometryNormals, ARunTakesThePriorOnceWhenShadingStartsAndResumesWithIt) {
  namespace fs = std::filesystem;
  const fs::path run = test::scratch_dir("geometry_normals_run");
  TrainConfig c;
  c.mode = "intrinsic";
  c.data = (test::resource_dir() / "default_scene").string();
  c.device = "cpu";
  c.resolution = 32;
  c.iterations = 30;
  c.random_init_points = 3000;
  c.intrinsic.env_resolution = 8;
  c.intrinsic.net_hidden_layers = 1;
  c.intrinsic.geometry_normals = true;
  c.checkpoint_interval = 0;
  PreparedTraining p = prepare_training(run, c, std::nullopt);
  Trainer& t = *p.trainer;
  const int from = t.config().shading_from();
  ASSERT_GT(from, 0);
  ASSERT_LT(from, c.iterations);
  while (t.state().iteration < from) {
    EXPECT_FALSE(apply_geometry_normals(t, run).has_value()) << "iteration " << t.state().iteration;
    t.step();
  }
  for (const TrainView& v : t.views()) EXPECT_TRUE(v.normal_prior.empty());
  const std::optional<std::string> note = apply_geometry_normals(t, run);
  ASSERT_TRUE(note.has_value());
  EXPECT_NE(note->find("geometry_normals"), std::string::npos) << *note;
  EXPECT_EQ(fs::path(t.config().intrinsic.normals), run / "geometry_normals");
  EXPECT_EQ(fs::path(read_run_config(run).intrinsic.normals), run / "geometry_normals");
  EXPECT_FALSE(apply_geometry_normals(t, run).has_value()) << "taken twice";
  std::size_t with_prior = 0;
  for (const TrainView& v : t.views()) {
    ASSERT_EQ(v.normal_prior.size(), 3 * std::size_t(v.camera.width) * v.camera.height);
    EXPECT_TRUE(fs::exists(run / "geometry_normals" / ("normal_" + v.name + ".png")));
    for (float x : v.normal_prior) with_prior += x != 0.0f;
  }
  EXPECT_GT(with_prior, 0u);
  t.step();
  t.save_checkpoint(checkpoint_path(run, t.state().iteration));

  // Resumed: the checkpoint's configuration names the maps, and the views read the same prior.
  std::optional<ResumePoint> r = read_latest_checkpoint(run);
  ASSERT_TRUE(r.has_value());
  TrainConfig rc = r->checkpoint.config;
  EXPECT_EQ(fs::path(rc.intrinsic.normals), run / "geometry_normals");
  PreparedTraining p2 = prepare_training(run, rc, std::move(r));
  EXPECT_FALSE(apply_geometry_normals(*p2.trainer, run).has_value());
  for (std::size_t i = 0; i < t.views().size(); ++i) EXPECT_EQ(p2.trainer->views()[i].normal_prior, t.views()[i].normal_prior);
}

}  // namespace
}  // namespace goris
