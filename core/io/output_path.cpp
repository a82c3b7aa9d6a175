#include "core/io/output_path.h"

#include <exception>
#include <fstream>
#include <system_error>
#include <utility>

#include "core/io/dataset.h"
#include "core/util/error.h"

namespace goris {

namespace fs = std::filesystem;

namespace {

fs::path normalised(const fs::path& p) {
  std::error_code ec;
  const fs::path c = fs::weakly_canonical(fs::absolute(p), ec);
  return ec ? fs::absolute(p).lexically_normal() : c;
}

// `p` is `dir` or lies below it (both normalised).
bool is_within(const fs::path& p, const fs::path& dir) {
  auto a = p.begin(), b = dir.begin();
  for (; b != dir.end(); ++a, ++b) {
    if (b->empty()) continue;  // a trailing separator
    if (a == p.end() || *a != *b) return false;
  }
  return true;
}

bool is_dataset_folder(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return false;
  try {
    detect_dataset_format(dir);
    return true;
  } catch (const Error&) {
    return false;
  }
}

void check_guard(const fs::path& shown, const fs::path& out, const OutputGuard& guard) {
  for (const fs::path& d : guard.datasets)
    if (is_within(out, normalised(d)))
      throw Error(shown.string(), "is inside the data set " + normalised(d).string() +
                                      "; write outputs elsewhere (a data set is only read)");
  for (fs::path dir = out; !dir.empty(); dir = dir.parent_path()) {
    if (is_dataset_folder(dir))
      throw Error(shown.string(), "is inside the data set " + dir.string() +
                                      "; write outputs elsewhere (a data set is only read)");
    if (dir == dir.root_path()) break;
  }
  for (const fs::path& k : guard.keep)
    if (is_within(out, normalised(k)))
      throw Error(shown.string(), "would overwrite " + normalised(k).string() +
                                      ", an input of the run; choose another output path");
}

void require_folder(const fs::path& shown, const fs::path& dir) {
  std::error_code ec;
  if (fs::is_directory(dir, ec)) return;
  if (fs::exists(dir, ec)) throw Error(shown.string(), "cannot write: " + dir.string() + " is not a folder");
  throw Error(shown.string(), "cannot write: the folder " + dir.string() + " does not exist (create it first)");
}

// A file can be created (and removed again) in `dir`.
void probe_writable(const fs::path& shown, const fs::path& dir) {
  const fs::path probe = dir / ".goris_output_probe";
  {
    std::ofstream f(probe, std::ios::binary);
    if (!f) throw Error(shown.string(), "cannot write into " + dir.string() + " (permissions?)");
  }
  std::error_code ec;
  fs::remove(probe, ec);
}

}  // namespace

void check_output_file(const fs::path& path, const OutputGuard& guard) {
  const fs::path abs = normalised(path);
  if (fs::absolute(path).filename().empty()) throw Error(path.string(), "an output file name is needed, not a folder");
  std::error_code ec;
  if (fs::is_directory(abs, ec)) throw Error(path.string(), "is a folder; an output file name is needed");
  check_guard(path, abs, guard);
  require_folder(path, abs.parent_path());
  probe_writable(path, abs.parent_path());
}

void check_output_dir(const fs::path& dir, const OutputGuard& guard) {
  const fs::path abs = normalised(dir);
  std::error_code ec;
  if (fs::exists(abs, ec) && !fs::is_directory(abs, ec)) throw Error(dir.string(), "exists and is not a folder");
  check_guard(dir, abs, guard);
  if (!fs::is_directory(abs, ec)) {
    require_folder(dir, abs.parent_path());
    fs::create_directory(abs, ec);
    if (ec) throw Error(dir.string(), "cannot create the folder (" + ec.message() + ")");
  }
  probe_writable(dir, abs);
}

RemoveIfLeftEmpty::RemoveIfLeftEmpty(fs::path dir)
    : dir_(std::move(dir)), existed_(fs::exists(dir_)), exceptions_(std::uncaught_exceptions()) {}

RemoveIfLeftEmpty::~RemoveIfLeftEmpty() {
  if (existed_ || std::uncaught_exceptions() <= exceptions_) return;
  std::error_code ec;
  if (fs::is_directory(dir_, ec) && fs::is_empty(dir_, ec)) fs::remove(dir_, ec);
}

}  // namespace goris
