// What the editor's viewports display: model snapshots render exactly like the model, the host frame
// carries every channel with the right layout, picking returns the surface point under a pixel, the render
// worker answers the newest request, and opening data sets and run folders.
#include <chrono>
#include <cmath>
#include <random>
#include <thread>

#include "core/io/ply.h"
#include "train/radiance/raster_renderer.h"
#include "train/run/run_folder.h"
#include "core/util/error.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "render/raster/rasterizer.h"
#include "ui/display/display_renderer.h"
#include "tests/support/test_support.h"
#include "tests/unit/test_studio_scenes.h"
#include "ui/display/display_frame.h"
#include "ui/display/model_snapshot.h"
#include "ui/display/render_worker.h"
#include "ui/document/scene_loader.h"

using namespace goris;
using namespace goris::ui;
namespace fs = std::filesystem;

namespace {

Camera front_camera() { return test::studio_front_camera(); }

// A wall of opaque Gaussians near z = 0 with varied colours and material logits.
GaussianModel wall(int n = 200) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  GaussianModel m(Device::CPU);
  m.allocate(size_t(n));
  for (int i = 0; i < n; ++i) {
    const glm::vec3 position(1.2f * u(rng), 1.0f * u(rng), 0.05f * u(rng));
    const glm::vec3 dc(u(rng), u(rng), u(rng));
    test::set_studio_gaussian(m, i, position, glm::vec3(0.25f, 0.25f, 0.02f), dc);
    for (int k = 0; k < extra::kCount; ++k) m.values(Param::ExtraLogit)[i * extra::kCount + k] = 2.0f * u(rng);
  }
  return m;
}

}  // namespace

TEST(StudioDisplay, SnapshotRendersLikeTheModel) {
  GaussianModel m = wall();
  m.sh_degree = 0;
  RasterSettings rs = RasterSettings::mip_splatting();
  rs.background = glm::vec3(0.2f, 0.3f, 0.4f);
  const ModelSnapshot snap(m, 7, rs);
  EXPECT_EQ(snap.count(), m.count());
  EXPECT_EQ(snap.iteration(), 7);
  EXPECT_EQ(snap.settings().background, rs.background);
  const Camera cam = front_camera();
  const RasterOutput a = rasterize(m.view(true), cam, rs, Device::CPU);
  const RasterOutput b = rasterize(snap.view(), cam, snap.settings(), Device::CPU);
  ASSERT_EQ(b.gbuffer.n_extras, extra::kCount);
  EXPECT_EQ(a.gbuffer.color.to_host(), b.gbuffer.color.to_host());
  EXPECT_EQ(a.gbuffer.extras.to_host(), b.gbuffer.extras.to_host());
  // The copy is independent: later training steps do not change it.
  m.values(Param::Sh)[0] += 1.0f;
  const RasterOutput c = rasterize(snap.view(), cam, snap.settings(), Device::CPU);
  EXPECT_EQ(b.gbuffer.color.to_host(), c.gbuffer.color.to_host());
}

TEST(StudioDisplay, SnapshotGivesBackTheModel) {
  GaussianModel m = wall(60);
  m.sh_degree = 1;
  const ModelSnapshot snap(m, 2, RasterSettings{});
  EXPECT_FALSE(snap.intrinsic());
  const GaussianModel back = snap.to_model();
  ASSERT_EQ(back.count(), m.count());
  EXPECT_EQ(back.sh_degree, 1);
  for (Param p : {Param::Position, Param::LogScale, Param::Rotation, Param::OpacityLogit, Param::Sh, Param::ExtraLogit})
    EXPECT_EQ(back.tensor(p).value.to_host(), m.tensor(p).value.to_host()) << param_name(p);
}

// An intrinsic snapshot is shaded with the renderer state it carries; the selection adds its coverage.
TEST(StudioDisplay, RendersIntrinsicMapsAndSelection) {
  GaussianModel m = wall();
  TrainConfig cfg;
  cfg.mode = TrainMode::Intrinsic;
  cfg.intrinsic.env_resolution = 8;
  cfg.iterations = 100;
  const float extent = 4.0f;
  IntrinsicRenderer reference(cfg, extent, Device::CPU);
  reference.set_shading(true);
  auto source = std::make_shared<const ShadingSource>(ShadingSource{cfg, extent});
  auto state = std::make_shared<const std::string>(reference.save_own_state());
  const ModelSnapshot snap(m, 5, RasterRenderer::settings_for(cfg), source, state);
  EXPECT_TRUE(snap.intrinsic());
  const Camera cam = front_camera();

  DisplayRenderer dr;
  const DisplayFrame f = dr.render(snap, cam, nullptr);
  ASSERT_TRUE(f.intrinsic());
  EXPECT_TRUE(f.selection.empty());
  const IntrinsicMaps maps = reference.render_maps(snap.view(), cam);
  const size_t hw = f.pixels(), p = 17 * 48 + 30;
  ASSERT_EQ(maps.color.size(), 3 * hw);
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(f.color[p * 3 + c], maps.color[c * hw + p]);  // the shaded colour, not the SH colour
    EXPECT_FLOAT_EQ(f.glossy[p * 3 + c], maps.glossy[c * hw + p]);
    EXPECT_FLOAT_EQ(f.env[p * 3 + c], maps.env[c * hw + p]);
    EXPECT_FLOAT_EQ(f.indirect[p * 3 + c], maps.indirect[c * hw + p]);
  }
  EXPECT_FLOAT_EQ(f.light[p * 2], maps.visibility[p]);
  EXPECT_EQ(f.screen_roughness, !maps.screen_roughness.empty());
  // With the filter, the traced light before it: L_ind rgb and V per pixel.
  ASSERT_TRUE(f.screen_roughness) << "the test's config has the screen-space filter on";
  ASSERT_EQ(f.traced.size(), 4 * hw);
  {
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(f.traced[p * 4 + c], maps.indirect_traced[c * hw + p]);
    EXPECT_FLOAT_EQ(f.traced[p * 4 + 3], maps.visibility_traced[p]);
  }

  // A later snapshot with a brighter environment: the display reloads it and L_dir follows.
  IntrinsicRenderer brighter(cfg, extent, Device::CPU);
  std::vector<float> env = brighter.environment().params().to_host();
  for (float& v : env) v += 1.0f;  // log radiance: e times brighter
  brighter.environment().params().upload(env.data(), env.size());
  brighter.environment().update();
  const ModelSnapshot later(m, 6, RasterRenderer::settings_for(cfg), source,
                            std::make_shared<const std::string>(brighter.save_own_state()));
  const DisplayFrame g = dr.render(later, cam, nullptr);
  double before = 0, after = 0;
  for (size_t i = 0; i < f.env.size(); ++i) before += f.env[i], after += g.env[i];
  EXPECT_GT(after, 2.0 * before);

  // The selection's coverage: everything selected covers what the alpha covers; nothing selected, nothing.
  auto all = std::make_shared<const SelectionMask>(m.count(), std::uint8_t(1));
  const DisplayFrame s = dr.render(snap, cam, all);
  ASSERT_EQ(s.selection.size(), hw);
  for (size_t q = 0; q < hw; ++q) EXPECT_NEAR(s.selection[q], std::min(1.0f, f.misc[q * 4 + 3]), 1e-4f);
  auto none = std::make_shared<const SelectionMask>(m.count(), std::uint8_t(0));
  const DisplayFrame n = dr.render(snap, cam, none);
  for (float v : n.selection) EXPECT_EQ(v, 0.0f);
  auto wrong = std::make_shared<const SelectionMask>(m.count() + 1, std::uint8_t(1));
  EXPECT_THROW(dr.render(snap, cam, wrong), Error);
}

TEST(StudioDisplay, FrameChannelsAndPicking) {
  GaussianModel m = wall();
  const Camera cam = front_camera();
  const RasterOutput out = rasterize(m.view(true), cam, RasterSettings{}, Device::CPU);
  const DisplayFrame f = make_display_frame(out.gbuffer, cam);
  ASSERT_EQ(f.width, 48);
  ASSERT_EQ(f.height, 40);
  const size_t hw = f.pixels();
  EXPECT_EQ(f.color.size(), hw * 3);
  EXPECT_EQ(f.misc.size(), hw * 4);
  EXPECT_EQ(f.depth.size(), hw);
  const std::vector<float> color = out.gbuffer.color.to_host(), alpha = out.gbuffer.alpha.to_host(),
                           extras = out.gbuffer.extras.to_host(), depth = out.gbuffer.depth.to_host();
  const size_t p = 17 * 48 + 30;  // planar -> interleaved, channel by channel
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(f.color[p * 3 + c], color[c * hw + p]);
    EXPECT_EQ(f.diffuse[p * 3 + c], extras[(extra::kDiffuse + c) * hw + p]);
    EXPECT_EQ(f.fresnel[p * 3 + c], extras[(extra::kFresnel + c) * hw + p]);
  }
  EXPECT_EQ(f.misc[p * 4 + 0], extras[extra::kRoughness * hw + p]);
  EXPECT_EQ(f.misc[p * 4 + 1], extras[extra::kRegion * hw + p]);
  EXPECT_EQ(f.misc[p * 4 + 2], extras[extra::kLabel * hw + p]);
  EXPECT_EQ(f.misc[p * 4 + 3], alpha[p]);
  ASSERT_GT(alpha[p], 0.5f);
  EXPECT_NEAR(f.depth[p], depth[p] / alpha[p], 1e-5f);
  EXPECT_NEAR(f.depth[p], 4.0f, 0.1f);
  EXPECT_NEAR(glm::length(glm::vec3(f.normal[p * 3], f.normal[p * 3 + 1], f.normal[p * 3 + 2])), 1.0f, 1e-4f);
  EXPECT_GT(f.inv_depth_near, f.inv_depth_far);
  EXPECT_NEAR(1.0f / f.inv_depth_near, 4.0f, 0.2f);

  // Picking: the world point under a pixel lies on the wall (z ~ 0) and projects back to the pixel.
  const auto r = pick(f, 30.5f, 17.5f);
  ASSERT_TRUE(r.has_value());
  EXPECT_TRUE(r->hit);
  EXPECT_EQ(r->x, 30);
  EXPECT_EQ(r->y, 17);
  EXPECT_NEAR(r->world.z, 0.0f, 0.1f);
  const glm::vec2 back = cam.project_camera(cam.to_camera(r->world));
  EXPECT_NEAR(back.x, 30.5f, 1e-3f);
  EXPECT_NEAR(back.y, 17.5f, 1e-3f);
  EXPECT_FALSE(pick(f, -1, 3).has_value());
  EXPECT_FALSE(pick(f, 48, 3).has_value());
  // A pixel beside the wall: nothing there.
  Camera aside = cam;
  aside.t = glm::vec3(5, 0, 4);
  const DisplayFrame empty =
      make_display_frame(rasterize(m.view(true), aside, RasterSettings{}, Device::CPU).gbuffer, aside);
  const auto miss = pick(empty, 2.5f, 2.5f);
  ASSERT_TRUE(miss.has_value());
  EXPECT_FALSE(miss->hit);
  EXPECT_EQ(miss->depth, 0.0f);
}

TEST(StudioDisplay, WorkerAnswersTheNewestRequest) {
  GaussianModel m = wall();
  auto snap = std::make_shared<const ModelSnapshot>(m, 3, RasterSettings{});
  RenderWorker w;
  EXPECT_TRUE(w.idle());
  EXPECT_EQ(w.take(), nullptr);
  Camera small = front_camera();
  std::uint64_t last = 0;
  for (int i = 0; i < 5; ++i) {  // a burst: older requests may be dropped, the last one is answered
    small.t.x = 0.01f * float(i);
    last = w.request({snap, small});
  }
  std::shared_ptr<const DisplayFrame> f;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (std::chrono::steady_clock::now() < end) {
    if (auto got = w.take()) f = got;
    if (f && f->id == last && w.idle()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->id, last);
  EXPECT_EQ(f->model_iteration, 3);
  EXPECT_EQ(f->gaussians, m.count());
  EXPECT_EQ(f->camera.t, small.t);
  EXPECT_TRUE(w.error().empty());
  // A camera the rasterizer rejects: an error, no frame.
  Camera bad = small;
  bad.fx = 0;
  w.request({snap, bad});
  while (!w.idle()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_FALSE(w.error().empty());
  EXPECT_EQ(w.take(), nullptr);
}

TEST(StudioDisplay, OpensDataSetsAndRuns) {
  const fs::path data = test::resource_dir() / "default_scene";
  const OpenedScene d = open_scene(data, Device::CPU);
  EXPECT_EQ(d.kind, OpenedScene::Kind::Dataset);
  ASSERT_TRUE(d.dataset.has_value());
  EXPECT_EQ(d.dataset->train.size(), 40u);
  EXPECT_EQ(d.model, nullptr);
  EXPECT_GT(d.up.z, 0.9f);  // NeRF-synthetic scenes are z-up
  EXPECT_GT(d.radius, 0.0f);
  EXPECT_FALSE(is_run_folder(data));

  // A run folder: config.json naming the data set, and the final model.
  const fs::path run = test::scratch_dir("studio_open_run");
  TrainConfig cfg;
  cfg.input.data = fs::absolute(data).string();
  cfg.input.background = glm::vec3(1.0f);
  write_run_config(run, cfg);
  write_ply(run_ply_path(run), wall(50).to_ply());
  const OpenedScene r = open_scene(run, Device::CPU);
  EXPECT_TRUE(is_run_folder(run));
  EXPECT_EQ(r.kind, OpenedScene::Kind::Run);
  ASSERT_NE(r.model, nullptr);
  EXPECT_EQ(r.model->count(), 50u);
  EXPECT_EQ(r.model->settings().background, glm::vec3(1.0f));  // the run's own render settings
  EXPECT_TRUE(r.dataset.has_value());
  EXPECT_TRUE(r.warnings.empty());

  // The run's data set moved away: the model still opens, with a warning, framed by its points.
  cfg.input.data = (run / "gone").string();
  write_run_config(run, cfg);
  const OpenedScene lonely = open_scene(run, Device::CPU);
  EXPECT_FALSE(lonely.dataset.has_value());
  ASSERT_EQ(lonely.warnings.size(), 1u);
  EXPECT_NE(lonely.warnings[0].find("gone"), std::string::npos);
  EXPECT_LT(glm::length(lonely.center), 1.0f);
  EXPECT_GT(lonely.radius, 0.3f);

  try {
    open_scene(run / "nothing_here", Device::CPU);
    FAIL() << "a missing path opened";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing_here: no such file or folder"), std::string::npos) << e.what();
  }
  EXPECT_THROW(open_scene(test::resource_dir() / "default_scene" / "README.md", Device::CPU), Error);
}
