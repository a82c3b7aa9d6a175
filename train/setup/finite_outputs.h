#pragma once
// Are a run's outputs finite? The stability bench's verdict (`goris bench stability`): every parameter of
// the latest checkpoint (values and Adam moments, the 3D filter), point_cloud.ply, the renderer's own
// parameters (environment map and roughness net of an intrinsic run) and the metrics of `goris eval`.
// Each check returns "FILE: what is not finite" lines; none = finite. A file that cannot be read at all is
// a problem too (a half-written or corrupted output is no better than a NaN).
#include <filesystem>
#include <string>
#include <vector>

#include "core/scene/gaussians.h"

namespace goris {

// Non-finite values per parameter array of `model` (any device), named "WHAT: parameter 'sh' value has 3
// non-finite values (first at Gaussian 17)".
std::vector<std::string> model_finite_problems(const GaussianModel& model, const std::string& what);

// point_cloud.ply-style file: read back, where NaN / Inf are refused naming the vertex and property.
std::vector<std::string> ply_finite_problems(const std::filesystem::path& ply);

// metrics.json of `goris eval`: psnr and ssim must be numbers (a NaN render makes them null), the masked
// ones too when masked views were evaluated, and its count of non-finite rendered values must be 0.
std::vector<std::string> metrics_finite_problems(const std::filesystem::path& metrics_json);

struct RunFiniteReport {
  std::vector<std::string> checked;   // files looked at
  std::vector<std::string> problems;  // empty = every checked output is finite
  bool has_checkpoint = false;
  int skipped_steps = 0;  // training steps skipped for non-finite values (the latest checkpoint's count)
};

// The outputs a run folder (a stage-1 run or RUN/removal) holds now: the latest checkpoint with its
// renderer state, point_cloud.ply and the metrics files of `goris eval` (metrics*.json); what is absent is
// not checked (a step that did not finish is reported by its caller).
RunFiniteReport check_run_finite(const std::filesystem::path& run_dir);

}  // namespace goris
