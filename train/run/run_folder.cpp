#include "core/io/json_file.h"
#include "train/run/run_folder.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/io/file_bytes.h"
#include "core/io/ply.h"
#include "core/io/splat_formats.h"
#include "core/util/error.h"
#include "train/config/config_migration.h"
#include "train/loop/checkpoint.h"

namespace goris {

std::filesystem::path run_config_path(const std::filesystem::path& run_dir) { return run_dir / "config.json"; }
std::filesystem::path run_ply_path(const std::filesystem::path& run_dir) { return run_dir / "point_cloud.ply"; }

void write_run_config(const std::filesystem::path& run_dir, const TrainConfig& config) {
  write_json_file(run_config_path(run_dir), nlohmann::json(config));
}

TrainConfig read_run_config(const std::filesystem::path& run_dir) {
  const auto path = run_config_path(run_dir);
  std::ifstream f(path);
  if (!f) throw Error(path.string(), "cannot open (is " + run_dir.string() + " a training run folder?)");
  TrainConfig c;
  try {
    nlohmann::json j = nlohmann::json::parse(f);
    print_config_migration_notes(path.string(), migrate_config_json(j));
    from_json(j, c);
  } catch (const std::exception& e) {
    throw Error(path.string(), e.what());
  }
  c.validate(path.string());
  return c;
}

GaussianModel load_run_model(const std::filesystem::path& run_dir, Device device, std::string* source) {
  if (const auto ck = latest_checkpoint(run_dir)) {
    if (source) *source = ck->string();
    return std::move(read_checkpoint(*ck, device).state.model);
  }
  const auto ply = run_ply_path(run_dir);
  if (std::filesystem::exists(ply)) {
    if (source) *source = ply.string();
    return GaussianModel::from_ply(read_gaussians(ply), device);
  }
  throw Error(run_dir.string(), "no trained model: neither checkpoints/ nor point_cloud.ply");
}

bool run_outputs_written_after(const std::filesystem::path& run_dir, const std::filesystem::path& checkpoint,
                               const TrainConfig& config) {
  auto written_after = [&](const std::filesystem::path& f) {
    std::error_code e1, e2;
    const auto t = std::filesystem::last_write_time(f, e1);
    return !e1 && t >= std::filesystem::last_write_time(checkpoint, e2) && !e2;
  };
  return written_after(run_ply_path(run_dir)) &&
         (config.mode != TrainMode::Intrinsic || written_after(run_dir / "environment.png"));
}

}  // namespace goris
