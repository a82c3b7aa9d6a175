#pragma once
// Turning a data set and a training configuration into what the trainer consumes: the loading options,
// the training images (planar, on the host), the scene extent and the initial Gaussians.
#include <functional>
#include <string>
#include <vector>

#include "core/io/dataset.h"
#include "core/io/image.h"
#include "train/config/train_config.h"
#include "train/loop/trainer.h"

namespace goris {

// DatasetOptions matching the configuration (background, downscale or target width).
DatasetOptions dataset_options(const TrainConfig& config);

// Planar RGB [3][H][W] on the host from an RGB image (any device), and back (an RGB image on the CPU).
std::vector<float> to_planar_rgb(const Image& image);
Image from_planar(const float* planar, int channels, int width, int height);

// Loads every view's image (composited on the configured background, at the configured size).
// `on_view` (optional) is told each view index as it loads, for progress display.
std::vector<TrainView> load_train_views(const std::vector<View>& views, const DatasetOptions& options,
                                        const std::function<void(size_t, size_t)>& on_view = {});

// The 3DGS scene extent: 1.1 x the largest distance of a training camera from their mean.
float scene_extent(const Dataset& dataset);

// intrinsic.env_distance > 0 and no sphere yet (env_radius 0): places the environment's sphere around the
// point the training cameras look at, radius env_distance x their mean distance to it (IntrinsicSettings).
void resolve_environment_sphere(const Dataset& dataset, TrainConfig& config);

// The initial model on `device`: config.init.model when given (throws goris::Error naming the file when it
// cannot be read or is empty), else the data set's SfM points when it has some, otherwise
// config.init.random_points random points in the box the training cameras look at (seeded by config.seed).
// `how` receives a one-line description for the user.
GaussianModel initial_model(const Dataset& dataset, const TrainConfig& config, Device device, std::string* how = nullptr);

}  // namespace goris
