// Cameras of NeRF-style transforms*.json files (shared by the NeRF-synthetic and instant-ngp loaders).
#include <cmath>

#include "core/io/loaders/loader_common.h"
#include "core/util/error.h"

namespace goris::loaders {

Camera camera_from_transforms(const TransformsIntrinsics& in, const glm::dmat4& c2w_gl, ImageSize file_size,
                              const std::filesystem::path& image, const std::string& json, const std::string& what) {
  Camera c;
  c.width = in.w.value_or(file_size.width);
  c.height = in.h.value_or(file_size.height);
  const double W = c.width, H = c.height;
  double fx = 0;
  if (in.fl_x) fx = *in.fl_x;
  else if (in.camera_angle_x) fx = 0.5 * W / std::tan(0.5 * *in.camera_angle_x);
  else throw Error(json, what + ": no focal length (neither 'fl_x' nor 'camera_angle_x')");
  double fy = fx;
  if (in.fl_y) fy = *in.fl_y;
  else if (in.camera_angle_y && !in.fl_x) fy = 0.5 * H / std::tan(0.5 * *in.camera_angle_y);
  c.fx = float(fx);
  c.fy = float(fy);
  c.cx = float(in.cx.value_or(0.5 * W));
  c.cy = float(in.cy.value_or(0.5 * H));
  c.dist.k1 = float(in.k1.value_or(0));
  c.dist.k2 = float(in.k2.value_or(0));
  c.dist.k3 = float(in.k3.value_or(0));
  c.dist.p1 = float(in.p1.value_or(0));
  c.dist.p2 = float(in.p2.value_or(0));
  // OpenGL camera axes (x right, y up, z back) -> OpenCV (x right, y down, z forward): flip y and z.
  const glm::dmat3 r_gl(c2w_gl);
  const glm::dmat3 r_cv(r_gl[0], -r_gl[1], -r_gl[2]);
  set_pose_from_c2w(c, r_cv, glm::dvec3(c2w_gl[3]), json, what);
  require_finite_camera(c, json, what);
  return fit_camera_to_image(c, file_size, image, json);
}

}  // namespace goris::loaders
