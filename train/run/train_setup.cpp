#include "train/run/train_setup.h"

#include "core/io/splat_formats.h"
#include "core/scene/gaussian_init.h"
#include "core/util/error.h"

namespace goris {

DatasetOptions dataset_options(const TrainConfig& config) {
  DatasetOptions o;
  o.background = config.input.background;
  o.downscale = config.input.downscale;
  o.target_width = config.input.resolution;
  o.undistort = true;
  return o;
}

std::vector<float> to_planar_rgb(const Image& image) {
  if (image.channels != 3) throw Error("to_planar_rgb: expected an RGB image, got " + std::to_string(image.channels) + " channels");
  const std::vector<float> hwc = image.pixels.to_host();
  const size_t hw = image.pixel_count();
  std::vector<float> out(3 * hw);
  for (size_t p = 0; p < hw; ++p)
    for (int c = 0; c < 3; ++c) out[c * hw + p] = hwc[p * 3 + c];
  return out;
}

Image from_planar(const float* planar, int channels, int width, int height) {
  Image img(width, height, channels, Device::CPU);
  const size_t hw = size_t(width) * size_t(height);
  for (size_t p = 0; p < hw; ++p)
    for (int c = 0; c < channels; ++c) img.pixels[p * channels + c] = planar[c * hw + p];
  return img;
}

std::vector<TrainView> load_train_views(const std::vector<View>& views, const DatasetOptions& options,
                                        const std::function<void(size_t, size_t)>& on_view) {
  std::vector<TrainView> out;
  out.reserve(views.size());
  for (size_t i = 0; i < views.size(); ++i) {
    if (on_view) on_view(i, views.size());
    const View& v = views[i];
    if (v.camera.has_distortion())
      throw Error(v.image.string(), "the camera has lens distortion, which the rasterizer does not model "
                                    "(undistort the images first)");
    std::optional<Image> alpha;
    const Image img = load_view_image(v, options, Device::CPU, &alpha);
    if (img.width != v.camera.width || img.height != v.camera.height)
      throw Error(v.image.string(), "image size differs from its camera's");
    TrainView tv;
    tv.name = v.name, tv.camera = v.camera, tv.image = to_planar_rgb(img);
    if (v.glossy_mask) tv.glossy_mask = load_view_glossy_mask(v).pixels.to_host();
    if (v.object_mask) tv.object_mask = load_view_object_mask(v).pixels.to_host();
    if (alpha) tv.alpha = alpha->pixels.to_host();
    out.push_back(std::move(tv));
  }
  return out;
}

float scene_extent(const Dataset& dataset) {
  const SceneBounds b = dataset.camera_bounds();
  // A single camera (or coincident ones) has radius 0: fall back to its distance to the origin.
  if (b.radius > 0) return b.radius;
  const float d = glm::length(b.center);
  return d > 0 ? d : 1.0f;
}

void resolve_environment_sphere(const Dataset& dataset, TrainConfig& config) {
  IntrinsicSettings& in = config.intrinsic;
  if (!(in.env_distance > 0) || in.env_radius > 0 || dataset.train.empty()) return;
  const CameraFocus f = camera_focus(cameras_of(dataset.train));
  if (!(f.mean_distance > 0)) throw Error(config.input.data, "the training cameras all sit at the point they look at");
  in.env_center = f.center;
  in.env_radius = in.env_distance * f.mean_distance;
}

GaussianModel initial_model(const Dataset& dataset, const TrainConfig& config, Device device, std::string* how) {
  GaussianInit init;
  init.roughness = config.intrinsic.init_roughness;
  init.fresnel = config.intrinsic.init_fresnel;
  if (!config.init.model.empty()) {
    const GaussianPly ply = read_gaussians(config.init.model);
    if (ply.count == 0) throw Error(config.init.model, "the model to start from holds no Gaussians");
    if (how) *how = std::to_string(ply.count) + " Gaussians from " + config.init.model;
    return GaussianModel::from_ply(ply, device, init);
  }
  if (!dataset.points.xyz.empty()) {
    if (how) *how = std::to_string(dataset.points.size()) + " SfM points";
    return init_from_points(dataset.points.xyz, dataset.points.rgb, device, init);
  }
  const Box box = box_from_cameras(cameras_of(dataset.train), config.init.random_box_ratio);
  std::vector<glm::vec3> pts, cols;
  random_points(box, size_t(config.init.random_points), config.seed, pts, cols);
  if (how) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%d random points in the box [%.2f, %.2f] x [%.2f, %.2f] x [%.2f, %.2f]",
                  config.init.random_points, box.lo.x, box.hi.x, box.lo.y, box.hi.y, box.lo.z, box.hi.z);
    *how = buf;
  }
  return init_from_points(pts, cols, device, init);
}

}  // namespace goris
