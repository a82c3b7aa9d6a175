#include "app/bench/bench_pipeline.h"

#include <algorithm>
#include <cmath>

namespace goris::bench::pipeline {

json row_json(const Row& r) {
  return {{"scene", r.scene},       {"config", r.config},         {"schedule", r.schedule},   {"status", r.status},
          {"error", r.error},       {"device", r.device},         {"train_iters", r.train_iters},
          {"remove_iters", r.remove_iters}, {"gaussians", r.gaussians}, {"psnr", r.psnr},  {"ssim", r.ssim},
          {"m_psnr", r.m_psnr},     {"m_ssim", r.m_ssim},         {"train_s", r.train_s},     {"select_s", r.select_s},
          {"remove_s", r.remove_s}, {"export_s", r.export_s},     {"eval_s", r.eval_s},       {"peak_mib", r.peak_mib},
          {"peak_device_mib", r.peak_device_mib}, {"cpu_s", r.cpu_s},       {"remove_steps", r.remove_steps}, {"note", r.note},
          {"region_psnr", r.region_psnr}, {"region_ssim", r.region_ssim}, {"region_flip", r.region_flip},
          {"flip", r.flip}, {"ghost_ratio", r.ghost_ratio}, {"ghost_floor", r.ghost_floor},
          {"stage1_glossy_share", r.stage1_glossy_share}};
}

Row row_from_json(const json& j) {
  Row r;
  auto s = [&](const char* k) { return j.value(k, std::string()); };
  auto d = [&](const char* k) { return j.contains(k) && j[k].is_number() ? j[k].get<double>() : std::nan(""); };
  r.scene = s("scene"), r.config = s("config"), r.schedule = s("schedule"), r.status = s("status");
  r.error = s("error"), r.device = s("device"), r.note = s("note");
  r.train_iters = j.value("train_iters", 0), r.remove_iters = j.value("remove_iters", 0);
  r.gaussians = d("gaussians"), r.psnr = d("psnr"), r.ssim = d("ssim"), r.m_psnr = d("m_psnr"), r.m_ssim = d("m_ssim");
  r.train_s = d("train_s"), r.select_s = d("select_s"), r.remove_s = d("remove_s"), r.export_s = d("export_s");
  r.eval_s = d("eval_s"), r.peak_mib = d("peak_mib"), r.cpu_s = d("cpu_s");
  r.region_psnr = d("region_psnr"), r.region_ssim = d("region_ssim"), r.region_flip = d("region_flip");
  r.flip = d("flip"), r.ghost_ratio = d("ghost_ratio"), r.ghost_floor = d("ghost_floor");
  r.stage1_glossy_share = d("stage1_glossy_share");
  r.peak_device_mib = j.contains("peak_device_mib") ? d("peak_device_mib") : 0.0;
  if (j.contains("remove_steps") && j["remove_steps"].is_object())
    for (auto it = j["remove_steps"].begin(); it != j["remove_steps"].end(); ++it)
      if (it.value().is_number()) r.remove_steps[it.key()] = it.value().get<double>();
  return r;
}


// The host and device peaks of a row so far and those of one more step.
void add_peaks(Row& r, const StepRun& step) {
  r.peak_mib = std::max(r.peak_mib, step.peak_mib);
  r.peak_device_mib = std::max(r.peak_device_mib, step.peak_device_mib);
}

// The device peak as a table cell: `none` when no step used GPU memory.
std::string device_mib(const Row& r, const std::string& none) {
  return r.peak_device_mib > 0 ? fmt(r.peak_device_mib, "%.0f") : none;
}

// "remove_STEP_s": the results table's column of a removal step.
std::string step_column(std::string step) {
  std::replace(step.begin(), step.end(), ' ', '_');
  std::replace(step.begin(), step.end(), '-', '_');
  return "remove_" + step + "_s";
}

}  // namespace goris::bench::pipeline
