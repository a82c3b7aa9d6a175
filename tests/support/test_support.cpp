#include "tests/support/test_support.h"

namespace goris::test {

std::filesystem::path shared_dir() { return std::filesystem::path(GORIS_SHARED_DIR); }
std::filesystem::path resource_dir() { return std::filesystem::path(GORIS_RESOURCE_DIR); }

std::filesystem::path scratch_dir(const std::string& name) {
  auto p = std::filesystem::path(GORIS_BINARY_DIR) / "test_scratch" / name;
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

}  // namespace goris::test
