#include "export/run/run_export.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/io/json_file.h"
#include "core/compute/memory.h"
#include "core/io/file_bytes.h"
#include "core/io/image.h"
#include "core/io/ply.h"
#include "core/io/splat_formats.h"
#include "train/losses/image_losses.h"
#include "train/run/run_data.h"
#include "train/run/run_folder.h"
#include "train/run/run_output_guard.h"
#include "train/run/train_setup.h"
#include "core/util/error.h"
#include "export/frames/camera_path.h"
#include "export/frames/frame_grid.h"
#include "export/frames/channel_image.h"
#include "render/raster/rasterizer.h"
#include "train/radiance/raster_renderer.h"
#include "train/setup/run_renderer.h"

namespace goris {

namespace fs = std::filesystem;

namespace {

constexpr int kHoldoutOrbitFrames = 16;  // held-out cameras when the data set has no test split

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
nlohmann::json vec_json(const glm::vec3& v) { return {v.x, v.y, v.z}; }

void write_json(const fs::path& path, const nlohmann::json& j) {
  write_json_file(path, j);
}

}  // namespace

RenderPath parse_render_path(const std::string& name) {
  if (name == "test") return RenderPath::Test;
  if (name == "train") return RenderPath::Train;
  if (name == "orbit") return RenderPath::Orbit;
  throw Error("--path", "unknown render path '" + name + "' (expected test, train or orbit)");
}

const char* render_path_name(RenderPath path) {
  switch (path) {
    case RenderPath::Test: return "test";
    case RenderPath::Train: return "train";
    case RenderPath::Orbit: return "orbit";
  }
  return "?";
}

fs::path baked_json_path(const fs::path& ply) {
  fs::path j = ply;
  return j.replace_extension(".json");
}

RunExport::RunExport(const fs::path& run_dir, Device device, const std::string& data)
    : run_dir_(fs::absolute(run_dir)), device_(device), config_(read_run_config_with_data(run_dir_, data)) {
  dataset_ = load_dataset(config_.input.data, dataset_options(config_));
  if (dataset_.train.empty()) throw Error(config_.input.data, "the data set has no training views");
  extent_ = scene_extent(dataset_);
  model_ = load_run_model(run_dir_, device_, &model_source_);
  renderer_ = load_run_renderer(run_dir_, config_, extent_, device_);
}

std::vector<float> RunExport::render(const Camera& camera) {
  const RenderedImages r = renderer_->forward(model_.view(renderer_->wants_extras()), camera);
  std::vector<float> color(size_t(3) * size_t(camera.width) * size_t(camera.height));
  device_copy(color.data(), Device::CPU, r.color, device_, color.size() * sizeof(float));
  return color;
}

const char* RunExport::channel_unavailable(Channel channel) const {
  if (channel_info(channel).needs == ChannelNeeds::RemovalMasks)
    return "is a mask of the training views (RUN/removal/), not a render along a path";
  ChannelContext ctx;
  ctx.intrinsic = intrinsic();
  ctx.screen_filter = config_.intrinsic.screen_space_filter;
  return goris::channel_unavailable(channel, ctx);
}

void RunExport::require_channel(Channel channel) const {
  if (const char* why = channel_unavailable(channel))
    throw Error(run_dir_.string(), std::string("channel '") + channel_info(channel).id + "' " + why);
}

std::vector<float> RunExport::render(const Camera& camera, Channel channel) {
  require_channel(channel);
  if (channel == Channel::Final) {
    std::vector<float> color = render(camera);
    for (float& v : color) v = std::clamp(v, 0.0f, 1.0f);
    return color;
  }
  const GaussianView gv = model_.view(/*with_extras=*/true);
  if (IntrinsicRenderer* in = as_intrinsic(renderer_.get())) {
    const IntrinsicMaps maps = in->render_maps(gv, camera);
    return channel_image(channel, in->last().gbuffer, &maps);
  }
  const RasterOutput r = rasterize(gv, camera, RasterRenderer::settings_for(config_), device_);
  return channel_image(channel, r.gbuffer, nullptr);
}

void RunExport::write_ply(const fs::path& out) const {
  check_output_file(out, run_output_guard(run_dir_, config_));
  goris::write_ply(out, model_.to_ply(/*bake_3d_filter=*/true));
}

GaussianPly RunExport::radiance_model() const {
  if (intrinsic())
    throw Error(run_dir_.string(), "an intrinsic run's colours need the distillation (bake) for a plain SH model");
  GaussianPly g = model_.to_ply(/*bake_3d_filter=*/true);
  g.extras.clear();
  return g;
}

void RunExport::write_model(const fs::path& out, const GaussianPly& model) const {
  check_output_file(out, run_output_guard(run_dir_, config_));
  write_gaussians(out, model);
}

std::vector<Camera> RunExport::path_cameras(RenderPath path, int frames, std::vector<std::string>* names) const {
  std::vector<Camera> cams;
  if (names) names->clear();
  if (path == RenderPath::Orbit) {
    const int n = frames > 0 ? frames : kDefaultOrbitFrames;
    cams = orbit_cameras(orbit_from_cameras(cameras_of(dataset_.train)), n);
    if (names)
      for (int k = 0; k < n; ++k) {
        char b[32];
        std::snprintf(b, sizeof b, "frame_%03d", k);
        names->push_back(b);
      }
    return cams;
  }
  const std::vector<View>& views = path == RenderPath::Test ? dataset_.test : dataset_.train;
  if (views.empty())
    throw Error(config_.input.data, std::string("the data set has no ") + render_path_name(path) +
                                  " views; use --path train or --path orbit");
  for (size_t i : evenly_spaced(views.size(), frames)) {
    cams.push_back(views[i].camera);
    if (names) names->push_back(views[i].name);
  }
  return cams;
}

BakedReport RunExport::write_baked(const fs::path& out, const DistillSettings& settings,
                                   const std::function<void(const DistillProgress&)>& on_progress,
                                   const std::atomic<bool>* stop) {
  BakedReport rep = bake(settings, on_progress, stop);
  write_baked_files(rep, out);
  return rep;
}

BakedReport RunExport::bake(const DistillSettings& settings, const std::function<void(const DistillProgress&)>& on_progress,
                            const std::atomic<bool>* stop) {
  BakedReport rep;
  rep.distilled = intrinsic();
  const std::vector<Camera> train = cameras_of(dataset_.train);
  std::vector<Camera> holdout = cameras_of(dataset_.test);
  rep.holdout = "test";
  if (holdout.empty()) {
    holdout = orbit_cameras(orbit_from_cameras(train), kHoldoutOrbitFrames);
    rep.holdout = "orbit";
  }
  DistillSettings s = settings;
  if (!rep.distilled) s.iterations = 0;  // plain SH already: bake the model as it is
  const DistillTeacher teacher = [this](const Camera& c) { return render(c); };
  rep.distill = distill_to_sh(model_, teacher, config_, train, holdout, extent_, s, on_progress, stop);

  // Both against the data set's own test images, as `goris eval` scores the run.
  rep.gt_psnr_run = rep.gt_psnr_baked = std::numeric_limits<double>::quiet_NaN();
  if (rep.holdout == "test") {
    const DatasetOptions dopt = dataset_options(config_);
    std::vector<std::vector<float>> gt;
    for (const View& v : dataset_.test) gt.push_back(to_planar_rgb(load_view_image(v, dopt)));
    double sum = 0;
    for (size_t i = 0; i < gt.size(); ++i)
      sum += psnr_from_mse(mse<float>(rep.distill.holdout_images[i].data(), gt[i].data(), gt[i].size()));
    rep.gt_psnr_run = sum / double(gt.size());
    GaussianModel baked = GaussianModel::from_ply(rep.distill.ply, device_);
    rep.gt_psnr_baked = raster_psnr(baked, distill_config(config_, s), holdout, gt);
  }
  rep.settings = s;
  rep.resolution = {holdout.front().width, holdout.front().height};
  return rep;
}

void RunExport::write_baked_files(BakedReport& rep, const fs::path& out) const {
  rep.ply = out;
  rep.json = baked_json_path(out);
  const DistillSettings& s = rep.settings;
  check_output_file(out, run_output_guard(run_dir_, config_));
  check_output_file(rep.json, run_output_guard(run_dir_, config_));
  goris::write_ply(out, rep.distill.ply);
  const DistillResult& d = rep.distill;
  nlohmann::json per_view = nlohmann::json::array();
  for (double p : d.psnr_per_view) per_view.push_back(number_or_null(p));
  const nlohmann::json j = {
      {"run", run_dir_.string()}, {"model", model_source_}, {"mode", enum_name(config_.mode)},
      {"ply", fs::absolute(out).string()}, {"distilled", rep.distilled},
      {"note", rep.distilled ? "SH distilled from the run's shaded renders (paper S1.6)"
                             : "radiance run: the model is plain SH already; the baked PLY is the --ply export without "
                               "the extra properties (psnr checks the baked 3D filter against the run's own renders)"},
      {"psnr", number_or_null(d.psnr)}, {"psnr_start", number_or_null(d.psnr_start)}, {"psnr_per_view", per_view},
      {"psnr_against", "the run's renderer (clamped to [0, 1]) from the held-out cameras"},
      {"holdout", rep.holdout}, {"holdout_views", d.holdout_views},
      {"iterations", d.iterations}, {"stopped", d.stopped},
      {"target_views", d.target_views}, {"extra_views", d.extra_views}, {"geometry_lr_scale", s.geometry_lr_scale},
      {"gaussians", d.ply.count}, {"sh_degree", d.ply.sh_degree},
      {"resolution", {rep.resolution.first, rep.resolution.second}}, {"device", device_name(device_)},
      {"time_s", d.seconds_total},
      {"seconds", {{"targets", d.seconds_targets}, {"train", d.seconds_train}, {"holdout", d.seconds_holdout}}},
      {"gt", {{"images", "the data set's test images (GOR-IS scenes: after removal)"},
              {"psnr_run", number_or_null(rep.gt_psnr_run)}, {"psnr_baked", number_or_null(rep.gt_psnr_baked)}}}};
  write_json(rep.json, j);
}

RendersReport RunExport::write_renders(const fs::path& dir, RenderPath path, int frames,
                                       const std::function<void(size_t, size_t)>& on_frame, Channel channel) {
  require_channel(channel);
  RendersReport rep;
  rep.dir = fs::absolute(dir);
  check_output_dir(dir, run_output_guard(run_dir_, config_));
  const std::vector<Camera> cams = path_cameras(path, frames, &rep.frames);
  rep.width = cams.front().width;
  rep.height = cams.front().height;
  const FrameGrid grid = frame_grid_layout(int(cams.size()), rep.width, rep.height);
  std::vector<Image> cells;
  nlohmann::json jc = nlohmann::json::array();
  double ms = 0;
  for (size_t i = 0; i < cams.size(); ++i) {
    const Camera& c = cams[i];
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<float> color = render(c, channel);
    ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const Image img = from_planar(color.data(), 3, c.width, c.height);
    save_png(rep.dir / (rep.frames[i] + ".png"), img);
    cells.push_back(resize_image(img, grid.cell_width, grid.cell_height));
    const nlohmann::json cam_json = {{"name", rep.frames[i]}, {"width", c.width}, {"height", c.height}, {"fx", c.fx}, {"fy", c.fy},
                  {"cx", c.cx}, {"cy", c.cy}, {"position", vec_json(c.center())}, {"forward", vec_json(c.forward())},
                  {"R", {vec_json(glm::vec3(c.R[0][0], c.R[1][0], c.R[2][0])), vec_json(glm::vec3(c.R[0][1], c.R[1][1], c.R[2][1])),
                         vec_json(glm::vec3(c.R[0][2], c.R[1][2], c.R[2][2]))}},
                  {"t", vec_json(c.t)}};
    jc.push_back(cam_json);
    if (on_frame) on_frame(i + 1, cams.size());
  }
  rep.ms_per_frame = ms / double(cams.size());
  rep.contact_sheet = rep.dir / "contact_sheet.png";
  save_png(rep.contact_sheet, compose_frame_grid(grid, cells));
  nlohmann::json j = {{"run", run_dir_.string()},
                      {"path", render_path_name(path)},
                      {"channel", channel_info(channel).id},
                      {"convention", "world-to-camera x_cam = R x_world + t, OpenCV axes (x right, y down, z forward)"},
                      {"cameras", jc}};
  if (path == RenderPath::Orbit) {
    const OrbitPath o = orbit_from_cameras(cameras_of(dataset_.train));
    j["orbit"] = {{"center", vec_json(o.center)}, {"up", vec_json(o.up)}, {"radius", o.radius}, {"height", o.height},
                  {"rule", "circle about the cameras' mean up through the point nearest to their optical axes, at "
                           "their mean height and horizontal distance; frame 0 towards the first training camera, "
                           "counter-clockwise seen from above, every frame looking at that point"}};
  }
  write_json(rep.dir / "cameras.json", j);
  return rep;
}

}  // namespace goris
