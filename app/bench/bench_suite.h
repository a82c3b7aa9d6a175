#pragma once
// The generalization suite of `goris bench pipeline --suite NAME`: GOR-IS-style scenes made with `goris synth`
// that vary what a removal depends on (the glossy surface's material, roughness and shape, the target's
// shape, the clutter, the camera elevation) plus the method's two failure cases, cached by their scene
// description; and the suite's summary: the removal metrics of each scene, their mean and worst scene, the
// goals they must meet and the regression check against a committed summary.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/synth/presets.h"

namespace goris::bench {

struct SuiteScene {
  std::string name;
  std::string kind;  // "glossy" (the method applies), "lambertian" or "failure" (twin mirrors)
  synth::SynthOptions synth;
};

// "generalization" (14 scenes: 12 glossy, a Lambertian room and twin mirrors) or "fast" (3 of them, for the
// short schedule). goris::Error listing the names for another name.
const std::vector<SuiteScene>& suite_scenes(const std::string& suite);
const std::vector<std::string>& suite_names();

// The data set folder of a scene under `cache` (cache/NAME), rendered with Blender unless a folder made from
// the same scene description is there already. Progress goes to stderr.
std::filesystem::path ensure_suite_scene(const SuiteScene& scene, const std::filesystem::path& cache,
                                         const std::filesystem::path& blender_script);

// The fingerprint of a rendered scene (16 hex digits): FNV-1a over the decoded pixels of every PNG directly in
// its train/ and test/ folders (the views and their masks), with their paths and sizes. Blender builds or
// machines that render a scene differently give different fingerprints (PNG encoders that merely compress
// differently do not), and results measured on differently rendered scenes are not comparable.
std::string scene_images_fingerprint(const std::filesystem::path& scene);

// One configuration's result on one scene, as the suite summary reads it.
struct SuiteResult {
  std::string scene, kind, config;
  bool ok = false;
  double psnr, region_psnr, region_ssim, region_flip, flip, ghost_ratio, seconds;
  double ghost_floor;  // stage 1's own share of the ghost (goris eval); NaN when not measured
  // The share of the glossy surface's colour in stage 1's glossy term (goris eval's "reflections"); NaN for
  // a radiance stage 1 or when not measured.
  double stage1_glossy_share;
  std::string contact_sheet;  // relative to the bench folder; "" when none
  std::string scene_images;   // scene_images_fingerprint of the scene it ran on; "" when unknown
  SuiteResult();
};

// The summary of `results` (every config against `reference`, normally "baseline"): suite.md text and the
// suite.json object that a later run checks against.
struct SuiteSummary {
  std::string markdown;
  nlohmann::json json;
};
SuiteSummary summarize_suite(const std::string& suite, const std::string& schedule,
                             const std::vector<SuiteResult>& results, const std::string& reference);

// One row per scene from its configurations' contact sheets (goris eval's METRICS_removal.png: rows of
// full_ | r_ | render | error, the largest changed region first; paths relative to `root`): full_ | r_ |
// each configuration's render.
// False when no sheet was there.
bool write_suite_sheet(const std::vector<SuiteResult>& results, const std::filesystem::path& root,
                       const std::filesystem::path& path);

// Compares `current` with a committed suite.json: a configuration whose changed-region PSNR on any scene
// fell by more than `tolerance_db` (or that failed where it succeeded) is a regression. A scene whose images
// differ from those the committed results were measured on (both rows name their scene_images) is not
// compared: a drop there says nothing about the code.
struct SuiteCheck {
  std::vector<std::string> regressions;   // one line each (empty: none)
  std::vector<std::string> not_compared;  // one line per scene rendered differently
  int compared = 0;                       // rows compared
  int unverified = 0;                     // of them, rows whose committed result names no scene images
};
SuiteCheck check_suite(const nlohmann::json& committed, const nlohmann::json& current, double tolerance_db);

}  // namespace goris::bench
