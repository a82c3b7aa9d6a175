// Stage 2 end to end on the embedded scene (short schedule), through the library calls `goris train` and
// `goris remove` make: an intrinsic stage 1, removal from the learned labels, and the check that matters
// for the paper's claim - the target's reflection goes away with it. The glossy term G (traced reflections)
// of the training views is rendered before and after removal: inside the lighting-aware masks (the target's
// reflections) it changes much more than on the rest of the glossy surface.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/io/dataset.h"
#include "core/io/image.h"
#include "removal/selection/selection_file.h"
#include "removal/selection/selection_labels.h"
#include "core/scene/selection_points.h"
#include "train/run/run_folder.h"
#include "train/run/train_setup.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "removal/pipeline/removal_pipeline.h"
#include "removal/selection/selection_masks.h"
#include "train/radiance/raster_renderer.h"
#include "train/setup/run_renderer.h"
#include "train/setup/training_setup.h"
#include "tests/support/test_support.h"

using namespace goris;
namespace fs = std::filesystem;

namespace {

// G of every training view of a run folder (stage 1 or RUN/removal), [3][H][W] each.
std::vector<std::vector<float>> glossy_maps(const fs::path& run, const Dataset& ds) {
  const TrainConfig config = read_run_config(run);
  GaussianModel model = load_run_model(run, Device::CPU);
  const auto renderer = load_run_renderer(run, config, scene_extent(ds), Device::CPU);
  IntrinsicRenderer* intrinsic = as_intrinsic(renderer.get());
  EXPECT_NE(intrinsic, nullptr) << run;
  std::vector<std::vector<float>> out;
  if (!intrinsic) return out;
  for (const View& v : ds.train) out.push_back(intrinsic->render_maps(model.view(true), v.camera).glossy);
  return out;
}

}  // namespace

TEST(RemovalPipeline, EmbeddedSceneLosesTheTargetsReflection) {
  const fs::path run = test::scratch_dir("removal_reflection") / "run";
  TrainConfig c;
  c.mode = TrainMode::Intrinsic;
  c.input.data = (test::resource_dir() / "default_scene").string();
  c.device = DeviceChoice::CPU;
  c.input.resolution = 64;
  // Radiance until 1000, then shading. Shorter runs (600 iterations, or 3000 points in a small box) leave the
  // geometry too blurred for any reflection ray to reach the torus: no lighting-aware mask at all.
  c.iterations = 2000;
  c.init.random_points = 10000;
  c.intrinsic.env_resolution = 8;
  c.bookkeeping.checkpoint_interval = 0;
  {
    PreparedTraining p = prepare_training(run, c, std::nullopt);
    write_run_config(run, p.config);
    Trainer::RunOptions ro;
    ro.run_dir = run;
    ASSERT_EQ(p.trainer->run(ro), Trainer::RunResult::Finished);
    write_trained_run(run, *p.trainer, *p.trainer->renderer());
  }
  const Dataset ds = load_dataset(c.input.data, dataset_options(read_run_config(run)));
  {  // goris select RUN --masks: votes of the training views' object masks, closed by the hull
    const GaussianModel model = load_run_model(run, Device::CPU);
    const MaskVotes votes = labels_from_masks(model, load_masked_views(ds.train, std::nullopt), MaskVoteSettings{},
                                              RasterRenderer::settings_for(read_run_config(run)));
    const SelectionResult sel = close_selection(selection_points(model), votes.selected);
    ASSERT_GT(sel.summary.selected, 0u);
    ASSERT_LT(sel.summary.fraction(), 0.5);
    SelectionRecord record;
    record.method = "masks";
    record.model_fingerprint = model_fingerprint(model);
    write_selection(selection_json_path(run), record, sel.mask);
  }
  RemovalOptions o;
  o.device = DeviceChoice::CPU;
  o.finetune_iterations = 20;
  const RemovalReport rep = run_removal(run, o);
  ASSERT_GT(rep.selected, 0u);
  std::printf("selected %zu Gaussians; lighting-aware masks %zu px, inpainting masks %zu px\n", rep.selected,
              rep.lighting_pixels, rep.inpaint_pixels);
  ASSERT_GT(rep.lighting_pixels, 0u) << "no reflection of the target found";
  // By default the fine-tune trains the mask's pixels on dereflected photos (dereflect.h), written per view.
  EXPECT_EQ(rep.dereflected_pixels, rep.lighting_pixels);
  std::size_t dereflected_images = 0;
  for (const View& v : load_dataset(c.input.data, dataset_options(read_run_config(run))).train)
    dereflected_images += fs::exists(rep.out_dir / "dereflected" / (v.name + ".png"));
  EXPECT_GT(dereflected_images, 0u);
  EXPECT_LT(rep.gaussians_after, rep.gaussians_before + rep.added);

  const auto before = glossy_maps(run, ds), after = glossy_maps(rep.out_dir, ds);
  ASSERT_EQ(before.size(), ds.train.size());
  ASSERT_EQ(after.size(), ds.train.size());
  // Mean |dG| over the views' lighting-mask pixels against the other glossy pixels that are neither the
  // target nor its hole (where the target itself, or the inpainted floor, is what changes).
  double in_sum = 0, out_sum = 0;
  std::size_t in_n = 0, out_n = 0;
  for (std::size_t i = 0; i < ds.train.size(); ++i) {
    const View& v = ds.train[i];
    const Image lam = load_mask(rep.out_dir / "lighting_masks" / (v.name + ".png"));
    const Image hole = load_mask(rep.out_dir / "inpaint_masks" / (v.name + ".png"));
    const Image obj = load_view_object_mask(v), gloss = load_view_glossy_mask(v);
    const std::size_t hw = lam.pixel_count();
    ASSERT_EQ(before[i].size(), 3 * hw) << v.name;
    const std::vector<float> l = lam.pixels.to_host(), h = hole.pixels.to_host(), m = obj.pixels.to_host(),
                             g = gloss.pixels.to_host();
    for (std::size_t p = 0; p < hw; ++p) {
      double d = 0;
      for (int ch = 0; ch < 3; ++ch) d += std::abs(double(after[i][ch * hw + p]) - double(before[i][ch * hw + p]));
      if (m[p] > 0.5f || h[p] > 0.5f) continue;
      if (l[p] > 0.5f) {
        in_sum += d;
        ++in_n;
      } else if (g[p] > 0.5f) {
        out_sum += d;
        ++out_n;
      }
    }
  }
  ASSERT_GT(in_n, 20u);
  ASSERT_GT(out_n, 100u);
  const double inside = in_sum / double(in_n), outside = out_sum / double(out_n);
  std::printf("mean |G after - G before| (sum over RGB): %.4f in the lighting masks (%zu px), %.4f on the "
              "rest of the glossy surface (%zu px)\n",
              inside, in_n, outside, out_n);
  EXPECT_GT(inside, 3.0 * outside) << "the target's reflection region should change much more than the rest";
  EXPECT_GT(inside, 0.02);
}
