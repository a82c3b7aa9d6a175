// The training loop end to end on a tiny synthetic scene rendered by the engine itself (no ../shared):
// re-fitting from a perturbed start (gradients and optimiser work together), bit-exact resume from a
// checkpoint, clean stops, NaN detection naming the parameter group, and bad checkpoint files.
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/io/ply.h"
#include "core/util/error.h"
#include "tests/support/model_values.h"
#include "tests/support/test_scenes.h"
#include "tests/support/test_support.h"
#include "train/loop/checkpoint.h"
#include "train/loop/trainer.h"
#include "train/losses/image_losses.h"
#include "train/radiance/raster_renderer.h"

using namespace goris;

using goris::test::all_values;

namespace {

Camera look_at(glm::vec3 eye, int size, float fov_deg) { return goris::test::look_at(eye, glm::vec3(0.0f), size, fov_deg); }

// A few dozen coloured Gaussians around the origin (SH degree 0).
GaussianModel ground_truth_scene(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  GaussianModel m(Device::CPU);
  m.allocate(size_t(n));
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      m.values(Param::Position)[i * 3 + a] = 0.8f * u(rng);
      m.values(Param::LogScale)[i * 3 + a] = std::log(0.12f + 0.06f * u(rng));
    }
    float* q = m.values(Param::Rotation) + i * 4;
    for (int k = 0; k < 4; ++k) q[k] = u(rng);
    q[0] += 2.0f;
    m.values(Param::OpacityLogit)[i] = 1.0f + u(rng);
    float* sh = m.values(Param::Sh) + i * 48;
    std::fill(sh, sh + 48, 0.0f);
    for (int c = 0; c < 3; ++c) sh[c] = 1.5f * u(rng);
    for (int k = 0; k < extra::kCount; ++k) m.values(Param::ExtraLogit)[i * extra::kCount + k] = 0.0f;
  }
  m.sh_degree = 0;
  m.max_sh_degree = 0;
  return m;
}

TrainConfig refit_config(int iterations) {
  TrainConfig c;
  c.mode = TrainMode::Radiance;
  c.iterations = iterations;
  c.device = DeviceChoice::CPU;
  c.sh.max_degree = 0;
  c.densify.from_iter = 1 << 30;  // pure optimisation: no densification, no opacity reset
  c.densify.until_iter = 0;
  c.densify.opacity_reset_interval = 1 << 30;
  c.anti_aliasing.filter_3d = false;
  c.loss.depth_normal_weight = 0;
  c.bookkeeping.log_interval = 50;
  c.bookkeeping.checkpoint_interval = 0;
  return c;
}

struct Scene {
  std::vector<TrainView> views;
  std::shared_ptr<RasterRenderer> renderer;
};

Scene make_scene(const TrainConfig& config, int size = 48) {
  Scene s;
  s.renderer = std::make_shared<RasterRenderer>(RasterRenderer::settings_for(config), Device::CPU);
  GaussianModel gt = ground_truth_scene(40, 11);
  const glm::vec3 eyes[4] = {{4, 0.5f, 1}, {-0.5f, 4, 1.5f}, {-4, -0.5f, 0.5f}, {0.3f, -4, 2}};
  for (int k = 0; k < 4; ++k) {
    TrainView v;
    v.name = "view" + std::to_string(k);
    v.camera = look_at(eyes[k], size, 50);
    const RenderedImages r = s.renderer->forward(gt.view(false), v.camera);
    v.image.assign(r.color, r.color + 3 * size * size);
    s.views.push_back(std::move(v));
  }
  return s;
}

GaussianModel perturbed(std::uint64_t seed) {
  GaussianModel m = ground_truth_scene(40, 11);
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> n(0, 1);
  for (size_t i = 0; i < m.count(); ++i) {
    for (int a = 0; a < 3; ++a) {
      m.values(Param::Position)[i * 3 + a] += 0.08f * n(rng);
      m.values(Param::LogScale)[i * 3 + a] += 0.3f * n(rng);
      m.values(Param::Sh)[i * 48 + a] += 0.6f * n(rng);
    }
    m.values(Param::OpacityLogit)[i] += 1.0f * n(rng);
  }
  return m;
}

double mean_psnr(Trainer& t) {
  double sum = 0;
  for (const TrainView& v : t.views()) {
    auto r = std::make_shared<RasterRenderer>(RasterRenderer::settings_for(t.config()), Device::CPU);
    const RenderedImages img = r->forward(t.model().view(false), v.camera);
    sum += psnr_from_mse(mse<float>(img.color, v.image.data(), v.image.size()));
  }
  return sum / double(t.views().size());
}

}  // namespace

TEST(Trainer, RefitsAPerturbedSceneTo35Db) {
  const TrainConfig config = refit_config(1500);
  Scene s = make_scene(config);
  Trainer t(config, s.views, 4.0f, s.renderer, Trainer::initial_state(config, perturbed(5)));
  const double before = mean_psnr(t);
  const auto t0 = std::chrono::steady_clock::now();
  while (!t.finished()) t.step();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double after = mean_psnr(t);
  std::printf("re-fit: %zu Gaussians, 4 views 48x48, %d iterations in %.2f s: PSNR %.2f -> %.2f dB\n",
              t.model().count(), config.iterations, secs, before, after);
  EXPECT_LT(before, 25.0) << "the perturbation should be visible";
  EXPECT_GE(after, 35.0);
  // Radiance runs keep the diffuse channel on the SH colour too (the editor's diffuse viewport, the PLY).
  const test::DiffuseVsSh d = test::diffuse_vs_sh_colour(t.model());
  EXPECT_LT(d.max_error, 1e-5);
  EXPECT_GT(d.mean_from_grey, 0.02);
}

TEST(Trainer, ResumeFromCheckpointIsBitExact) {
  TrainConfig config = refit_config(80);
  // Densification and opacity resets inside the run, so their state is part of what must survive.
  config.densify.from_iter = 10;
  config.densify.interval = 10;
  config.densify.until_iter = 40;
  config.densify.opacity_reset_interval = 20;
  config.densify.min_opacity = 0.005f;  // reset Gaussians have 10 iterations to recover
  config.densify.grad_threshold = 1e-5f;
  config.sh.max_degree = 2;
  config.sh.degree_interval = 25;
  config.anti_aliasing.filter_3d = true;
  Scene s = make_scene(config, 32);
  Trainer straight(config, s.views, 4.0f, s.renderer, Trainer::initial_state(config, perturbed(6)));
  while (!straight.finished()) straight.step();

  Trainer first(config, s.views, 4.0f, s.renderer, Trainer::initial_state(config, perturbed(6)));
  for (int i = 0; i < 35; ++i) first.step();
  const auto dir = test::scratch_dir("trainer_resume");
  first.save_checkpoint(dir / "a.ckpt");
  Checkpoint ck = read_checkpoint(dir / "a.ckpt", Device::CPU);
  EXPECT_EQ(ck.state.iteration, 35);
  EXPECT_EQ(all_values(ck.state.model), all_values(first.model())) << "write/read round trip";
  EXPECT_EQ(ck.state.view_stack, first.state().view_stack);
  Trainer resumed(ck.config, s.views, 4.0f, s.renderer, std::move(ck.state));
  while (!resumed.finished()) resumed.step();

  ASSERT_EQ(resumed.model().count(), straight.model().count());
  EXPECT_GT(straight.model().count(), 40u) << "densification should have added Gaussians";
  EXPECT_EQ(resumed.model().sh_degree, 2);
  EXPECT_EQ(all_values(resumed.model()), all_values(straight.model()));
  EXPECT_EQ(resumed.model().filter3d_var.to_host(), straight.model().filter3d_var.to_host());
  EXPECT_EQ(resumed.state().adam.steps, straight.state().adam.steps);
}

TEST(Trainer, StopFlagWritesACheckpointAndLog) {
  TrainConfig config = refit_config(1000);
  config.bookkeeping.log_interval = 5;
  Scene s = make_scene(config, 32);
  Trainer t(config, s.views, 4.0f, s.renderer, Trainer::initial_state(config, perturbed(7)));
  std::atomic<bool> stop{false};
  const auto dir = test::scratch_dir("trainer_stop");
  Trainer::RunOptions o;
  o.run_dir = dir;
  o.stop = &stop;
  int calls = 0;
  o.progress_every = 1;
  o.on_progress = [&](const TrainProgress& p) {
    ++calls;
    EXPECT_EQ(p.total, 1000);
    EXPECT_EQ(p.gaussians, 40u);
    if (p.iteration == 12) stop = true;
  };
  EXPECT_EQ(t.run(o), Trainer::RunResult::Stopped);
  EXPECT_EQ(t.state().iteration, 12);
  const auto latest = latest_checkpoint(dir);
  ASSERT_TRUE(latest.has_value());
  EXPECT_EQ(latest->filename().string(), "iter_00000012.ckpt");
  EXPECT_EQ(read_checkpoint(*latest, Device::CPU).state.iteration, 12);
  std::ifstream log(dir / "log.csv");
  std::string header, line, last;
  std::getline(log, header);
  EXPECT_EQ(header, "iteration,loss,psnr,gaussians,elapsed_s,it_per_s");
  int lines = 0;
  while (std::getline(log, line)) {
    ++lines;
    last = line;
  }
  EXPECT_EQ(lines, 2);  // iterations 5 and 10
  EXPECT_EQ(last.rfind("10,", 0), 0u);
  EXPECT_GE(calls, 12);
}

TEST(Trainer, NonFiniteParameterNamesItsGroup) {
  const TrainConfig config = refit_config(10);
  Scene s = make_scene(config, 32);
  GaussianModel m = perturbed(8);
  // Behind every camera (culled), so only the parameter check can see it.
  m.values(Param::Position)[0] = 0;
  m.values(Param::Position)[1] = 0;
  m.values(Param::Position)[2] = 200;
  m.values(Param::LogScale)[3 * 0 + 1] = NAN;
  Trainer t(config, s.views, 4.0f, s.renderer, Trainer::initial_state(config, std::move(m)));
  try {
    t.step();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("iteration 1"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'scale'"), std::string::npos) << msg;
  }
}

// A renderer that breaks one chosen iteration: NaN in the image (a loss term becomes NaN) or in one
// Gaussian's position gradient (the loss is fine, a gradient is not).
class BreakingRenderer final : public DifferentiableRenderer {
 public:
  enum class Break { Image, Gradient };
  BreakingRenderer(std::shared_ptr<DifferentiableRenderer> inner, Break what, std::set<int> at)
      : inner_(std::move(inner)), what_(what), at_(std::move(at)) {}
  Device device() const override { return inner_->device(); }
  void begin_iteration(int it) override { it_ = it; }
  RenderedImages forward(const GaussianView& g, const Camera& c) override {
    RenderedImages r = inner_->forward(g, c);
    if (what_ == Break::Image && at_.count(it_)) {
      broken_.assign(r.color, r.color + 3 * size_t(r.width) * r.height);
      broken_[5] = std::numeric_limits<float>::quiet_NaN();
      r.color = broken_.data();
    }
    return r;
  }
  void backward(const GaussianView& g, const ImageGradients& d, const GaussianGradView& grads) override {
    inner_->backward(g, d, grads);
    if (what_ == Break::Gradient && at_.count(it_)) grads.positions[4] = std::numeric_limits<float>::infinity();
  }

 private:
  std::shared_ptr<DifferentiableRenderer> inner_;
  Break what_;
  std::set<int> at_;
  int it_ = 0;
  std::vector<float> broken_;
};

TEST(Trainer, NonFiniteLossIsSkippedNamingTheTermAndLowersTheLearningRates) {
  const TrainConfig config = refit_config(6);
  Scene s = make_scene(config, 32);
  auto r = std::make_shared<BreakingRenderer>(s.renderer, BreakingRenderer::Break::Image, std::set<int>{3});
  Trainer t(config, s.views, 4.0f, r, Trainer::initial_state(config, perturbed(8)));
  t.step();
  t.step();
  const std::vector<float> before = all_values(t.model());
  const StepStats bad = t.step();
  ASSERT_TRUE(bad.skipped);
  EXPECT_NE(bad.problem.find("iteration 3"), std::string::npos) << bad.problem;
  EXPECT_NE(bad.problem.find("term l1=nan"), std::string::npos) << bad.problem;
  EXPECT_NE(bad.problem.find("view"), std::string::npos) << bad.problem;
  EXPECT_EQ(all_values(t.model()), before) << "a skipped step must not update anything";
  EXPECT_EQ(t.state().iteration, 3);
  EXPECT_DOUBLE_EQ(t.state().lr_scale, 0.5);
  EXPECT_EQ(t.state().skipped_steps, 1);
  const StepStats next = t.step();
  EXPECT_FALSE(next.skipped);
  EXPECT_NE(all_values(t.model()), before);
}

TEST(Trainer, NonFiniteGradientIsSkippedNamingTheGroupOrStopsOnRequest) {
  TrainConfig config = refit_config(6);
  Scene s = make_scene(config, 32);
  auto r = std::make_shared<BreakingRenderer>(s.renderer, BreakingRenderer::Break::Gradient, std::set<int>{2});
  {
    Trainer t(config, s.views, 4.0f, r, Trainer::initial_state(config, perturbed(8)));
    t.step();
    const StepStats bad = t.step();
    ASSERT_TRUE(bad.skipped);
    EXPECT_NE(bad.problem.find("'position' (Gaussian 1)"), std::string::npos) << bad.problem;
    EXPECT_NE(bad.problem.find("l1="), std::string::npos) << "the loss terms are listed: " << bad.problem;
  }
  config.nan.policy = NanPolicy::Stop;
  Trainer t(config, s.views, 4.0f, r, Trainer::initial_state(config, perturbed(8)));
  t.step();
  try {
    t.step();
    FAIL() << "nan_policy stop must stop";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("iteration 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'position'"), std::string::npos) << e.what();
  }
}

TEST(Trainer, PersistentNonFiniteStepsStopAfterTheLimitAndTheScaleSurvivesACheckpoint) {
  TrainConfig config = refit_config(20);
  config.nan.max_skips = 3;
  Scene s = make_scene(config, 32);
  auto r = std::make_shared<BreakingRenderer>(s.renderer, BreakingRenderer::Break::Image, std::set<int>{2, 3, 4, 5, 6});
  Trainer t(config, s.views, 4.0f, r, Trainer::initial_state(config, perturbed(8)));
  t.step();
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(t.step().skipped);
  const auto dir = goris::test::scratch_dir("trainer_nan_checkpoint");
  t.save_checkpoint(dir / "c.ckpt");
  EXPECT_DOUBLE_EQ(read_checkpoint(dir / "c.ckpt", Device::CPU).state.lr_scale, 0.125);
  EXPECT_THROW(t.step(), Error);  // the 4th in a row
}

TEST(Checkpoint, BadFilesAreRejectedWithTheirName) {
  const auto dir = test::scratch_dir("trainer_bad_ckpt");
  EXPECT_THROW(read_checkpoint(dir / "missing.ckpt", Device::CPU), Error);
  {
    std::ofstream f(dir / "foreign.ckpt", std::ios::binary);
    f << "hello, this is not a checkpoint at all";
  }
  try {
    read_checkpoint(dir / "foreign.ckpt", Device::CPU);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("foreign.ckpt"), std::string::npos);
  }
  const TrainConfig config = refit_config(3);
  TrainerState st = Trainer::initial_state(config, perturbed(9));
  write_checkpoint(dir / "good.ckpt", config, st);
  std::string bytes;
  {
    std::ifstream f(dir / "good.ckpt", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(f), {});
  }
  bytes[bytes.size() / 2] ^= 0x40;
  {
    std::ofstream f(dir / "flipped.ckpt", std::ios::binary);
    f.write(bytes.data(), std::streamsize(bytes.size()));
  }
  EXPECT_THROW(read_checkpoint(dir / "flipped.ckpt", Device::CPU), Error);
  {
    std::ofstream f(dir / "short.ckpt", std::ios::binary);
    f.write(bytes.data(), std::streamsize(bytes.size() / 3));
  }
  EXPECT_THROW(read_checkpoint(dir / "short.ckpt", Device::CPU), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "good.ckpt.tmp"));
  EXPECT_NO_THROW(read_checkpoint(dir / "good.ckpt", Device::CPU));
}

TEST(TrainConfig, JsonRoundTripAndValidation) {
  TrainConfig c;
  c.iterations = 1234;
  c.input.background = glm::vec3(1, 0.5f, 0);
  c.densify.grad_threshold = 3e-4f;
  c.lr.label = 0.5f;
  c.device = DeviceChoice::CPU;
  const nlohmann::json j = c;
  TrainConfig back;
  from_json(j, back);
  EXPECT_EQ(nlohmann::json(back), j);
  EXPECT_EQ(back.input.background, c.input.background);
  nlohmann::json bad = j;
  bad["iteratoins"] = 5;
  EXPECT_THROW(from_json(bad, back), Error);
  bad = j;
  bad["iterations"] = "many";
  EXPECT_THROW(from_json(bad, back), Error);
  EXPECT_EQ(j.at("mode"), "auto");
  bad = j;
  bad["mode"] = "intrinsic-but-not-yet";
  test::expect_error([&] { from_json(bad, back); },
                     "'mode' must be radiance, intrinsic or auto, got \"intrinsic-but-not-yet\"");
  EXPECT_EQ(j.at("device"), "cpu");  // the enumeration is written by name, as the files always had it
  bad = j;
  bad["device"] = "gpu";
  test::expect_error([&] { from_json(bad, back); }, "'device' must be auto, cpu or cuda, got \"gpu\"");
  TrainConfig invalid;
  invalid.input.downscale = 0.5f;
  EXPECT_THROW(invalid.validate("cfg"), Error);
  invalid = TrainConfig{};
  invalid.intrinsic.init_roughness = 1.0f;  // sigmoid-activated: the logit would be infinite
  EXPECT_THROW(invalid.validate("cfg"), Error);
  EXPECT_NO_THROW(TrainConfig{}.validate("cfg"));
}

// A run folder from a version that still had a removed setting loads when the setting was off there; one
// trained with it on is refused by name, and --set names it as removed rather than unknown.
TEST(TrainConfig, RemovedSettingsLoadWhenOffAndAreRefusedWhenOn) {
  nlohmann::json j = TrainConfig{};
  j.erase("config_version");  // written before config.json had a version (train/config/config_migration.h)
  j["intrinsic_net_residual"] = false;
  j["intrinsic_region_rough"] = 0;
  j["intrinsic_roughness_follows_region"] = 0.0;
  j["densify_stop"] = "fixed";
  j["densify_holdout_every"] = 4;  // acted only through densify_stop=adaptive: any value loads
  TrainConfig back;
  EXPECT_NO_THROW(from_json(j, back));
  EXPECT_EQ(nlohmann::json(back), nlohmann::json(TrainConfig{}));  // and writes no removed key back
  auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  j["intrinsic_region_rough"] = 0.3;
  const std::string on = message([&] { from_json(j, back); });
  EXPECT_NE(on.find("'intrinsic_region_rough' = 0.3"), std::string::npos) << on;
  EXPECT_NE(on.find("no longer has"), std::string::npos) << on;
  j["intrinsic_region_rough"] = 0;
  j["densify_stop"] = "adaptive";
  const std::string adaptive = message([&] { from_json(j, back); });
  EXPECT_NE(adaptive.find("'densify_stop' = \"adaptive\""), std::string::npos) << adaptive;
  TrainConfig c;
  const std::string set = message([&] { apply_config_overrides({"intrinsic_ray_offset_normal=true"}, c); });
  EXPECT_NE(set.find("was removed"), std::string::npos) << set;
  const std::string typo = message([&] { apply_config_overrides({"intrinsic_ray_offset_nromal=true"}, c); });
  EXPECT_NE(typo.find("unknown setting"), std::string::npos) << typo;
}

TEST(PlyExport, BakedThreeDFilterRendersLikeTheFilteredModel) {
  // Viewers without Mip-Splatting's 3D filter must see what the engine renders with it.
  TrainConfig config = refit_config(1);
  Scene s = make_scene(config, 40);
  GaussianModel m = ground_truth_scene(40, 11);
  std::vector<Camera> cams;
  for (const TrainView& v : s.views) cams.push_back(v.camera);
  // A strong filter (as from low-resolution cameras) so the difference is visible if baking were wrong.
  m.filter3d_var = Buffer<float>(std::vector<float>(m.count(), 0.01f), Device::CPU);
  GaussianModel baked = GaussianModel::from_ply(m.to_ply(true), Device::CPU);
  GaussianModel unbaked = GaussianModel::from_ply(m.to_ply(false), Device::CPU);
  EXPECT_EQ(baked.filter3d_var.size(), 0u);
  const Camera& cam = s.views[0].camera;
  const RenderedImages a = s.renderer->forward(m.view(false), cam);
  const std::vector<float> with_filter(a.color, a.color + 3 * 40 * 40);
  const RenderedImages b = s.renderer->forward(baked.view(false), cam);
  const std::vector<float> from_baked(b.color, b.color + 3 * 40 * 40);
  const RenderedImages c = s.renderer->forward(unbaked.view(false), cam);
  const std::vector<float> from_unbaked(c.color, c.color + 3 * 40 * 40);
  EXPECT_GT(psnr_from_mse(mse<float>(from_baked.data(), with_filter.data(), with_filter.size())), 60.0);
  EXPECT_LT(psnr_from_mse(mse<float>(from_unbaked.data(), with_filter.data(), with_filter.size())), 40.0);
}

TEST(Trainer, DepthNormalConsistencyTrainsWithoutHarm) {
  // The RaDe-GS regulariser switched on from the start: finite, positive, and the re-fit still converges.
  TrainConfig config = refit_config(400);
  config.loss.depth_normal_from = 0;
  config.loss.depth_normal_weight = 0.05f;
  Scene s = make_scene(config, 32);
  Trainer t(config, s.views, 4.0f, s.renderer, Trainer::initial_state(config, perturbed(10)));
  double first = 0, last = 0;
  while (!t.finished()) {
    const StepStats st = t.step();
    ASSERT_TRUE(std::isfinite(st.depth_normal));
    if (t.state().iteration <= 4) first += st.depth_normal;
    if (t.state().iteration > 396) last += st.depth_normal;
  }
  EXPECT_GT(first, 0.0);
  EXPECT_LT(last, first) << "the consistency term should not grow while training";
  EXPECT_GT(mean_psnr(t), 30.0);
}

TEST(Trainer, AlphaLossMakesABlackSceneOverBlackOpaque) {
  // Black Gaussians over a black background: the colour says nothing about their opacity, so a half
  // transparent start stays so; the images' alpha (alpha_weight) makes it opaque again.
  auto run = [](float alpha_weight) {
    TrainConfig config = refit_config(150);
    config.loss.alpha_weight = alpha_weight;
    Scene s = make_scene(config, 32);
    GaussianModel gt = ground_truth_scene(40, 11);
    for (size_t i = 0; i < gt.count(); ++i)
      for (int c = 0; c < 3; ++c) gt.values(Param::Sh)[i * 48 + c] = -0.5f / 0.28209479177387814f;
    for (TrainView& v : s.views) {
      const RenderedImages r = s.renderer->forward(gt.view(false), v.camera);
      v.image.assign(r.color, r.color + v.image.size());
      v.alpha.assign(r.alpha, r.alpha + v.image.size() / 3);
    }
    GaussianModel start = gt.copy_to(Device::CPU);
    for (size_t i = 0; i < start.count(); ++i) start.values(Param::OpacityLogit)[i] = -2.0f;
    Trainer t(config, s.views, 4.0f, s.renderer, Trainer::initial_state(config, std::move(start)));
    auto alpha_error = [&] {
      double sum = 0;
      for (const TrainView& v : t.views()) {
        const RenderedImages r = s.renderer->forward(t.model().view(false), v.camera);
        sum += l1_loss<float>(r.alpha, v.alpha.data(), v.alpha.size());
      }
      return sum / double(t.views().size());
    };
    const double before = alpha_error();
    double logged = 0;
    while (!t.finished()) logged = t.step().alpha;
    if (alpha_weight > 0) EXPECT_GT(logged, 0.0) << "the step reports its alpha term";
    return std::make_pair(before, alpha_error());
  };
  const auto [before, without] = run(0.0f);
  const auto [before2, with] = run(0.5f);
  std::printf("alpha L1: %.4f at the start, %.4f without the alpha loss, %.4f with it\n", before, without, with);
  EXPECT_GT(before, 0.05);
  EXPECT_EQ(before, before2);
  EXPECT_GT(without, 0.8 * before) << "the colour alone should not fix the opacity here";
  EXPECT_LT(with, 0.3 * before);
}

TEST(Trainer, DepthDistortionStartsOnScheduleAndTrainsWithoutHarm) {
  // 2DGS's depth distortion from its scaled start (3000 of 30K -> 40 of 400): 0 before, finite and
  // positive after; the re-fit still converges and the term falls.
  TrainConfig config = refit_config(400);
  config.loss.depth_distortion_weight = 100.0f;
  ASSERT_EQ(config.scaled_iteration(config.loss.depth_distortion_from), 40);
  Scene s = make_scene(config, 32);
  Trainer t(config, s.views, 4.0f, s.renderer, Trainer::initial_state(config, perturbed(10)));
  double first = 0, last = 0;
  while (!t.finished()) {
    const StepStats st = t.step();
    const int it = t.state().iteration;
    ASSERT_TRUE(std::isfinite(st.distortion));
    if (it <= 40) ASSERT_EQ(st.distortion, 0.0) << it;
    if (it > 40 && it <= 60) first += st.distortion;
    if (it > 380) last += st.distortion;
  }
  EXPECT_GT(first, 0.0);
  EXPECT_LT(last, first);
  EXPECT_GT(mean_psnr(t), 30.0);

  // depth_distortion_glossy = 0 leaves glossy-mask pixels alone: with every pixel glossy the term is 0;
  // with the left half glossy it is less than the whole image's.
  auto distortion_after_start = [&](float glossy_weight, float glossy_left, float glossy_right) {
    TrainConfig c = config;
    c.loss.depth_distortion_glossy = glossy_weight;
    Scene sc = make_scene(c, 32);
    for (TrainView& v : sc.views) {
      const int w = v.camera.width;
      v.glossy_mask.resize(std::size_t(w) * std::size_t(v.camera.height));
      for (std::size_t p = 0; p < v.glossy_mask.size(); ++p)
        v.glossy_mask[p] = int(p % std::size_t(w)) < w / 2 ? glossy_left : glossy_right;
    }
    Trainer tr(c, sc.views, 4.0f, sc.renderer, Trainer::initial_state(c, perturbed(10)));
    double sum = 0;
    for (int i = 0; i < 50; ++i) sum += tr.step().distortion;
    return sum;
  };
  EXPECT_EQ(distortion_after_start(0.0f, 1.0f, 1.0f), 0.0);
  const double half = distortion_after_start(0.0f, 1.0f, 0.0f), whole = distortion_after_start(1.0f, 1.0f, 0.0f);
  EXPECT_GT(half, 0.0);
  EXPECT_LT(half, whole);
  config.loss.depth_distortion_glossy = 1.5f;
  EXPECT_THROW(config.validate("test"), Error);
  config.loss.depth_distortion_glossy = 1.0f;
  config.loss.depth_distortion_weight = -1.0f;
  EXPECT_THROW(config.validate("test"), Error);
  config.loss.depth_distortion_weight = 100.0f;
  config.loss.depth_distortion_until = config.loss.depth_distortion_from;  // must end after it starts
  EXPECT_THROW(config.validate("test"), Error);
  config.loss.depth_distortion_until = -1;
  EXPECT_THROW(config.validate("test"), Error);
}

TEST(Trainer, DepthDistortionStopsAtItsScaledEnd) {
  // depth_distortion_until = 15000 of 30K -> 200 of 400: on in (40, 200], 0 after.
  TrainConfig config = refit_config(400);
  config.loss.depth_distortion_weight = 100.0f;
  config.loss.depth_distortion_until = 15000;
  ASSERT_NO_THROW(config.validate("test"));
  ASSERT_EQ(config.scaled_iteration(config.loss.depth_distortion_until), 200);
  Scene s = make_scene(config, 32);
  Trainer t(config, s.views, 4.0f, s.renderer, Trainer::initial_state(config, perturbed(10)));
  double during = 0;
  for (int i = 0; i < 240; ++i) {
    const StepStats st = t.step();
    const int it = t.state().iteration;
    if (it <= 40 || it > 200) ASSERT_EQ(st.distortion, 0.0) << it;
    else during += st.distortion;
  }
  EXPECT_GT(during, 0.0);
}

TEST(Trainer, DensificationScheduleFitsShortRuns) {
  // until_iter beyond the run: density control stops at densify_until_fraction of the run (here half of
  // it), and a reset only happens when a pruning step follows it inside that window.
  TrainConfig config = refit_config(100);
  config.densify.until_fraction = 0.5f;
  config.densify.from_iter = 10;
  config.densify.interval = 10;
  config.densify.until_iter = 100;
  config.densify.opacity_reset_interval = 60;  // of the full window of 100: every 30 in this one of 50
  config.densify.min_opacity = 0.005f;
  Scene s = make_scene(config, 24);
  Trainer t(config, s.views, 4.0f, s.renderer, Trainer::initial_state(config, perturbed(11)));
  EXPECT_EQ(t.densify_until(), 50);
  EXPECT_EQ(config.opacity_reset_every(), 30);
  std::vector<int> densified;
  while (!t.finished()) {
    const StepStats st = t.step();
    if (st.densify.before > 0) densified.push_back(t.state().iteration);
    const float* op = t.model().values(Param::OpacityLogit);
    const float max_logit = *std::max_element(op, op + t.model().count());
    if (t.state().iteration == 30) EXPECT_LE(max_logit, std::log(0.01f / 0.99f) + 1e-5f) << "reset at 30";
    if (t.state().iteration == 60) EXPECT_GT(max_logit, std::log(0.01f / 0.99f) + 0.1f) << "no reset at 60";
  }
  EXPECT_EQ(densified, (std::vector<int>{10, 20, 30, 40, 50}));
}
