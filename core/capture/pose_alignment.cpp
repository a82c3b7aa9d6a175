#include "core/capture/pose_alignment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <opencv2/core.hpp>

#include "core/util/error.h"

namespace goris::capture {

Similarity fit_similarity(const std::vector<glm::dvec3>& from, const std::vector<glm::dvec3>& to) {
  const size_t n = from.size();
  if (n < 3 || to.size() != n) throw Error("fit_similarity: needs at least 3 point pairs");
  glm::dvec3 mf(0.0), mt(0.0);
  for (size_t i = 0; i < n; ++i) mf += from[i], mt += to[i];
  mf /= double(n), mt /= double(n);
  cv::Matx33d cov = cv::Matx33d::zeros();
  double var_from = 0;
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 a = from[i] - mf, b = to[i] - mt;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) cov(r, c) += b[r] * a[c];
    var_from += glm::dot(a, a);
  }
  cov *= 1.0 / double(n);
  var_from /= double(n);
  cv::Mat w, u, vt;
  cv::SVD::compute(cv::Mat(cov), w, u, vt);
  cv::Matx33d U(u), Vt(vt), S = cv::Matx33d::eye();
  if (cv::determinant(U) * cv::determinant(Vt) < 0) S(2, 2) = -1;  // a rotation, not a reflection
  const cv::Matx33d R = U * S * Vt;
  const double trace = w.at<double>(0) * S(0, 0) + w.at<double>(1) * S(1, 1) + w.at<double>(2) * S(2, 2);
  Similarity sim;
  sim.scale = var_from > 0 ? trace / var_from : 1.0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) sim.rotation[c][r] = R(r, c);  // glm is column-major
  sim.translation = mt - sim.scale * (sim.rotation * mf);
  return sim;
}

PoseComparison compare_poses(const Dataset& captured, const Dataset& given, const std::string& given_name) {
  // A name that two given views share (GOR-IS train and test views) cannot be matched: left out.
  std::map<std::string, const Camera*> given_by_name;
  std::map<std::string, int> uses;
  for (const auto* views : {&given.train, &given.test})
    for (const View& v : *views) given_by_name.emplace(v.name, &v.camera), ++uses[v.name];
  for (const auto& [name, n] : uses)
    if (n > 1) given_by_name.erase(name);
  PoseComparison c;
  c.given = int(given_by_name.size());
  std::vector<glm::dvec3> from, to, dir_from, dir_to;
  for (const auto* views : {&captured.train, &captured.test})
    for (const View& v : *views) {
      auto it = given_by_name.find(v.name);
      if (it == given_by_name.end()) continue;
      from.push_back(glm::dvec3(v.camera.center()));
      to.push_back(glm::dvec3(it->second->center()));
      dir_from.push_back(glm::dvec3(v.camera.forward()));
      dir_to.push_back(glm::dvec3(it->second->forward()));
    }
  c.matched = int(from.size());
  if (c.matched < 3)
    throw Error(given_name, "only " + std::to_string(c.matched) + " of its image names are in the capture: nothing to compare");
  c.alignment = fit_similarity(from, to);
  glm::dvec3 mean(0.0);
  for (const auto& p : to) mean += p;
  mean /= double(to.size());
  double radius = 0;
  for (const auto& p : to) radius = std::max(radius, glm::length(p - mean));
  c.extent = 2 * radius;
  for (size_t i = 0; i < from.size(); ++i) {
    const double e = glm::length(c.alignment.apply(from[i]) - to[i]) / c.extent;
    c.mean_error += e;
    c.max_error = std::max(c.max_error, e);
    const double cosang = std::clamp(glm::dot(glm::normalize(c.alignment.rotation * dir_from[i]), glm::normalize(dir_to[i])), -1.0, 1.0);
    c.mean_angle_deg += std::acos(cosang) * 180.0 / M_PI;
  }
  c.mean_error /= double(from.size());
  c.mean_angle_deg /= double(from.size());
  return c;
}

std::string comparison_text(const PoseComparison& c) {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "poses: %d of %d given views matched by name; after a similarity alignment the camera centres are "
                "%.2f %% (mean) / %.2f %% (largest) of the scene extent from the given ones, viewing directions %.2f deg apart (mean)\n",
                c.matched, c.given, 100 * c.mean_error, 100 * c.max_error, c.mean_angle_deg);
  return buf;
}

}  // namespace goris::capture
