// The training hooks (train/loop/hooks/): which ones a configuration creates and in what order, the emit
// weights' schedule, and their state in checkpoints (the emit weights' float block, as the format has it).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "tests/support/test_support.h"
#include "train/loop/checkpoint.h"
#include "train/loop/hooks/hooks.h"
#include "train/loop/trainer.h"

using namespace goris;

namespace {

// A renderer that records the emit weights it is given (and renders nothing).
class RecordingRenderer final : public DifferentiableRenderer {
 public:
  explicit RecordingRenderer(bool extras) : extras_(extras) {}
  Device device() const override { return Device::CPU; }
  RenderedImages forward(const GaussianView&, const Camera&) override { return {}; }
  void backward(const GaussianView&, const ImageGradients&, const GaussianGradView&) override {}
  bool wants_extras() const override { return extras_; }
  void set_emit_weights(std::vector<float> weights, bool or_own) override {
    given.push_back(std::move(weights));
    or_region = or_own;
  }
  std::vector<std::vector<float>> given;
  bool or_region = false;

 private:
  bool extras_;
};

std::vector<std::string> names(const TrainHooks& hooks) {
  std::vector<std::string> n;
  for (const auto& h : hooks) n.emplace_back(h->name());
  return n;
}

// The checkpoint's float block of `v`: a uint64 count, then the floats.
std::string float_block(const std::vector<float>& v) {
  const std::uint64_t n = v.size();
  std::string b(reinterpret_cast<const char*>(&n), sizeof n);
  b.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(float));
  return b;
}

GaussianModel small_model(size_t n) {
  GaussianModel m(Device::CPU);
  m.allocate(n);
  for (size_t i = 0; i < n; ++i) m.values(Param::Position)[i * 3 + 2] = float(i);
  return m;
}

}  // namespace

TEST(TrainHooks, TheConfigurationCreatesOnlyTheHooksItNeedsInAFixedOrder) {
  const RecordingRenderer radiance(false), intrinsic_renderer(true);
  TrainConfig c;
  EXPECT_TRUE(make_train_hooks(c, radiance).empty()) << "a default radiance run needs none";
  c.intrinsic.glossy_plane = true;  // intrinsic-mode behaviours stay off in radiance mode
  EXPECT_TRUE(make_train_hooks(c, radiance).empty());

  TrainConfig in;
  in.mode = TrainMode::Intrinsic;
  EXPECT_EQ(names(make_train_hooks(in, intrinsic_renderer)), (std::vector<std::string>{"emit_weights", "mirror_world"}))
      << "the default stage-1 setting: emit = mask and the mirror-world prune";
  in.intrinsic.emit = EmitSource::Region;
  in.intrinsic.prune_mirror_world = 0;
  EXPECT_TRUE(make_train_hooks(in, intrinsic_renderer).empty()) << "the paper's setting";

  in.intrinsic.emit = EmitSource::Max;
  in.intrinsic.prune_mirror_world = 0.05f;
  in.intrinsic.glossy_plane = true;
  in.loss.depth_distortion_weight = 100;
  EXPECT_EQ(names(make_train_hooks(in, intrinsic_renderer)),
            (std::vector<std::string>{"emit_weights", "depth_distortion", "mirror_world", "glossy_plane"}));
  EXPECT_EQ(names(make_train_hooks(in, radiance)), (std::vector<std::string>{"depth_distortion", "mirror_world", "glossy_plane"}))
      << "emit weights only for a renderer that takes the extra channels";
}

// The weights go to the renderer at the first step, then only when refreshed: every kRefreshInterval
// iterations or when the count changed. Restored weights are given again at once, not recomputed.
TEST(TrainHooks, EmitWeightsAreGivenOnceAndRefreshedOnSchedule) {
  TrainConfig c;
  c.mode = TrainMode::Intrinsic;
  c.intrinsic.emit = EmitSource::Max;
  RecordingRenderer r(true);
  GaussianModel m = small_model(3);
  TrainView view;
  view.name = "v";
  const std::vector<TrainView> views{view};
  StepStats out;
  EmitWeightsHook hook;
  for (int it = 1; it <= 2 * EmitWeightsHook::kRefreshInterval; ++it) {
    HookStep s{it, c, m, views, views[0], r, 1.0f, out};
    hook.before_forward(s);
  }
  ASSERT_EQ(r.given.size(), 3u) << "at iteration 1 and at two refreshes";
  EXPECT_TRUE(r.or_region) << "emit = max";
  EXPECT_EQ(r.given[0], std::vector<float>(3, 1.0f)) << "no view with a glossy mask sees them: all emit";

  const std::vector<float> saved{0.5f, 0.25f, 1.0f};
  EmitWeightsHook resumed;
  resumed.deserialize(float_block(saved), "test");
  EXPECT_EQ(resumed.serialize(), float_block(saved));
  RecordingRenderer r2(true);
  HookStep s{7, c, m, views, views[0], r2, 1.0f, out};
  resumed.before_forward(s);
  ASSERT_EQ(r2.given.size(), 1u);
  EXPECT_EQ(r2.given[0], saved) << "the saved weights, not ones of the later model";
  EXPECT_EQ(EmitWeightsHook().serialize(), "") << "nothing to keep before the first step";

  test::expect_error([&] { resumed.deserialize(float_block(saved).substr(0, 10), "bad.ckpt"); }, "bad.ckpt");
}

// A hook's state travels in TrainerState::hooks; the emit weights keep the place the checkpoint format gives
// them, and a state the format has no place for is refused rather than lost.
TEST(TrainHooks, CheckpointsKeepTheEmitWeightsBlockAndRefuseOtherHookState) {
  const auto dir = test::scratch_dir("train_hooks_checkpoint");
  TrainerState st;
  st.model = small_model(2);
  st.stats.reset(2, Device::CPU);
  st.hooks[EmitWeightsHook::kName] = float_block({0.75f, 0.125f});
  write_checkpoint(dir / "a.ckpt", TrainConfig{}, st);
  EXPECT_EQ(read_checkpoint(dir / "a.ckpt", Device::CPU).state.hooks, st.hooks);

  st.hooks.clear();
  write_checkpoint(dir / "none.ckpt", TrainConfig{}, st);
  EXPECT_TRUE(read_checkpoint(dir / "none.ckpt", Device::CPU).state.hooks.empty());

  st.hooks["glossy_plane"] = "x";
  test::expect_error([&] { write_checkpoint(dir / "b.ckpt", TrainConfig{}, st); }, "glossy_plane");
}
