#pragma once
// Data sets that load but cannot train well: one training view, every training camera at one place (a
// zero-volume scene extent: nothing to triangulate, random points in a point), the same image listed
// twice. Each becomes a warning in Dataset::warnings naming the camera file.
#include "core/io/dataset.h"

namespace goris::loaders {

void add_camera_warnings(Dataset& d);

}  // namespace goris::loaders
