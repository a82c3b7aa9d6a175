#pragma once
// Opening what the user points the editor at: a data set folder (anything load_dataset reads), a run
// folder (config.json present: its trained model plus, when still there, its data set for the cameras and
// photos) or a model file of any splat format (3DGS PLY, compressed PLY, SPZ, .splat, GLB: shown, inspected
// and selected on; with no photos it cannot be trained or cleaned). Runs on a background thread in the app;
// nothing here touches the GUI.
#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/io/dataset.h"
#include "train/config/train_config.h"
#include "ui/display/model_snapshot.h"

namespace goris::ui {

struct OpenedScene {
  enum class Kind { Dataset, Run, Model };
  Kind kind = Kind::Dataset;
  std::filesystem::path path;      // what was opened, absolute
  std::optional<Dataset> dataset;  // absent only for a run whose data set is gone (see warnings)
  DatasetOptions dataset_options;  // how its photos are loaded (the run's background and size)
  std::optional<TrainConfig> run_config;
  std::shared_ptr<const ModelSnapshot> model;  // runs: the latest checkpoint or point_cloud.ply; model files
  std::string model_source;                    // the file the model came from
  // A cleaned scene (RUN/removal, see is_cleaned_scene): the model of RUN, with the target; else null.
  std::shared_ptr<const ModelSnapshot> before_model;
  glm::vec3 up{0, 0, 1}, center{0.0f};         // for the orbit camera
  float radius = 1.0f;
  std::vector<std::string> warnings;
};

// "data set", "run" or "model": what the editor says it opened.
const char* scene_kind_name(OpenedScene::Kind kind);

// True when `path` is a run folder (holds config.json).
bool is_run_folder(const std::filesystem::path& path);

// True when `path` is the cleaned scene of a run: RUN/removal holding stage 2's finished result
// (config.json and report.json) inside a run folder.
bool is_cleaned_scene(const std::filesystem::path& path);

// Opens a data set, a run folder or a model file; the model lives on `device`. Throws goris::Error naming
// the file and the problem (missing path, unknown format, unreadable model...).
OpenedScene open_scene(const std::filesystem::path& path, Device device);

}  // namespace goris::ui
