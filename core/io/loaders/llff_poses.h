#pragma once
// LLFF's poses_bounds.npy: N rows of 17 values, a 3x5 matrix [R | t | (h, w, f)] in row-major order whose
// rotation columns are the camera's (down, right, back) axes in world coordinates and whose (h, w, f) are
// the image size and focal length of the ORIGINAL images, then the near and far depth bounds.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/io/npy.h"

namespace goris {

struct LlffPose {
  glm::dmat3 c2w_llff{1.0};  // columns: down, right, back
  glm::dvec3 center{0.0};
  double height = 0, width = 0, focal = 0;  // of the images the poses were computed on
  double near = 0, far = 0;
};

// Throws goris::Error(name_for_errors, ...) unless `a` is N x 17 (N >= 1) of finite values with positive
// h, w, f.
std::vector<LlffPose> llff_poses_from_npy(const NpyArray& a, const std::string& name_for_errors);

}  // namespace goris
