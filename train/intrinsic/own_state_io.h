#pragma once
// Byte format of the intrinsic renderer's own parameters beside a checkpoint (environment map and
// roughness net with their Adam moments): a magic, the sizes they were made for, then the buffers as
// length-prefixed float arrays. Reading checks every size, so a file from another configuration (another
// cube map resolution or net depth) is an error naming the file, never a silent mismatch.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/compute/buffer.h"
#include "core/util/error.h"
#include "train/optimizer/flat_adam.h"

namespace goris {

inline constexpr char kOwnStateMagic[8] = {'G', 'O', 'R', 'I', 'S', 'I', 'R', '1'};

class OwnStateWriter {
 public:
  void header(int env_resolution, int net_params) {
    raw(kOwnStateMagic, sizeof kOwnStateMagic);
    value(std::int32_t(env_resolution));
    value(std::int32_t(net_params));
  }
  void buffer(const Buffer<float>& b) {
    const std::vector<float> h = b.to_host();
    value(std::uint64_t(h.size()));
    raw(h.data(), h.size() * sizeof(float));
  }
  void adam(const FlatAdam& a) {
    value(std::int32_t(a.steps()));
    buffer(a.first_moment());
    buffer(a.second_moment());
  }
  const std::string& bytes() const { return out_; }

 private:
  template <class T>
  void value(T v) { raw(&v, sizeof v); }
  void raw(const void* p, std::size_t n) { out_.append(static_cast<const char*>(p), n); }
  std::string out_;
};

class OwnStateReader {
 public:
  OwnStateReader(const std::string& bytes, std::string source) : in_(bytes), source_(std::move(source)) {}
  void header(int env_resolution, int net_params) {
    char magic[sizeof kOwnStateMagic];
    raw(magic, sizeof magic);
    if (std::memcmp(magic, kOwnStateMagic, sizeof magic) != 0)
      throw Error(source_, "not an environment map / roughness net file");
    const auto res = value<std::int32_t>(), np = value<std::int32_t>();
    if (res != env_resolution || np != net_params)
      throw Error(source_, "holds a " + std::to_string(res) + "^2 cube map and a net of " + std::to_string(np) +
                               " parameters; the run's configuration wants " + std::to_string(env_resolution) +
                               "^2 and " + std::to_string(net_params));
  }
  void buffer(Buffer<float>& b) {
    const auto n = value<std::uint64_t>();
    if (n != b.size())
      throw Error(source_, "an array of " + std::to_string(n) + " values where " + std::to_string(b.size()) +
                               " were expected");
    std::vector<float> h(n);
    raw(h.data(), n * sizeof(float));
    b.upload(h.data(), h.size());
  }
  void adam(FlatAdam& a) {
    a.set_steps(value<std::int32_t>());
    buffer(a.first_moment());
    buffer(a.second_moment());
  }
  void finish() const {
    if (pos_ != in_.size()) throw Error(source_, "has trailing bytes (corrupt file)");
  }

 private:
  template <class T>
  T value() {
    T v;
    raw(&v, sizeof v);
    return v;
  }
  void raw(void* p, std::size_t n) {
    if (pos_ + n > in_.size()) throw Error(source_, "is truncated");
    std::memcpy(p, in_.data() + pos_, n);
    pos_ += n;
  }
  const std::string& in_;
  std::string source_;
  std::size_t pos_ = 0;
};

}  // namespace goris
