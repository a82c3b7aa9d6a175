#include "train/run/run_output_guard.h"

#include "train/run/run_folder.h"

namespace goris {

OutputGuard run_output_guard(const std::filesystem::path& run_dir, const TrainConfig& config, bool keep_selection) {
  OutputGuard g;
  if (!config.input.data.empty()) g.datasets.push_back(config.input.data);
  g.keep = {run_config_path(run_dir), run_ply_path(run_dir), run_dir / "checkpoints", run_dir / "log.csv"};
  if (keep_selection) {
    g.keep.push_back(run_dir / "selection.json");
    g.keep.push_back(run_dir / "selection.npy");
  }
  return g;
}

}  // namespace goris
