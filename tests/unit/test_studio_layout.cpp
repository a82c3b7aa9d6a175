// Small non-GL parts of the editor: the window layout, the channel table, the bounded training history
// and the frame limiter.
#include <cmath>
#include <set>
#include <string>

#include "core/util/duration_text.h"
#include "tests/support/test_support.h"
#include "render/maps/channels.h"
#include "ui/shell/frame_limiter.h"
#include "ui/document/panel_layout.h"
#include "ui/document/training_history.h"

using namespace goris;
using namespace goris::ui;

TEST(StudioLayout, SplitsTheWindow) {
  LayoutInput in;
  in.width = 1280;
  in.height = 800;
  in.menu_height = 20;
  in.status_height = 24;
  in.sidebar_width = 340;
  in.grid_count = 4;
  const StudioLayout l = compute_layout(in);
  EXPECT_FLOAT_EQ(l.sidebar.x, 0);
  EXPECT_FLOAT_EQ(l.sidebar.y, 20);
  EXPECT_FLOAT_EQ(l.sidebar.w, 340);
  EXPECT_FLOAT_EQ(l.sidebar.h, 800 - 20 - 24);
  EXPECT_FLOAT_EQ(l.status.y, 776);
  EXPECT_FLOAT_EQ(l.status.h, 24);
  ASSERT_EQ(l.grid.size(), 4u);
  // Tiles share the width right of the sidebar, sit at the bottom, and the main viewport fills the rest.
  float x = 340;
  for (const Rect& r : l.grid) {
    EXPECT_FLOAT_EQ(r.x, x);
    EXPECT_FLOAT_EQ(r.w, 940.0f / 4);
    EXPECT_FLOAT_EQ(r.y + r.h, 776);
    EXPECT_LE(r.h, 0.34f * 756 + 1e-3f);
    x += r.w;
  }
  EXPECT_FLOAT_EQ(l.main.x, 340);
  EXPECT_FLOAT_EQ(l.main.y, 20);
  EXPECT_FLOAT_EQ(l.main.w, 940);
  EXPECT_FLOAT_EQ(l.main.h + l.grid[0].h, 756);

  in.sidebar = false;
  in.grid_count = 0;
  const StudioLayout bare = compute_layout(in);
  EXPECT_FLOAT_EQ(bare.sidebar.w, 0);
  EXPECT_TRUE(bare.grid.empty());
  EXPECT_FLOAT_EQ(bare.main.w, 1280);
  EXPECT_FLOAT_EQ(bare.main.h, 756);
  EXPECT_TRUE(bare.main.contains(640, 400));
  EXPECT_FALSE(bare.main.contains(640, 10));
}

TEST(StudioLayout, FitsAndCapsImages) {
  const Rect r = fit_aspect({10, 20, 400, 200}, 1.0f);  // a square in a wide box: pillarboxed
  EXPECT_FLOAT_EQ(r.w, 200);
  EXPECT_FLOAT_EQ(r.h, 200);
  EXPECT_FLOAT_EQ(r.x, 110);
  EXPECT_FLOAT_EQ(r.y, 20);
  const Rect t = fit_aspect({0, 0, 100, 300}, 2.0f);  // wide in a tall box: letterboxed
  EXPECT_FLOAT_EQ(t.w, 100);
  EXPECT_FLOAT_EQ(t.h, 50);
  EXPECT_FLOAT_EQ(t.y, 125);
  EXPECT_FLOAT_EQ(fit_aspect({0, 0, 100, 100}, 0.0f).w, 0);
  int w = 0, h = 0;
  capped_size(1024, 512, 256, w, h);
  EXPECT_EQ(w, 256);
  EXPECT_EQ(h, 128);
  capped_size(100, 50, 256, w, h);  // never enlarged
  EXPECT_EQ(w, 100);
  EXPECT_EQ(h, 50);
  capped_size(0, 0, 256, w, h);
  EXPECT_EQ(w, 1);
  EXPECT_EQ(h, 1);
}

TEST(StudioChannels, TableIsComplete) {
  std::set<std::string> ids;
  for (const ChannelInfo& c : all_channels()) {
    EXPECT_TRUE(ids.insert(c.id).second) << c.id;
    EXPECT_EQ(&channel_info(c.channel), &c);
    EXPECT_EQ(channel_from_id(c.id), c.channel);
  }
  EXPECT_EQ(ids.size(), size_t(Channel::InpaintMask) + 1);  // every enumerator listed
  // What each channel needs: a radiance model shows the G-buffer channels only.
  const ChannelContext radiance;
  for (Channel c : {Channel::Final, Channel::Diffuse, Channel::Fresnel, Channel::Roughness, Channel::Normal,
                    Channel::Depth, Channel::Region, Channel::Label, Channel::Alpha})
    EXPECT_EQ(channel_unavailable(c, radiance), nullptr) << channel_info(c).id;
  for (Channel c : {Channel::Glossy, Channel::IndirectLight, Channel::Visibility, Channel::EnvLight,
                    Channel::ScreenRoughness, Channel::TracedIndirect, Channel::TracedVisibility})
    EXPECT_NE(std::string(channel_unavailable(c, radiance)).find("needs an intrinsic run"), std::string::npos);
  EXPECT_NE(std::string(channel_unavailable(Channel::LightingMask, radiance)).find("needs removal"), std::string::npos);
  EXPECT_NE(std::string(channel_unavailable(Channel::InpaintMask, radiance)).find("needs removal"), std::string::npos);
  // An intrinsic run: the intrinsic channels; R_s only with the screen-space filter.
  ChannelContext intrinsic;
  intrinsic.intrinsic = true;
  for (Channel c : {Channel::Glossy, Channel::IndirectLight, Channel::Visibility, Channel::EnvLight})
    EXPECT_EQ(channel_unavailable(c, intrinsic), nullptr) << channel_info(c).id;
  for (Channel c : {Channel::ScreenRoughness, Channel::TracedIndirect, Channel::TracedVisibility})
    EXPECT_NE(std::string(channel_unavailable(c, intrinsic)).find("screen-space filter"), std::string::npos);
  intrinsic.screen_filter = true;
  for (Channel c : {Channel::ScreenRoughness, Channel::TracedIndirect, Channel::TracedVisibility})
    EXPECT_EQ(channel_unavailable(c, intrinsic), nullptr) << channel_info(c).id;
  // After removal the masks show for training cameras only.
  intrinsic.removal_masks = true;
  EXPECT_NE(std::string(channel_unavailable(Channel::LightingMask, intrinsic)).find("training cameras"),
            std::string::npos);
  intrinsic.snapped_training = true;
  EXPECT_EQ(channel_unavailable(Channel::LightingMask, intrinsic), nullptr);
  EXPECT_EQ(channel_unavailable(Channel::InpaintMask, intrinsic), nullptr);
  EXPECT_FALSE(channel_from_id("sparkle").has_value());
  EXPECT_NE(channel_id_list().find("depth"), std::string::npos);
}

TEST(StudioHistory, StaysBoundedAndSpansTheRun) {
  TrainingHistory h(64);
  for (int i = 1; i <= 1000; ++i) h.add({i, float(i), 0, 0, 0});
  EXPECT_LT(h.samples().size(), 64u);
  EXPECT_GT(h.samples().size(), 16u);
  EXPECT_EQ(h.samples().front().iteration, 1);
  EXPECT_GT(h.samples().back().iteration, 1000 - 64);  // recent samples are kept
  for (size_t k = 1; k < h.samples().size(); ++k) EXPECT_GT(h.samples()[k].iteration, h.samples()[k - 1].iteration);
  const std::vector<float> loss = h.series(&ProgressSample::loss);
  ASSERT_EQ(loss.size(), h.samples().size());
  EXPECT_EQ(loss.front(), 1.0f);
  // A run that restarts from an earlier iteration drops what lies ahead of it.
  h.add({500, -1, 0, 0, 0});
  EXPECT_EQ(h.samples().back().iteration, 500);
  EXPECT_EQ(h.samples().back().loss, -1.0f);
  h.clear();
  EXPECT_TRUE(h.samples().empty());
}

TEST(StudioFrameLimiter, SleepsUntilTheNextFrame) {
  using namespace std::chrono;
  FrameLimiter l(50.0);  // 20 ms frames
  const auto t0 = FrameLimiter::clock::now();
  l.begin_frame(t0);
  EXPECT_EQ(duration_cast<milliseconds>(l.end_frame(t0 + milliseconds(5))).count(), 15);
  EXPECT_NEAR(l.work_ms(), 5.0, 1e-6);
  l.begin_frame(t0 + milliseconds(20));
  EXPECT_EQ(l.end_frame(t0 + milliseconds(45)), FrameLimiter::clock::duration::zero());  // a slow frame
  EXPECT_NEAR(l.frame_ms(), 20.0, 1e-6);
  EXPECT_EQ(l.frames(), 2);
  // A lower cap while only background work runs, never above the maximum.
  l.set_target_fps(10.0);
  l.begin_frame(t0 + milliseconds(100));
  EXPECT_EQ(duration_cast<milliseconds>(l.end_frame(t0 + milliseconds(110))).count(), 90);
  l.set_target_fps(500.0);
  EXPECT_EQ(l.target_fps(), 50.0);
}

TEST(StudioText, Durations) {
  EXPECT_EQ(goris::duration_text(0.4), "0s");
  EXPECT_EQ(goris::duration_text(59.6), "1m00s");
  EXPECT_EQ(goris::duration_text(185), "3m05s");
  EXPECT_EQ(goris::duration_text(3725), "1h02m");
  EXPECT_EQ(goris::duration_text(-1), "--");
  EXPECT_EQ(goris::duration_text(1e12), "--");
  EXPECT_EQ(goris::duration_text(std::nan("")), "--");
}
