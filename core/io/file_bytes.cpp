#include "core/io/file_bytes.h"

#include <atomic>
#include <fstream>
#include <system_error>

#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>

#include "core/util/error.h"

namespace goris {
namespace fs = std::filesystem;

std::string regular_file_problem(const fs::path& path, const std::string& what) {
  const std::string a_what = (std::string("aeiou").find(what[0]) != std::string::npos ? "an " : "a ") + what;
  std::error_code ec;
  const auto st = fs::status(path, ec);
  if (ec || !fs::exists(st)) return what + " not found";
  if (fs::is_directory(st)) return "is a folder, not " + a_what;
  const char* kind = fs::is_fifo(st)             ? "a FIFO (named pipe)"
                     : fs::is_character_file(st) ? "a character device"
                     : fs::is_block_file(st)     ? "a block device"
                     : fs::is_socket(st)         ? "a socket"
                     : fs::is_regular_file(st)   ? nullptr
                                                 : "neither a regular file nor a folder";
  return kind ? std::string("is ") + kind + ", not " + a_what : std::string();
}

void require_regular_file(const fs::path& path, const std::string& what) {
  if (const std::string problem = regular_file_problem(path, what); !problem.empty()) throw Error(path.string(), problem);
}

std::vector<uint8_t> read_file_bytes(const fs::path& path) {
  require_regular_file(path);
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw Error(path.string(), "cannot open for reading");
  const std::streamoff size = in.tellg();
  if (size < 0) throw Error(path.string(), "cannot determine the file size");
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  in.seekg(0);
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size))
    throw Error(path.string(), "read failed");
  return bytes;
}

std::string read_text_file(const fs::path& path) {
  auto bytes = read_file_bytes(path);
  return std::string(bytes.begin(), bytes.end());
}

void write_file_bytes(const fs::path& path, const void* bytes, size_t size) {
  write_via_temp_file(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path.string(), "cannot open " + tmp.string() + " for writing");
    out.write(static_cast<const char*>(bytes), std::streamsize(size));
    out.close();
    if (!out) throw Error(path.string(), "write failed (disk full?)");
  });
}

void remove_stale_temp_files(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    // .<stem>.tmp<pid>_<n><ext>, as write_via_temp_file names them
    const std::string name = e.path().filename().string();
    const std::size_t at = name.rfind(".tmp");
    if (name.empty() || name[0] != '.' || at == std::string::npos || at == 0) continue;
    std::size_t i = at + 4, digits = 0;
    long long pid = 0;
    for (; i < name.size() && std::isdigit(static_cast<unsigned char>(name[i])) && digits < 12; ++i, ++digits)
      pid = pid * 10 + (name[i] - '0');
    if (digits == 0 || i >= name.size() || name[i] != '_' || pid <= 0) continue;
    if (::kill(pid_t(pid), 0) == 0 || errno == EPERM) continue;  // its writer still runs
    std::error_code rm;
    fs::remove(e.path(), rm);
  }
}

void write_via_temp_file(const fs::path& path, const std::function<void(const fs::path& tmp)>& write) {
  static std::atomic<unsigned> counter{0};
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(path.string(), "cannot write: folder " + dir.string() + " does not exist");
  // Keep the extension last: some writers (OpenCV) pick the encoder from it.
  std::string name = ".";
  name += path.stem().string();
  name += ".tmp";
  name += std::to_string(::getpid());
  name += '_';
  name += std::to_string(counter++);
  name += path.extension().string();
  const fs::path tmp = dir / name;
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ec2;
    fs::remove(tmp, ec2);
    throw Error(path.string(), "cannot replace the file: " + ec.message());
  }
}

}  // namespace goris
