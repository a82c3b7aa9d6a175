#include "ui/display/model_snapshot.h"

#include <vector>

#include "core/compute/parallel_for.h"
#include "core/scene/gaussian_kernels.h"

namespace goris::ui {

ModelSnapshot::ModelSnapshot(const GaussianModel& model, int iteration, const RasterSettings& settings,
                             std::shared_ptr<const ShadingSource> shading,
                             std::shared_ptr<const std::string> renderer_state)
    : device_(model.device()),
      count_(model.count()),
      iteration_(iteration),
      sh_degree_(model.sh_degree),
      max_sh_degree_(model.max_sh_degree),
      settings_(settings),
      shading_(std::move(shading)),
      renderer_state_(std::move(renderer_state)) {
  positions_ = model.tensor(Param::Position).value.copy_to(device_);
  log_scales_ = model.tensor(Param::LogScale).value.copy_to(device_);
  rotations_ = model.tensor(Param::Rotation).value.copy_to(device_);
  opacity_logits_ = model.tensor(Param::OpacityLogit).value.copy_to(device_);
  sh_ = model.tensor(Param::Sh).value.copy_to(device_);
  extra_logits_ = model.tensor(Param::ExtraLogit).value.copy_to(device_);
  if (model.filter3d_var.size() == count_ && count_ > 0) filter3d_var_ = model.filter3d_var.copy_to(device_);
  // Activation on the host keeps this file free of device code; the extras are a small part of the model.
  std::vector<float> logits = model.tensor(Param::ExtraLogit).value.to_host();
  std::vector<float> activated(logits.size());
  const float* in = logits.data();
  float* out = activated.data();
  parallel_for(Device::CPU, logits.size(), [=](size_t i) { kernels::extras_forward(in, out, i); });
  extras_ = Buffer<float>(activated, device_);
}

GaussianView ModelSnapshot::view() const {
  GaussianView v;
  v.count = int(count_);
  v.positions = positions_.data();
  v.log_scales = log_scales_.data();
  v.rotations = rotations_.data();
  v.opacity_logits = opacity_logits_.data();
  v.sh = sh_.data();
  v.sh_degree = sh_degree_;
  v.extras = extras_.data();
  v.n_extras = extra::kCount;
  v.filter3d_var = filter3d_var_.empty() ? nullptr : filter3d_var_.data();
  return v;
}

Buffer<float> ModelSnapshot::opacity_logits_hiding(const std::vector<std::uint8_t>& hidden) const {
  std::vector<float> v = opacity_logits_.to_host();
  for (size_t i = 0; i < v.size() && i < hidden.size(); ++i)
    if (hidden[i]) v[i] = -30.0f;
  return Buffer<float>(v, device_);
}

GaussianModel ModelSnapshot::to_model() const {
  GaussianModel m(device_);
  m.allocate(count_);
  m.sh_degree = sh_degree_;
  m.max_sh_degree = max_sh_degree_;
  const std::pair<Param, const Buffer<float>*> values[] = {
      {Param::Position, &positions_}, {Param::LogScale, &log_scales_}, {Param::Rotation, &rotations_},
      {Param::OpacityLogit, &opacity_logits_}, {Param::Sh, &sh_},     {Param::ExtraLogit, &extra_logits_}};
  for (const auto& [p, b] : values)
    if (b->size() > 0) device_copy(m.values(p), device_, b->data(), device_, b->bytes());
  if (!filter3d_var_.empty()) m.filter3d_var = filter3d_var_.copy_to(device_);
  return m;
}

}  // namespace goris::ui
