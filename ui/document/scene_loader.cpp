#include "ui/document/scene_loader.h"

#include <algorithm>
#include <cmath>

#include "core/io/splat_formats.h"
#include "core/util/error.h"
#include "train/radiance/raster_renderer.h"
#include "train/run/run_folder.h"
#include "train/run/train_setup.h"
#include "train/setup/run_renderer.h"
#include "ui/display/dataset_cameras.h"

namespace goris::ui {

namespace fs = std::filesystem;

const char* scene_kind_name(OpenedScene::Kind kind) {
  switch (kind) {
    case OpenedScene::Kind::Run:
      return "run";
    case OpenedScene::Kind::Model:
      return "model";
    case OpenedScene::Kind::Dataset:
      break;
  }
  return "data set";
}

bool is_run_folder(const fs::path& path) { return fs::is_directory(path) && fs::exists(run_config_path(path)); }

namespace {

// The orbit frame from the training cameras: up from their orientation, centre and size from where they are.
void frame_from_cameras(const Dataset& ds, OpenedScene& s) {
  const std::vector<View>& views = ds.train.empty() ? ds.test : ds.train;
  const SceneBounds b = camera_bounds(views);
  s.up = world_up(views);
  s.center = b.center;
  s.radius = b.radius > 0 ? b.radius : 1.0f;
  // Cameras on a ring look inwards: the scene is around their centre, about half their radius across.
  if (views.size() >= 2) s.radius *= 0.5f;
}

// Without cameras: the model's median position and the 90th percentile of distances from it.
void frame_from_model(const ModelSnapshot& m, OpenedScene& s) {
  if (m.count() == 0) return;
  Buffer<float> pos(m.count() * 3, m.device());
  device_copy(pos.data(), pos.device(), m.view().positions, m.device(), pos.bytes());
  const std::vector<float> p = pos.to_host();
  glm::vec3 c(0.0f);
  for (int k = 0; k < 3; ++k) {
    std::vector<float> axis(m.count());
    for (size_t i = 0; i < m.count(); ++i) axis[i] = p[i * 3 + k];
    std::nth_element(axis.begin(), axis.begin() + std::ptrdiff_t(axis.size() / 2), axis.end());
    c[k] = axis[axis.size() / 2];
  }
  std::vector<float> d(m.count());
  for (size_t i = 0; i < m.count(); ++i) d[i] = glm::length(glm::vec3(p[i * 3], p[i * 3 + 1], p[i * 3 + 2]) - c);
  const size_t k = std::min(d.size() - 1, d.size() * 9 / 10);
  std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(k), d.end());
  s.center = c;
  s.radius = d[k] > 0 ? d[k] : 1.0f;
}

// The model of the run in `path` as the viewports show it: shaded with the run's environment map and net
// (kept beside its latest checkpoint) for an intrinsic run. `s` gives the data set (for the scene extent)
// and takes the warnings; `source` the file the model came from.
std::shared_ptr<const ModelSnapshot> run_snapshot(const fs::path& path, const TrainConfig& config, Device device,
                                                  OpenedScene& s, std::string* source) {
  GaussianModel model = load_run_model(path, device, source);
  std::shared_ptr<const ShadingSource> shading;
  std::shared_ptr<const std::string> renderer_state;
  if (config.mode == TrainMode::Intrinsic) {
    float extent = 0;
    if (s.dataset && !s.dataset->train.empty()) {
      extent = scene_extent(*s.dataset);
    } else {
      frame_from_model(ModelSnapshot(model, 0, {}), s);
      extent = 2.0f * s.radius;
      s.warnings.push_back("without the data set the scene extent (reflection ray offsets) is estimated");
    }
    try {
      const auto renderer = load_run_renderer(path, config, extent, device);
      renderer_state = std::make_shared<const std::string>(renderer->save_own_state());
      shading = std::make_shared<const ShadingSource>(ShadingSource{config, extent});
    } catch (const Error& e) {
      s.warnings.push_back(std::string("shown unshaded (radiance only): ") + e.what());
    }
  }
  return std::make_shared<const ModelSnapshot>(model, 0, RasterRenderer::settings_for(config), std::move(shading),
                                               std::move(renderer_state));
}

}  // namespace

bool is_cleaned_scene(const fs::path& input) {
  const fs::path path = input.filename().empty() ? input.parent_path() : input;  // "RUN/removal/"
  return path.filename() == "removal" && is_run_folder(path) && fs::exists(path / "report.json") &&
         is_run_folder(path.parent_path());
}

OpenedScene open_scene(const fs::path& input, Device device) {
  if (input.empty()) throw Error("open: no path given");
  const fs::path path = fs::absolute(input).lexically_normal();
  if (!fs::exists(path)) throw Error(path.string(), "no such file or folder");
  OpenedScene s;
  s.path = path;
  if (is_run_folder(path)) {
    s.kind = OpenedScene::Kind::Run;
    s.run_config = read_run_config(path);
    s.dataset_options = dataset_options(*s.run_config);
    try {
      s.dataset = load_dataset(s.run_config->input.data, s.dataset_options);
    } catch (const Error& e) {
      s.warnings.push_back(std::string("the run's data set cannot be opened (") + e.what() +
                           "): no cameras or photos to compare with");
    }
    s.model = run_snapshot(path, *s.run_config, device, s, &s.model_source);
    if (is_cleaned_scene(path)) {
      // The run it was cleaned from, shown by the before / after toggle and compared against.
      try {
        s.before_model = run_snapshot(path.parent_path(), read_run_config(path.parent_path()), device, s, nullptr);
      } catch (const Error& e) {
        s.warnings.push_back(std::string("no before / after: the run it was cleaned from cannot be opened (") +
                             e.what() + ")");
      }
    }
  } else if (fs::is_regular_file(path)) {
    // A model file: read by its content (any splat format), rendered with the default settings (black
    // background, the filters of a trained run), framed by its own extent.
    s.kind = OpenedScene::Kind::Model;
    const GaussianModel model = GaussianModel::from_ply(read_gaussians(path), device);
    s.model = std::make_shared<const ModelSnapshot>(model, 0, RasterRenderer::settings_for(TrainConfig{}));
    s.model_source = path.string();
    s.warnings.push_back("a model file has no photos: it can be viewed and selected on; training and removal need "
                         "the data set or the run folder it came from");
  } else {
    s.kind = OpenedScene::Kind::Dataset;
    s.dataset = load_dataset(path, s.dataset_options);
  }
  if (s.dataset) {
    for (const std::string& w : s.dataset->warnings) s.warnings.push_back(w);
    if (!s.dataset->train.empty() || !s.dataset->test.empty()) frame_from_cameras(*s.dataset, s);
  } else if (s.model) {
    frame_from_model(*s.model, s);
  }
  return s;
}

}  // namespace goris::ui
