#include "tests/support/test_support.h"

#include <cstdlib>

namespace goris::test {

namespace {
// The build's paths, unless the environment names others: a test binary carried to another machine (the
// device bundle, tests/gpu/device_check.sh) finds the checkout, the shared data and a scratch folder there.
std::filesystem::path dir_from_env(const char* variable, const char* built_in) {
  const char* v = std::getenv(variable);
  return std::filesystem::path(v && *v ? v : built_in);
}
}  // namespace

std::filesystem::path shared_dir() { return dir_from_env("GORIS_SHARED_DIR", GORIS_SHARED_DIR); }
std::filesystem::path resource_dir() { return dir_from_env("GORIS_RESOURCE_DIR", GORIS_RESOURCE_DIR); }

std::filesystem::path scratch_dir(const std::string& name) {
  auto p = dir_from_env("GORIS_BINARY_DIR", GORIS_BINARY_DIR) / "test_scratch" / name;
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

}  // namespace goris::test
