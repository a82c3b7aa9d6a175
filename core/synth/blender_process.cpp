#include "core/synth/blender_process.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>

#include "core/util/error.h"

namespace goris::synth {
namespace fs = std::filesystem;

namespace {
bool executable(const fs::path& p) { return fs::is_regular_file(p) && ::access(p.c_str(), X_OK) == 0; }
}  // namespace

fs::path find_blender(const fs::path& requested) {
  const std::string install = "install it with `sudo apt-get install blender` (Blender 3.4 or newer)";
  if (!requested.empty()) {
    if (!executable(requested)) throw Error(requested.string(), "no Blender executable here; " + install + " or pass --blender PATH");
    return requested;
  }
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "";
  for (size_t start = 0; start <= dirs.size();) {
    size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    fs::path candidate = fs::path(dirs.substr(start, end - start)) / "blender";
    if (end > start && executable(candidate)) return candidate;
    start = end + 1;
  }
  throw Error("blender", "not found on PATH; " + install + " or pass --blender PATH");
}

ProcessResult run_logged(const fs::path& program, const std::vector<std::string>& args, const fs::path& log_path,
                         const std::function<void(const std::string&)>& on_line) {
  std::ofstream log(log_path);
  if (!log) throw Error(log_path.string(), "cannot create the log file");
  int fds[2];
  if (::pipe(fds) != 0) throw Error(program.string(), std::string("cannot create a pipe: ") + std::strerror(errno));

  std::vector<std::string> argv_s{program.string()};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);

  pid_t pid = ::fork();
  if (pid < 0) throw Error(program.string(), std::string("cannot start: ") + std::strerror(errno));
  if (pid == 0) {
    ::dup2(fds[1], STDOUT_FILENO);
    ::dup2(fds[1], STDERR_FILENO);
    ::close(fds[0]);
    ::close(fds[1]);
    ::execv(argv[0], argv.data());
    std::fprintf(stderr, "cannot execute %s: %s\n", argv[0], std::strerror(errno));
    ::_exit(127);
  }
  ::close(fds[1]);

  ProcessResult result;
  std::deque<std::string> tail;
  std::string pending;
  char buf[4096];
  auto emit = [&](const std::string& line) {
    log << line << '\n';
    log.flush();
    tail.push_back(line);
    if (tail.size() > 20) tail.pop_front();
    if (on_line) on_line(line);
  };
  for (;;) {
    ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    pending.append(buf, size_t(n));
    for (size_t nl; (nl = pending.find('\n')) != std::string::npos;) {
      emit(pending.substr(0, nl));
      pending.erase(0, nl + 1);
    }
  }
  if (!pending.empty()) emit(pending);
  ::close(fds[0]);

  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.last_lines.assign(tail.begin(), tail.end());
  return result;
}

}  // namespace goris::synth
