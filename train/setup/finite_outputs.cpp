#include "train/setup/finite_outputs.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include <nlohmann/json.hpp>

#include "core/io/file_bytes.h"
#include "core/io/ply.h"
#include "train/intrinsic/intrinsic_renderer.h"
#include "train/loop/checkpoint.h"
#include "train/run/run_folder.h"
#include "train/setup/run_renderer.h"

namespace goris {
namespace fs = std::filesystem;

namespace {

// "NAME has N non-finite values (first at UNIT i)" for a host or device array, or "" when all are finite.
std::string non_finite_text(const Buffer<float>& b, size_t width, const std::string& name, const char* unit) {
  const std::vector<float> v = b.to_host();
  size_t bad = 0, first = 0;
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]) && bad++ == 0) first = i;
  if (bad == 0) return {};
  return name + " has " + std::to_string(bad) + " non-finite value" + (bad == 1 ? "" : "s") + " (first at " + unit +
         " " + std::to_string(first / std::max<size_t>(width, 1)) + ")";
}

void add_renderer_problems(const fs::path& run_dir, const fs::path& checkpoint, RunFiniteReport& r) {
  const fs::path state = renderer_state_path(checkpoint);
  if (!fs::exists(state)) return;  // a radiance run owns no parameters
  r.checked.push_back(state.string());
  try {
    const TrainConfig config = read_run_config(run_dir);
    // The extent only sets the ray offset of shading, not the loaded parameters.
    auto renderer = make_renderer(config, 1.0f, Device::CPU);
    Trainer::load_renderer_state(checkpoint, *renderer);
    if (IntrinsicRenderer* in = as_intrinsic(renderer.get())) {
      for (const auto& [buf, name] : {std::pair{&in->environment().params(), "environment map"},
                                      std::pair{&in->net().params(), "roughness net"}}) {
        const std::string t = non_finite_text(*buf, 1, name, "value");
        if (!t.empty()) r.problems.push_back(state.string() + ": " + t);
      }
    }
  } catch (const std::exception& e) {  // loading refuses non-finite parameters, or the file is broken
    r.problems.push_back(state.string() + ": " + e.what());
  }
}

}  // namespace

std::vector<std::string> model_finite_problems(const GaussianModel& model, const std::string& what) {
  std::vector<std::string> out;
  for (int p = 0; p < kParamCount; ++p) {
    const ParamTensor& t = model.tensor(Param(p));
    const std::string name = std::string("parameter '") + param_name(Param(p)) + "'";
    for (const auto& [buf, part] : {std::pair{&t.value, " value"}, std::pair{&t.adam_m, " Adam first moment"},
                                    std::pair{&t.adam_v, " Adam second moment"}}) {
      const std::string text = non_finite_text(*buf, size_t(t.width), name + part, "Gaussian");
      if (!text.empty()) out.push_back(what + ": " + text);
    }
  }
  const std::string f = non_finite_text(model.filter3d_var, 1, "3D filter variance", "Gaussian");
  if (!f.empty()) out.push_back(what + ": " + f);
  return out;
}

std::vector<std::string> ply_finite_problems(const fs::path& ply) {
  try {
    read_ply(ply);
    return {};
  } catch (const std::exception& e) {
    return {e.what()};  // names the file, and for NaN / Inf the vertex and the property
  }
}

std::vector<std::string> metrics_finite_problems(const fs::path& metrics_json) {
  const std::string name = metrics_json.string();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_text_file(metrics_json), nullptr, false);
  } catch (const std::exception& e) {
    return {e.what()};
  }
  if (j.is_discarded() || !j.is_object()) return {name + ": not a JSON object"};
  std::vector<std::string> out;
  auto need_number = [&](const nlohmann::json& o, const char* key, const std::string& label) {
    if (!o.contains(key) || !o[key].is_number() || !std::isfinite(o[key].get<double>()))
      out.push_back(name + ": " + label + " is not a finite number (" + (o.contains(key) ? o[key].dump() : "missing") +
                    ")");
  };
  need_number(j, "psnr", "psnr");
  need_number(j, "ssim", "ssim");
  if (j.contains("masked") && j["masked"].is_object() && j["masked"].value("views", 0) > 0) {
    need_number(j["masked"], "psnr", "masked psnr");
    need_number(j["masked"], "ssim", "masked ssim");
  }
  if (j.contains("non_finite_values") && !(j["non_finite_values"].is_number() && j["non_finite_values"] == 0))
    out.push_back(name + ": the rendered test images hold " + j["non_finite_values"].dump() + " non-finite values");
  return out;
}

RunFiniteReport check_run_finite(const fs::path& run_dir) {
  RunFiniteReport r;
  auto add = [&r](const std::vector<std::string>& p) { r.problems.insert(r.problems.end(), p.begin(), p.end()); };
  if (const auto ck = latest_checkpoint(run_dir)) {
    r.checked.push_back(ck->string());
    r.has_checkpoint = true;
    try {
      const Checkpoint c = read_checkpoint(*ck, Device::CPU);
      r.skipped_steps = c.state.skipped_steps;
      if (!std::isfinite(c.state.lr_scale))
        r.problems.push_back(ck->string() + ": the learning-rate scale is not finite");
      add(model_finite_problems(c.state.model, ck->string()));
    } catch (const std::exception& e) {
      r.problems.push_back(e.what());
    }
    add_renderer_problems(run_dir, *ck, r);
  }
  if (const fs::path ply = run_ply_path(run_dir); fs::exists(ply)) {
    r.checked.push_back(ply.string());
    add(ply_finite_problems(ply));
  }
  std::vector<fs::path> metrics;  // metrics.json, metrics_full.json...: every evaluation of the run
  for (const auto& e : fs::directory_iterator(run_dir)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("metrics", 0) == 0 && e.path().extension() == ".json") metrics.push_back(e.path());
  }
  std::sort(metrics.begin(), metrics.end());
  for (const fs::path& m : metrics) {
    r.checked.push_back(m.string());
    add(metrics_finite_problems(m));
  }
  return r;
}

}  // namespace goris
