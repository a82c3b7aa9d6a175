#include "app/bench/bench_pipeline.h"

#include "core/util/fnv1a.h"
#include "train/config/train_config.h"

namespace goris::bench::pipeline {

const std::vector<ConfigSpec>& ladder() {
  static const std::vector<ConfigSpec> specs = {
      {"baseline", "radiance", {"--mode", "radiance"}, "material,lamask,twins,underside", false,
       "radiance stage 1; RGB-only inpainting, no lighting-aware mask, no mirror twin, the hole supervised by the "
       "reference views alone (3DGIC's rule)",
       {"--view-fill", "0"}},
      {"default", "default", {}, "", false,
       "`goris train` and `goris remove` with no options (--mode auto: intrinsic for a glossy scene, radiance "
       "otherwise): what a user gets"},
      {"default-noplanar", "default", {}, "twins,reflection,underside", false,
       "default without what the glossy plane gives the removal (no planar reflection mask, no mirror twin, nothing "
       "taken from under the target)"},
      {"default-nofill", "default", {}, "", false,
       "default without every other view's own fill of its hole (--view-fill 0): the reference views alone "
       "supervise it", {"--view-fill", "0"}},
      {"default-truefill", "default", {}, "", false,
       "a measurement, not a removal: default with the true images of the training views without the target in "
       "place of every target its fills make up (`goris remove --fill-truth`): what perfect fills would score",
       {}, true},
      {"+elt", "intrinsic_nossf", {"--mode", "intrinsic", "--set", "intrinsic_screen_space_filter=false"},
       "material,lamask,twins,underside", false, "intrinsic stage 1 with explicit light transport, no screen-space filter"},
      {"+ssf", "intrinsic", {"--mode", "intrinsic"}, "material,lamask,twins,underside", false,
       "intrinsic stage 1 with the screen-space filter"},
      {"full", "intrinsic", {"--mode", "intrinsic"}, "", false, "+ material inpainting, lighting-aware masks (reflections and the target's shadow) and the target's mirror twin"},
      {"planar", "intrinsic_planar", {"--mode", "intrinsic", "--preset", "planar-glossy"}, "", false,
       "full with `--preset planar-glossy` (the table opaque and held to its plane, exact normals)"},
      {"distilled", "intrinsic", {"--mode", "intrinsic"}, "", true,
       "full, exported as a baked (SH) PLY and evaluated as a radiance run"},
      // Modelling no more than a scene needs: each choice against full (and default, --mode auto, against
      // baseline).
      {"auto-detect", "auto_detect", {"--mode", "auto", "--set", "use_glossy_masks=false"}, "", false,
       "--mode auto with the glossy masks hidden: glossy regions detected from the photos once the geometry has settled"},
      {"sh1", "intrinsic_sh1", {"--mode", "intrinsic", "--set", "max_sh_degree=1"}, "", false,
       "full with SH degree 1 (the glossy term carries the view dependence)"},
      {"coarse", "intrinsic_coarse", {"--mode", "intrinsic", "--set", "intrinsic_coarse_tracing=true"}, "", false,
       "full with coarse tracing (one reflection ray per block where the glossy filter blurs)"},
  };
  return specs;
}

std::string config_names() {
  std::string names;
  for (const auto& c : ladder()) names += (names.empty() ? "" : ", ") + std::string(c.name);
  return names;
}

size_t config_index(const std::string& name) {
  for (size_t i = 0; i < ladder().size(); ++i)
    if (ladder()[i].name == name) return i;
  return 0;
}

// What `goris train` does with no options: its default configuration. A result of `default` is reused only
// when the defaults it was trained with are today's (other code changes are the --out folder's business,
// as for every configuration).
std::string defaults_fingerprint() {
  nlohmann::json j;
  to_json(j, goris::TrainConfig{});
  j.erase("data");
  j.erase("data_views");      // a record of the data set, not a training setting
  j.erase("config_version");  // the file's layout, not a setting
  return std::to_string(goris::fnv1a(j.dump()));
}


}  // namespace goris::bench::pipeline
