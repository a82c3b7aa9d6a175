// COLMAP sparse models: binary and text agree, every supported model, detection, and every bad input.
#include <gtest/gtest.h>

#include "core/io/dataset.h"
#include "core/io/file_bytes.h"
#include "core/io/loaders/colmap_model.h"
#include "tests/support/test_support.h"
#include "tests/unit/colmap_test_writer.h"
#include "tests/unit/io_test_util.h"

namespace goris {
namespace {
namespace fs = std::filesystem;
using test::expect_error;

ColmapSparseModel tiny_model() {
  ColmapSparseModel m;
  m.cameras = {test::colmap_camera(1, ColmapModel::SimplePinhole, 32, 24, {30, 16, 12}),
               test::colmap_camera(2, ColmapModel::Pinhole, 32, 24, {30, 31, 15.5, 12.25}),
               test::colmap_camera(3, ColmapModel::SimpleRadial, 32, 24, {29, 16, 12, 0.01}),
               test::colmap_camera(4, ColmapModel::Radial, 32, 24, {28, 16, 12, 0.02, -0.003}),
               test::colmap_camera(7, ColmapModel::OpenCV, 32, 24, {27, 28, 16.5, 11.5, 0.1, -0.2, 0.001, -0.002})};
  const double s = std::sqrt(0.5);
  // Registration order differs from name order on purpose.
  m.images = {test::colmap_image(5, 7, "e.png", {1, 0, 0, 0}, {0.1, 0.2, 4}),
              test::colmap_image(1, 1, "a.png", {s, 0, s, 0}, {0, 0, 5}),
              test::colmap_image(2, 2, "b.png", {0.9, 0.1, -0.2, 0.3}, {1, -2, 3}),
              test::colmap_image(3, 3, "c.png", {2, 0, 0, 0}, {0, 0, 3}),  // not normalised
              test::colmap_image(4, 4, "d.png", {0.5, 0.5, 0.5, 0.5}, {-1, 0, 6})};
  m.points.resize(3);
  for (int i = 0; i < 3; ++i) {
    m.points[i].id = uint64_t(10 + i);
    m.points[i].xyz[0] = 0.25 * i, m.points[i].xyz[1] = -1.5, m.points[i].xyz[2] = 3.0 + i;
    m.points[i].rgb[0] = uint8_t(10 * i), m.points[i].rgb[1] = 128, m.points[i].rgb[2] = 255;
  }
  return m;
}

fs::path make_scene(const std::string& name, bool binary, const ColmapSparseModel& m = tiny_model()) {
  const auto dir = test::scratch_dir(name);
  test::write_colmap_model(dir / "sparse/0", m, binary);
  for (const auto& im : m.images) test::write_png(dir / "images" / im.name, 32, 24);
  return dir;
}

void expect_same_cameras(const Camera& a, const Camera& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_FLOAT_EQ(a.fx, b.fx);
  EXPECT_FLOAT_EQ(a.fy, b.fy);
  EXPECT_FLOAT_EQ(a.cx, b.cx);
  EXPECT_FLOAT_EQ(a.cy, b.cy);
  EXPECT_FLOAT_EQ(a.dist.k1, b.dist.k1);
  EXPECT_FLOAT_EQ(a.dist.k2, b.dist.k2);
  EXPECT_FLOAT_EQ(a.dist.p1, b.dist.p1);
  EXPECT_FLOAT_EQ(a.dist.p2, b.dist.p2);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(a.t[c], b.t[c], 1e-6);
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(a.R[c][r], b.R[c][r], 1e-6);
  }
}

TEST(DatasetColmap, TextAndBinaryLoadersAgree) {
  const auto bin = make_scene("colmap_rt_bin", true), txt = make_scene("colmap_rt_txt", false);
  bool is_binary = false;
  const ColmapSparseModel mb = read_colmap_model(bin / "sparse/0", &is_binary);
  EXPECT_TRUE(is_binary);
  const ColmapSparseModel mt = read_colmap_model(txt / "sparse/0", &is_binary);
  EXPECT_FALSE(is_binary);
  const ColmapSparseModel ref = tiny_model();
  for (const auto* m : {&mb, &mt}) {
    ASSERT_EQ(m->cameras.size(), 5u);
    ASSERT_EQ(m->images.size(), 5u);
    ASSERT_EQ(m->points.size(), 3u);
    for (size_t i = 0; i < 5; ++i) {
      EXPECT_EQ(m->cameras[i].id, ref.cameras[i].id);
      EXPECT_EQ(m->cameras[i].model, ref.cameras[i].model);
      EXPECT_EQ(m->cameras[i].params, ref.cameras[i].params);  // %.17g text round-trips doubles exactly
      EXPECT_EQ(m->images[i].name, ref.images[i].name);
      EXPECT_EQ(m->images[i].camera_id, ref.images[i].camera_id);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(m->images[i].qvec[k], ref.images[i].qvec[k]);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(m->images[i].tvec[k], ref.images[i].tvec[k]);
    }
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(m->points[i].id, ref.points[i].id);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(m->points[i].xyz[k], ref.points[i].xyz[k]);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(m->points[i].rgb[k], ref.points[i].rgb[k]);
    }
  }
  DatasetOptions o;
  o.test_every = 0;
  const Dataset db = load_dataset(bin, o), dt = load_dataset(txt, o);
  EXPECT_EQ(db.format, "colmap-binary");
  EXPECT_EQ(dt.format, "colmap-text");
  ASSERT_EQ(db.train.size(), 5u);
  ASSERT_EQ(dt.train.size(), 5u);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(db.train[i].name, dt.train[i].name);
    expect_same_cameras(db.train[i].camera, dt.train[i].camera);
  }
  ASSERT_EQ(db.points.size(), 3u);
  EXPECT_EQ(db.points.xyz[2], dt.points.xyz[2]);
  EXPECT_EQ(db.points.xyz[2], glm::vec3(0.5f, -1.5f, 5.0f));
  EXPECT_NEAR(db.points.rgb[1].x, 10 / 255.0f, 1e-7);
  EXPECT_EQ(db.points.rgb[1].z, 1.0f);
}

TEST(DatasetColmap, ModelsMapToIntrinsicsAndDistortion) {
  DatasetOptions o;
  o.test_every = 0;
  const Dataset d = load_dataset(make_scene("colmap_models", true), o);
  // Sorted by name: a (SIMPLE_PINHOLE), b (PINHOLE), c (SIMPLE_RADIAL), d (RADIAL), e (OPENCV).
  ASSERT_EQ(d.train.size(), 5u);
  const Camera &a = d.train[0].camera, &b = d.train[1].camera, &c = d.train[2].camera, &r = d.train[3].camera,
               &e = d.train[4].camera;
  EXPECT_EQ(d.train[0].name, "a");
  EXPECT_FLOAT_EQ(a.fx, 30);
  EXPECT_FLOAT_EQ(a.fy, 30);
  EXPECT_FALSE(a.has_distortion());
  EXPECT_FLOAT_EQ(b.fy, 31);
  EXPECT_FLOAT_EQ(b.cx, 15.5f);
  EXPECT_FLOAT_EQ(b.cy, 12.25f);
  EXPECT_FLOAT_EQ(c.dist.k1, 0.01f);
  EXPECT_FLOAT_EQ(c.dist.k2, 0);
  EXPECT_FLOAT_EQ(r.dist.k1, 0.02f);
  EXPECT_FLOAT_EQ(r.dist.k2, -0.003f);
  EXPECT_FLOAT_EQ(e.fx, 27);
  EXPECT_FLOAT_EQ(e.fy, 28);
  EXPECT_FLOAT_EQ(e.dist.p1, 0.001f);
  EXPECT_FLOAT_EQ(e.dist.p2, -0.002f);
  // The unnormalised quaternion of c is normalised: identity rotation.
  EXPECT_NEAR(glm::length(c.R * glm::vec3(1, 2, 3) - glm::vec3(1, 2, 3)), 0, 1e-6);
  // Rotations are orthonormal.
  const glm::mat3 should_be_identity = glm::transpose(b.R) * b.R;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(should_be_identity[i][i], 1, 1e-6);
}

TEST(DatasetColmap, DetectionAndLayouts) {
  const auto dir = make_scene("colmap_detect", true);
  EXPECT_EQ(detect_dataset_format(dir), "colmap-binary");
  EXPECT_EQ(load_dataset(dir / "sparse/0").view_count(), 5u);
  EXPECT_EQ(load_dataset(dir / "sparse/0/cameras.bin").view_count(), 5u);
  // sparse/ without 0/
  fs::rename(dir / "sparse/0", dir / "tmp");
  fs::remove_all(dir / "sparse");
  fs::rename(dir / "tmp", dir / "sparse");
  EXPECT_EQ(load_dataset(dir).view_count(), 5u);
  const auto txt = make_scene("colmap_detect_txt", false);
  EXPECT_EQ(detect_dataset_format(txt / "sparse/0/images.txt"), "colmap-text");
}

TEST(DatasetColmap, SplitAndDownscaledImages) {
  ColmapSparseModel m = tiny_model();
  m.images.clear();
  for (int i = 0; i < 17; ++i) m.images.push_back(test::colmap_image(uint32_t(i + 1), 2, "img" + std::to_string(100 + i) + ".png", {1, 0, 0, 0}, {0, 0, 4}));
  const auto dir = test::scratch_dir("colmap_split");
  test::write_colmap_model(dir / "sparse/0", m, true);
  for (const auto& im : m.images) test::write_png(dir / "images" / im.name, 16, 12);  // half the declared 32x24
  const Dataset d = load_dataset(dir);
  ASSERT_EQ(d.test.size(), 3u);  // 0, 8, 16
  EXPECT_EQ(d.test[1].name, "img108");
  EXPECT_EQ(d.train.size(), 14u);
  const Camera& c = d.train[0].camera;
  EXPECT_EQ(c.width, 16);
  EXPECT_FLOAT_EQ(c.fx, 15);
  EXPECT_FLOAT_EQ(c.cy, 6.125f);
}

// --- bad input -------------------------------------------------------------------------------------

TEST(DatasetColmap, TruncatedBinariesNameFileAndOffset) {
  const ColmapSparseModel m = tiny_model();
  const std::vector<uint8_t> files[3] = {test::colmap_cameras_bin(m.cameras), test::colmap_images_bin(m.images),
                                         test::colmap_points_bin(m.points)};
  for (int f = 0; f < 3; ++f) {
    for (size_t cut = 0; cut < files[f].size(); ++cut) {
      const uint8_t* p = files[f].data();
      const std::string msg = expect_error(
          [&] {
            if (f == 0) parse_colmap_cameras_bin(p, cut, "cameras.bin");
            if (f == 1) parse_colmap_images_bin(p, cut, "images.bin");
            if (f == 2) parse_colmap_points3d_bin(p, cut, "points3D.bin");
          },
          {".bin: ", "byte offset"});
      ASSERT_NE(msg.find("truncated"), std::string::npos) << "cut " << cut << ": " << msg;
    }
  }
}

TEST(DatasetColmap, InconsistentBinaries) {
  ColmapSparseModel m = tiny_model();
  auto cams = test::colmap_cameras_bin(m.cameras);
  cams[0] = 4;  // count says 4, the file has 5
  expect_error([&] { parse_colmap_cameras_bin(cams.data(), cams.size(), "cameras.bin"); },
               {"cameras.bin", "inconsistent", "bytes after the last camera", "byte offset"});
  // An image whose 2D point count runs past the end of the file.
  auto images = test::colmap_images_bin({m.images[0]}, 1);
  const size_t n2d_at = images.size() - 24 - 8;
  images[n2d_at + 5] = 0x40;  // a huge count
  expect_error([&] { parse_colmap_images_bin(images.data(), images.size(), "images.bin"); },
               {"images.bin", "truncated at byte offset", "image 5 ('e.png') declares"});
  // Duplicate ids.
  auto dup = test::colmap_cameras_bin({m.cameras[0], m.cameras[0]});
  expect_error([&] { parse_colmap_cameras_bin(dup.data(), dup.size(), "cameras.bin"); }, {"cameras.bin", "duplicate camera id 1"});
  // Zero width, zero focal length, zero quaternion.
  auto w0 = m.cameras[0];
  w0.width = 0;
  auto bytes = test::colmap_cameras_bin({w0});
  expect_error([&] { parse_colmap_cameras_bin(bytes.data(), bytes.size(), "cameras.bin"); }, {"cameras.bin", "byte offset 8", "invalid image size 0x24"});
  auto f0 = m.cameras[1];
  f0.params[1] = -1;
  bytes = test::colmap_cameras_bin({f0});
  expect_error([&] { parse_colmap_cameras_bin(bytes.data(), bytes.size(), "cameras.bin"); }, {"cameras.bin", "focal length"});
  auto q0 = m.images[0];
  q0.qvec[0] = 0;
  bytes = test::colmap_images_bin({q0});
  expect_error([&] { parse_colmap_images_bin(bytes.data(), bytes.size(), "images.bin"); }, {"images.bin", "zero rotation"});
}

TEST(DatasetColmap, UnknownAndUnsupportedCameraModels) {
  ColmapSparseModel m = tiny_model();
  auto cam = m.cameras[1];
  auto bytes = test::colmap_cameras_bin({cam});
  bytes[8 + 4] = 42;  // model id
  expect_error([&] { parse_colmap_cameras_bin(bytes.data(), bytes.size(), "cameras.bin"); },
               {"cameras.bin", "camera 2", "unknown camera model id 42"});
  bytes[8 + 4] = 5;
  expect_error([&] { parse_colmap_cameras_bin(bytes.data(), bytes.size(), "cameras.bin"); },
               {"cameras.bin", "OPENCV_FISHEYE (id 5)", "not supported"});
  expect_error([&] { parse_colmap_cameras_txt("3 WEIRD 10 10 1 2 3\n", "cameras.txt"); },
               {"cameras.txt", "line 1", "camera 3", "unknown camera model 'WEIRD'"});
  expect_error([&] { parse_colmap_cameras_txt("# c\n3 FULL_OPENCV 10 10 1 2 3 4 5 6 7 8 9 10 11 12\n", "cameras.txt"); },
               {"cameras.txt", "line 2", "FULL_OPENCV", "not supported"});
  // Through the loader: the error names the file in the data set.
  const auto dir = make_scene("colmap_unknown_model", false);
  test::write_text(dir / "sparse/0/cameras.txt", "1 FOV 32 24 30 16 12 0.5\n");
  expect_error([&] { load_dataset(dir); }, {"sparse/0/cameras.txt", "FOV", "not supported"});
}

TEST(DatasetColmap, MalformedText) {
  expect_error([&] { parse_colmap_cameras_txt("1 PINHOLE 10 10 1 2 3\n", "cameras.txt"); }, {"cameras.txt", "line 1", "missing a camera parameter"});
  expect_error([&] { parse_colmap_cameras_txt("1 PINHOLE 10 abc 1 2 3 4\n", "cameras.txt"); }, {"cameras.txt", "line 1", "HEIGHT", "'abc'"});
  expect_error([&] { parse_colmap_cameras_txt("1 PINHOLE 10 10 1 2 3 4 5\n", "cameras.txt"); }, {"cameras.txt", "too many parameters"});
  expect_error([&] { parse_colmap_images_txt("# x\n1 1 0 0 0 0 0 0 1\n", "images.txt"); }, {"images.txt", "line 2", "missing NAME"});
  expect_error([&] { parse_colmap_images_txt("1 1 0 0 0 0 0 0 1 a.png\n1 2\n", "images.txt"); }, {"images.txt", "line 2", "triples"});
  expect_error([&] { parse_colmap_images_txt("1 1 0 0 0 0 0 0 1 a.png\n\n1 1 0 0 0 0 0 0 1 b.png\n", "images.txt"); },
               {"images.txt", "line 3", "duplicate image id 1"});
  expect_error([&] { parse_colmap_points3d_txt("1 0 0 0 300 0 0 0.1\n", "points3D.txt"); }, {"points3D.txt", "line 1", "300", "0..255"});
  expect_error([&] { parse_colmap_points3d_txt("1 0 nan 0 3 0 0 0.1\n", "points3D.txt"); }, {"points3D.txt", "line 1", "non-finite"});
  // Names with spaces, CRLF line ends and images without a points line at the end are fine.
  const auto ims = parse_colmap_images_txt("1 1 0 0 0 0 0 0 1 my photo.png\r\n0 0 -1\r\n2 1 0 0 0 0 0 0 1 b.png", "images.txt");
  ASSERT_EQ(ims.size(), 2u);
  EXPECT_EQ(ims[0].name, "my photo.png");
  EXPECT_EQ(ims[1].name, "b.png");
}

TEST(DatasetColmap, MissingFilesAndReferences) {
  const auto dir = make_scene("colmap_missing", true);
  fs::remove(dir / "images/c.png");
  expect_error([&] { load_dataset(dir); }, {"sparse/0/images.bin", "image 3 ('c.png') not found", "images/c.png"});
  fs::remove_all(dir / "images");
  expect_error([&] { load_dataset(dir); }, {"colmap_missing/images", "images folder not found"});
  fs::remove(dir / "sparse/0/images.bin");
  expect_error([&] { load_dataset(dir); }, {"sparse/0/images.bin", "file not found"});

  ColmapSparseModel m = tiny_model();
  m.images[0].camera_id = 99;
  const auto bad_ref = make_scene("colmap_bad_ref", true, m);
  expect_error([&] { load_dataset(bad_ref); }, {"images.bin", "image 5 ('e.png') refers to camera 99", "cameras.bin"});

  // Values beyond single precision.
  m = tiny_model();
  m.images[1].tvec[2] = 1e200;
  const auto far = make_scene("colmap_far", true, m);
  expect_error([&] { load_dataset(far); }, {"images.bin", "image 1 ('a.png')", "camera position out of range"});

  // Zero images.
  m = tiny_model();
  m.images.clear();
  const auto empty = make_scene("colmap_zero", false, m);
  expect_error([&] { load_dataset(empty); }, {"images.txt", "no images"});

  // An image whose file has a different aspect ratio from its camera.
  const auto aspect = make_scene("colmap_aspect", true);
  test::write_png(aspect / "images/b.png", 24, 24);
  expect_error([&] { load_dataset(aspect); }, {"images/b.png", "24x24", "camera 2", "32x24"});
}

}  // namespace
}  // namespace goris
