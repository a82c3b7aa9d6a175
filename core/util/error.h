#pragma once
#include <stdexcept>
#include <string>

namespace goris {

// The one exception type of the engine: a message meant for the user that names the file (when there is
// one) and what is wrong with it. The CLI prints what() and exits non-zero.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& msg) : std::runtime_error(msg) {}
  Error(const std::string& path, const std::string& problem) : std::runtime_error(path + ": " + problem) {}
};

}  // namespace goris
