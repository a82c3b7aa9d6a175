#pragma once
// `goris train --mode auto` (and the editor's "auto"): train the intrinsic model only when the scene has
// glossy surfaces, so a Lambertian scene costs exactly a radiance run.
//
//  - Data with glossy masks: intrinsic when the masks mark a glossy region (at least
//    intrinsic_auto_mask_fraction of their pixels > 0.5), otherwise radiance ("the glossy masks are empty").
//  - Data without glossy masks (or use_glossy_masks false): radiance with config.input.auto_detect_glossy set.
//    Once the geometry has settled (auto_detection_iteration: the end of the warm-up, TrainConfig::
//    shading_from, but not before intrinsic_detect_after iterations or half the run, whichever comes first,
//    nor before intrinsic_detect_settled iterations - on a Lambertian room (lambert_room) a 4K-iteration
//    run's geometry at the paper's scaled warm-up, 533, is a blur that makes every edge look
//    view-dependent; a late glossy decision lengthens the run, see lengthened_for_late_decision) and
//    apply_auto_mode, called before every step and once at the end of the iterations, detects
//    glossy regions from the photos (train/setup/glossy_detection.h), writes the masks to
//    RUN/detected_gloss/gloss_<view>.png with RUN/detected_gloss/summary.json, and either switches the
//    trainer to intrinsic with those masks as the views' glossy masks (the model's material extras start
//    from their initial values) or lets the run finish as pure radiance (no tracing, no environment map,
//    no net).
//
// Persistence: the decision is part of the configuration. Switching sets mode "intrinsic", the lengthened
// iterations, glossy_mask_dir = RUN/detected_gloss, intrinsic_warmup to the switch (so that the shading
// phase's schedules start there) and clears auto_detect_glossy; staying clears auto_detect_glossy.
// RUN/config.json is rewritten at once and every later checkpoint stores the new configuration, so a
// resumed run comes back in the mode it switched to, reading the same masks (prepare_training loads
// glossy_mask_dir); a run resumed from a checkpoint written before the decision detects again when it
// reaches the end of the warm-up.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/io/dataset.h"
#include "train/config/train_config.h"
#include "train/loop/trainer.h"

namespace goris {

// Fraction of the pixels > 0.5 over the views' glossy masks (views without a mask are not counted); nullopt
// when no view has one.
std::optional<double> glossy_mask_fraction(const std::vector<TrainView>& views);

// Resolves config.mode "auto" at the start of a run from the loaded training views (their glossy masks):
// sets the mode (and auto_detect_glossy when the detection has to decide later) and returns why, for the
// user, with a caution when the run ends before intrinsic_detect_settled (the decision may misfire on a
// Lambertian scene). No-op returning "" for any other mode.
std::string resolve_auto_mode(TrainConfig& config, const std::vector<TrainView>& views);

// Where the shading phase would start: max(TrainConfig::shading_from(), min(intrinsic_detect_after,
// iterations / 2)).
int planned_shading_start(const TrainConfig& config);

// The iteration after which the detection runs: the planned shading start, but not before
// intrinsic_detect_settled iterations (4000; capped at the run's end). While the geometry is still
// settling its misregistration reads as view dependence: before a radiance phase of 4000 iterations has run
// to its end, a Lambertian scene can show more evidence than a glossy one, and only after it do the two
// separate with a margin (docs/lab/bench/NOTES.md, 2026-11-22, "--mode auto over seeds"). When that
// iteration is an opacity reset's, or less than densify_interval after one, the detection runs just before
// the reset: a freshly reset model covers no pixel (a 6000- or 10000-iteration run resets at 4000).
int auto_detection_iteration(const TrainConfig& config);

// A glossy decision later than planned (a run shorter than 2 x intrinsic_detect_settled) keeps the shading
// phase the planned run would have had: iterations = decided_at + (iterations - planned start). The
// schedules scale with the new length, so the position learning rate rises again for the shading phase,
// as it is there in a planned run: with the radiance run's decay kept (the learning rate at its final value
// for the whole shading phase) the geometry could not follow the shading, and the removal left the target's
// reflection behind (docs/lab/bench/NOTES.md, 2026-11-22). A Lambertian scene's run keeps its length, so it
// still costs what the radiance baseline costs; a glossy one trains longer than `--mode intrinsic` would.
// Returns the config unchanged when not late.
TrainConfig lengthened_for_late_decision(const TrainConfig& config, int decided_at);

// Glossy masks of a folder written by the detection: gloss_<view name>.png at each view's size, into the
// views' glossy_mask. Throws goris::Error naming the file when one is missing or has another size.
void load_glossy_mask_folder(const std::filesystem::path& dir, std::vector<TrainView>& views);
// The glossy masks a run trained with, one per view of `views` (its training views) at the camera's size, in
// [0, 1]; empty for a view without one: the folder's (glossy_mask_dir: --mode auto's detected masks) when
// the config names one, else the data set's, none with use_glossy_masks off. Errors as the loaders throw them.
std::vector<std::vector<float>> run_glossy_masks(const TrainConfig& config, const std::vector<View>& views);
// The views' glossy masks as such a folder (8-bit PNG). Throws goris::Error when a view has none.
void save_glossy_mask_folder(const std::filesystem::path& dir, const std::vector<TrainView>& views);

struct AutoDecision {
  int iteration = 0;             // iterations done when it was taken
  bool glossy = false;           // switched to intrinsic
  double fraction = 0, threshold = 0;  // detected fraction of the covered pixels, and the threshold
  std::size_t covered = 0, scored = 0, detected = 0;
  int planes = 0;                // planes the masks were grown over
  int backdrops = 0;             // planes found but rejected: most of the evidence stands in front of them
  std::size_t mask_pixels = 0;   // pixels in the grown masks (at the detection's size, like `covered`)
  bool mirror_world = false;     // glossy because the model holds a mirror world (mirror_world_detection.h)
  double seconds = 0;            // rendering the depths and detecting
  int extended_by = 0;           // iterations added to the run (lengthened_for_late_decision)
  std::filesystem::path mask_dir;
  std::string message() const;   // one line for the user
};

// Before a training step (Trainer::RunOptions::before_step): when the trainer's config has
// auto_detect_glossy set and the warm-up is done, detects, writes RUN/detected_gloss/ and RUN/config.json,
// and switches the trainer (see above). Returns the decision when it was taken in this call.
std::optional<AutoDecision> apply_auto_mode(Trainer& trainer, const std::filesystem::path& run_dir);

}  // namespace goris
