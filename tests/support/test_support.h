#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/compute/device.h"
#include "core/util/error.h"

namespace goris::test {

// ../shared next to the checkout (data sets, fixtures); tests that need it skip when it is absent.
std::filesystem::path shared_dir();
std::filesystem::path resource_dir();
// A fresh, empty scratch folder for one test (under the build tree).
std::filesystem::path scratch_dir(const std::string& name);

// Runs f, expects a goris::Error whose message contains `needle`.
template <class F>
void expect_error(F&& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one mentioning '" << needle << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

}  // namespace goris::test

// Skips the current test, with a message, when ../shared/<rel> does not exist.
#define GORIS_REQUIRE_SHARED(rel)                                                                    \
  do {                                                                                               \
    if (!std::filesystem::exists(::goris::test::shared_dir() / (rel)))                               \
      GTEST_SKIP() << "needs ../shared/" << (rel) << " (absent on this machine)";                    \
  } while (0)

// Skips the current test, with a message, when no CUDA device can run it.
#define GORIS_REQUIRE_GPU()                                                                          \
  do {                                                                                               \
    if (::goris::cuda_device_count() == 0)                                                           \
      GTEST_SKIP() << "no CUDA device: " << ::goris::cuda_device_description();                      \
  } while (0)
