#include "core/io/loaders/camera_warnings.h"

#include <map>
#include <string>

namespace goris::loaders {

void add_camera_warnings(Dataset& d) {
  const std::string file = d.source.string();
  if (d.train.size() == 1)
    d.warnings.push_back(file + ": only one training view; Gaussians need several viewpoints to be placed in depth");
  if (d.train.size() > 1) {
    const SceneBounds b = camera_bounds(d.train);
    if (!(b.radius > 1e-6f))
      d.warnings.push_back(file + ": all " + std::to_string(d.train.size()) +
                           " training cameras are at the same position: the scene's extent is zero (nothing to "
                           "triangulate; the random initial points fill no volume)");
  }
  std::map<std::string, int> uses;
  for (const auto* split : {&d.train, &d.test})
    for (const View& v : *split) ++uses[v.image.lexically_normal().string()];
  for (const auto& [image, n] : uses)
    if (n > 1) d.warnings.push_back(file + ": " + image + " is listed " + std::to_string(n) + " times");
}

}  // namespace goris::loaders
