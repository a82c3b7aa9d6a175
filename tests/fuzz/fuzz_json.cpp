// libFuzzer target for the transforms*.json reader (NeRF-synthetic and instant-ngp) and the cameras built
// from it. Any input must give valid cameras or throw goris::Error; anything else is a bug.
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "core/io/loaders/loader_common.h"
#include "core/io/loaders/transforms_json.h"
#include "core/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const goris::TransformsFile tf = goris::parse_transforms_json(data, size, "transforms.json");
    for (const auto& f : tf.frames) {
      const goris::TransformsIntrinsics in = tf.intrinsics.overridden_by(f.intrinsics);
      const goris::Camera c =
          goris::loaders::camera_from_transforms(in, f.c2w, {64, 48}, "image.png", "transforms.json", "frame");
      if (c.width != 64 || c.height != 48) std::abort();
      if (!std::isfinite(c.t.x) || !std::isfinite(c.t.y) || !std::isfinite(c.t.z)) std::abort();
    }
  } catch (const goris::Error&) {
  }
  return 0;
}
