#pragma once
// Training checkpoints: one binary file with the configuration, the iteration, the view-order RNG, every
// parameter with its Adam moments and step counts, the densification statistics, the 3D filter and the
// training hooks' state (TrainerState::hooks: the emit weights of intrinsic mode, in the place the format
// gives them), ending in a checksum; older format versions still load. Written to a temporary file and
// renamed, so a crash never leaves a half-written checkpoint under the final name. Resuming from one
// continues bit for bit as if never interrupted.
#include <filesystem>
#include <optional>

#include "train/config/train_config.h"
#include "train/loop/trainer.h"

namespace goris {

// Throws goris::Error for hook state the format has no place for (a hook other than the emit weights').
void write_checkpoint(const std::filesystem::path& path, const TrainConfig& config, const TrainerState& state);

struct Checkpoint {
  TrainConfig config;
  TrainerState state;
};
// Reads a checkpoint onto `device`. Throws goris::Error naming the file for a missing, truncated,
// corrupted (checksum) or foreign file.
Checkpoint read_checkpoint(const std::filesystem::path& path, Device device);

// Checkpoint files of a run folder: RUN/checkpoints/iter_<8 digits>.ckpt.
std::filesystem::path checkpoint_path(const std::filesystem::path& run_dir, int iteration);
// The checkpoint with the highest iteration in RUN/checkpoints that is intact (a regular file with the magic
// and checksum), if any: a truncated or corrupted latest one (a kill or a full disk while it was written),
// or a FIFO, device or folder under a checkpoint's name, is passed over for the one before, with a warning on
// stderr naming it and what is wrong. nullopt when RUN/checkpoints holds no checkpoint; throws goris::Error
// naming every file and its problem, and how to start over (--restart), when it holds some but none is
// intact.
std::optional<std::filesystem::path> latest_checkpoint(const std::filesystem::path& run_dir);
// Whether RUN/checkpoints holds any file under a checkpoint's name, intact or not (none is opened).
bool has_checkpoint_files(const std::filesystem::path& run_dir);
// Where the renderer's own parameters (environment map, roughness net) of a checkpoint are stored:
// the checkpoint's path + ".renderer" (written only by renderers that own parameters).
std::filesystem::path renderer_state_path(const std::filesystem::path& checkpoint);
// Deletes all but the `keep` most recent checkpoints.
void remove_old_checkpoints(const std::filesystem::path& run_dir, int keep);

}  // namespace goris
