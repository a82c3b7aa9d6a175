#pragma once
// The one check of an output path, run by every command (and the editor) before any work, so that a
// careless path fails in a second with the path and the problem instead of destroying inputs:
//   - nothing is written inside a data set folder (the folder or any folder above the output holds a data
//     set that detect_dataset_format() recognises, or is one of OutputGuard::datasets);
//   - no file or folder of OutputGuard::keep (a run's own inputs: config.json, the model, checkpoints/) is
//     replaced or written into;
//   - no folders are made beyond the last level: a file's folder must exist, an output folder's parent must
//     exist (a mistyped path is refused instead of creating it, e.g. /nonexistent_dir at the root);
//   - a file name is not an existing folder, a folder is not an existing file, and the folder is writable.
// Throws goris::Error naming the path.
#include <filesystem>
#include <vector>

namespace goris {

struct OutputGuard {
  std::vector<std::filesystem::path> datasets;  // data set folders nothing may be written into
  std::vector<std::filesystem::path> keep;      // files and folders that must not be replaced or written into
};

// An output file: checks the rules above and that a file can be created in its folder (nothing is left).
void check_output_file(const std::filesystem::path& path, const OutputGuard& guard = {});
// An output folder: checks the rules above and creates it (its parent must exist).
void check_output_dir(const std::filesystem::path& dir, const OutputGuard& guard = {});

// Removes `dir` again when it did not exist at construction, the scope is left by an exception and nothing
// was written into it: a refused command leaves no empty folder behind.
class RemoveIfLeftEmpty {
 public:
  explicit RemoveIfLeftEmpty(std::filesystem::path dir);
  ~RemoveIfLeftEmpty();
  RemoveIfLeftEmpty(const RemoveIfLeftEmpty&) = delete;
  RemoveIfLeftEmpty& operator=(const RemoveIfLeftEmpty&) = delete;

 private:
  std::filesystem::path dir_;
  bool existed_;
  int exceptions_;
};

}  // namespace goris
