#pragma once
// `goris synth` as a library call: scene description -> scene.json -> Blender renders -> data set folder.
// The folder is assembled in a staging folder beside it (OUT.synth-tmp) and renamed into place only when
// Blender succeeded, so an interrupted or failed run never leaves a half data set under the final name.
#include <filesystem>
#include <functional>

#include "tools/synth/presets.h"

namespace goris::synth {

struct SynthJob {
  SynthOptions options;
  std::filesystem::path out;     // the data set folder (created; a previous synth output there is replaced)
  std::filesystem::path script;  // resources/synth/render_scene.py
  std::filesystem::path blender; // empty: `blender` on PATH
  bool contact_sheet = false;
  std::function<void(int done, int total)> on_frame;  // after each rendered view
};

// Throws goris::Error: unknown preset, no Blender, a non-empty OUT that is not a synth output, or a
// failed render (the message has the last lines of OUT/blender.log and its path).
void run_synth(const SynthJob& job);

// The training views of an existing synth data set rendered once more with the target hidden, into
// DATA/train_after/r_XXX.png (the views `goris remove --fill-truth` reads: what a perfect removal would
// show in the views it learns from). Rendered in DATA/train_after.synth-tmp and renamed into place.
struct TrainAfterJob {
  std::filesystem::path data;    // a `goris synth` output (has scene.json)
  std::filesystem::path script;  // resources/synth/render_scene.py
  std::filesystem::path blender; // empty: `blender` on PATH
  std::function<void(int done, int total)> on_frame;
};
// Throws goris::Error: DATA without scene.json, no Blender, or a failed render (log in
// DATA/blender_train_after.log).
void render_train_after(const TrainAfterJob& job);

}  // namespace goris::synth
