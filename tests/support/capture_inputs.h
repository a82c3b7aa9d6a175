#pragma once
// Inputs of the capture tests: a folder of noise photos, and a short video (write_orbit_clip) of a
// rendered scene's training views at one band of heights (neighbours overlap), in orbit order by azimuth,
// resized to size x size and written by OpenCV as MPEG-4; it returns the number of frames written (0 when
// OpenCV cannot write the file).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "core/io/dataset.h"

namespace goris::test {

// A folder with `n` small noise photos (images, but nothing COLMAP could map).
inline std::filesystem::path photo_folder(const std::filesystem::path& dir, int n) {
  std::filesystem::create_directories(dir);
  for (int i = 0; i < n; ++i) {
    cv::Mat img(40, 60, CV_8UC3);
    cv::randu(img, cv::Scalar::all(0), cv::Scalar::all(255));
    cv::imwrite((dir / ("p" + std::to_string(i) + ".png")).string(), img);
  }
  return dir;
}

inline int write_orbit_clip(const Dataset& scene, const std::filesystem::path& clip, int size = 200,
                            float min_height = 1.5f) {
  std::vector<const View*> views;
  for (const View& v : scene.train)
    if (v.camera.center().z > min_height) views.push_back(&v);
  std::sort(views.begin(), views.end(), [](const View* a, const View* b) {
    const glm::vec3 ca = a->camera.center(), cb = b->camera.center();
    return std::atan2(ca.y, ca.x) < std::atan2(cb.y, cb.x);
  });
  cv::VideoWriter writer(clip.string(), cv::VideoWriter::fourcc('m', 'p', '4', 'v'), 12, cv::Size(size, size));
  if (!writer.isOpened()) return 0;
  for (const View* v : views) {
    cv::Mat img = cv::imread(v->image.string(), cv::IMREAD_COLOR), resized;
    cv::resize(img, resized, cv::Size(size, size), 0, 0, cv::INTER_AREA);
    writer.write(resized);
  }
  writer.release();
  return int(views.size());
}

}  // namespace goris::test
