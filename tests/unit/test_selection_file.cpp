// selection.json + selection.npy: round trip, and clear errors when the selection does not belong to the
// model (count, fingerprint) or the files disagree.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/io/file_bytes.h"
#include "core/io/npy.h"
#include "core/util/error.h"
#include "removal/selection/selection_file.h"
#include "test_selection_scene.h"
#include "tests/support/test_support.h"

namespace goris {
namespace {

using test::TestGaussian;

std::vector<TestGaussian> five() {
  std::vector<TestGaussian> g;
  for (int i = 0; i < 5; ++i) g.push_back(TestGaussian{{float(i), 0.0f, 0.0f}});
  return g;
}

SelectionRecord record_for(const GaussianModel& m) {
  SelectionRecord r;
  r.method = "labels";
  r.parameters["threshold"] = 0.3;
  r.summary["selected"] = 2;
  r.model_source = "checkpoints/iter_00000050.ckpt";
  r.model_fingerprint = model_fingerprint(m);
  return r;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SelectionFile, RoundTripAndNumpyLayout) {
  const std::filesystem::path run = test::scratch_dir("selection_file_roundtrip");
  const GaussianModel m = test::make_model(five());
  const SelectionMask mask{0, 1, 0, 7, 0};  // any non-zero is selected
  write_selection(selection_json_path(run), record_for(m), mask);
  ASSERT_TRUE(std::filesystem::exists(run / "selection.json"));
  ASSERT_TRUE(std::filesystem::exists(run / "selection.npy"));
  // Only the two files: the temporary files were renamed away.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(run), std::filesystem::directory_iterator()), 2);

  const StoredSelection s = read_selection(run, m);
  EXPECT_EQ(s.mask, (SelectionMask{0, 1, 0, 1, 0}));
  EXPECT_EQ(s.record.method, "labels");
  EXPECT_EQ(s.record.selected, 2u);
  EXPECT_EQ(s.record.gaussian_count, 5u);
  EXPECT_EQ(s.record.mask_file, "selection.npy");
  EXPECT_EQ(s.record.model_source, "checkpoints/iter_00000050.ckpt");
  EXPECT_DOUBLE_EQ(s.record.parameters["threshold"].get<double>(), 0.3);

  const NpyArray a = load_npy(run / "selection.npy");  // what NumPy reads too
  ASSERT_EQ(a.shape, std::vector<std::size_t>{5});
  EXPECT_EQ(a.data, (std::vector<double>{0, 1, 0, 1, 0}));
  const std::vector<uint8_t> bytes = read_file_bytes(run / "selection.npy");
  EXPECT_EQ(bytes.size() % 64, 5u);  // the header is padded to 64 bytes
}

TEST(SelectionFile, CountMismatchIsAClearError) {
  const std::filesystem::path run = test::scratch_dir("selection_file_count");
  const GaussianModel m = test::make_model(five());
  write_selection(selection_json_path(run), record_for(m), {1, 1, 0, 0, 0});
  std::vector<TestGaussian> six = five();
  six.push_back(TestGaussian{{9.0f, 0.0f, 0.0f}});
  const std::string msg = message_of([&] { read_selection(run, test::make_model(six)); });
  EXPECT_NE(msg.find("selection.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("5 Gaussians but the model has 6"), std::string::npos) << msg;
  EXPECT_NE(msg.find("goris select"), std::string::npos) << msg;
}

TEST(SelectionFile, StaleModelAndInconsistentFilesAreErrors) {
  const std::filesystem::path run = test::scratch_dir("selection_file_stale");
  const GaussianModel m = test::make_model(five());
  write_selection(selection_json_path(run), record_for(m), {1, 1, 0, 0, 0});

  // Same count, a moved Gaussian: the fingerprint catches it.
  std::vector<TestGaussian> moved = five();
  moved[2].pos.y = 0.01f;
  const GaussianModel mm = test::make_model(moved);
  EXPECT_NE(model_fingerprint(mm), model_fingerprint(m));
  EXPECT_EQ(model_fingerprint(test::make_model(five())), model_fingerprint(m));
  const std::string stale = message_of([&] { read_selection(run, mm); });
  EXPECT_NE(stale.find("fingerprint"), std::string::npos) << stale;

  // A mask from another selection beside this json.
  const std::filesystem::path other = test::scratch_dir("selection_file_other");
  write_selection(selection_json_path(other), record_for(m), {1, 1, 1, 0, 0});
  std::filesystem::copy_file(other / "selection.npy", run / "selection.npy",
                             std::filesystem::copy_options::overwrite_existing);
  const std::string mixed = message_of([&] { read_selection(run, m); });
  EXPECT_NE(mixed.find("different selections"), std::string::npos) << mixed;

  // Not 0/1, malformed json, missing files.
  write_selection(selection_json_path(run), record_for(m), {1, 1, 0, 0, 0});
  std::vector<uint8_t> bytes = read_file_bytes(run / "selection.npy");
  bytes.back() = 3;
  write_file_bytes(run / "selection.npy", bytes.data(), bytes.size());
  EXPECT_NE(message_of([&] { read_selection(run, m); }).find("only 0 and 1"), std::string::npos);
  { std::ofstream(run / "selection.json") << "{\"format\": \"goris-selection-1\", \"method\": 3}"; }
  EXPECT_NE(message_of([&] { read_selection(run, m); }).find("malformed"), std::string::npos);
  std::filesystem::remove(run / "selection.json");
  EXPECT_NE(message_of([&] { read_selection(run, m); }).find("goris select"), std::string::npos);
}

}  // namespace
}  // namespace goris
