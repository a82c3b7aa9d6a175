#include "train/loop/checkpoint.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/io/file_bytes.h"
#include "core/util/error.h"
#include "core/util/fnv1a.h"
#include "train/config/config_migration.h"
#include "train/loop/hooks/hooks.h"

namespace goris {

namespace {

constexpr char kMagic[8] = {'G', 'O', 'R', 'I', 'S', 'C', 'K', 'P'};
// 2: + learning-rate scale and skipped steps; 3: + adaptive densification record; 4: + emit weights;
// 5: - the adaptive densification record (a removed setting: versions 3 and 4 still load, the record skipped)
constexpr std::uint32_t kVersion = 5;

class Writer {
 public:
  template <class T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  void str(const std::string& s) {
    pod(std::uint64_t(s.size()));
    out_ += s;
  }
  void floats(const Buffer<float>& b) { floats(b.to_host()); }
  void floats(const std::vector<float>& h) {
    pod(std::uint64_t(h.size()));
    out_.append(reinterpret_cast<const char*>(h.data()), h.size() * sizeof(float));
  }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

class Reader {
 public:
  Reader(const std::string& data, const std::filesystem::path& path) : d_(data), path_(path) {}
  template <class T>
  T pod() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, d_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  std::string str() {
    const std::uint64_t n = pod<std::uint64_t>();
    need(n);
    std::string s = d_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  Buffer<float> floats(size_t expect, Device device, const char* what, bool allow_empty = false) {
    const std::uint64_t n = pod<std::uint64_t>();
    if (n != expect && !(allow_empty && n == 0)) fail(std::string(what) + ": " + std::to_string(n) + " values where " + std::to_string(expect) + " were expected");
    need(n * sizeof(float));
    Buffer<float> cpu(n, Device::CPU);
    if (n) std::memcpy(cpu.data(), d_.data() + pos_, n * sizeof(float));
    pos_ += n * sizeof(float);
    return device == Device::CPU ? std::move(cpu) : cpu.copy_to(device);
  }
  // A float block of any length as its bytes: the count, then the floats.
  std::string float_block() {
    const size_t start = pos_;
    const std::uint64_t n = pod<std::uint64_t>();
    if (n > d_.size() / sizeof(float)) fail("is truncated");
    need(n * sizeof(float));
    pos_ += n * sizeof(float);
    return d_.substr(start, pos_ - start);
  }
  [[noreturn]] void fail(const std::string& problem) const { throw Error(path_.string(), "checkpoint " + problem); }

 private:
  void need(std::uint64_t n) const {
    if (n > d_.size() - pos_) fail("is truncated");
  }
  const std::string& d_;
  std::filesystem::path path_;
  size_t pos_ = 8;  // after the magic
};

}  // namespace

void write_checkpoint(const std::filesystem::path& path, const TrainConfig& config, const TrainerState& st) {
  Writer w;
  w.bytes().append(kMagic, 8);
  w.pod(kVersion);
  w.str(nlohmann::json(config).dump());
  w.pod(std::int32_t(st.iteration));
  std::ostringstream rng;
  rng << st.rng;
  w.str(rng.str());
  w.pod(std::uint64_t(st.view_stack.size()));
  for (std::uint32_t v : st.view_stack) w.pod(v);
  w.pod(st.ema_loss);
  w.pod(st.ema_psnr);
  w.pod(st.elapsed_s);

  const GaussianModel& m = st.model;
  w.pod(std::uint64_t(m.count()));
  w.pod(std::int32_t(m.sh_degree));
  w.pod(std::int32_t(m.max_sh_degree));
  for (int p = 0; p < kParamCount; ++p) {
    const ParamTensor& t = m.tensor(Param(p));
    w.pod(std::int32_t(t.width));
    w.floats(t.value);
    w.floats(t.adam_m);
    w.floats(t.adam_v);
  }
  w.floats(m.filter3d_var);
  w.pod(st.adam.beta1);
  w.pod(st.adam.beta2);
  w.pod(st.adam.eps);
  for (int s : st.adam.steps) w.pod(std::int32_t(s));
  w.floats(st.stats.grad_accum);
  w.floats(st.stats.denom);
  w.floats(st.stats.max_radii);
  w.pod(st.lr_scale);
  w.pod(std::int32_t(st.skipped_steps));
  // The emit-weights hook's state in its float block (count, floats), or an empty block. It is the one hook
  // whose state the format has a place for.
  for (const auto& [name, bytes] : st.hooks)
    if (name != EmitWeightsHook::kName)
      throw Error(path.string(), "the checkpoint format has no place for the state of training hook '" + name + "'");
  if (const auto emit = st.hooks.find(EmitWeightsHook::kName); emit != st.hooks.end())
    w.bytes() += emit->second;
  else
    w.pod(std::uint64_t(0));
  w.pod(fnv1a(w.bytes()));

  write_file_bytes(path, w.bytes().data(), w.bytes().size());
}

Checkpoint read_checkpoint(const std::filesystem::path& path, Device device) {
  require_regular_file(path, "checkpoint file");  // a FIFO is refused before opening it could block
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(path.string(), "cannot open the checkpoint");
  const std::string data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (data.size() < 8 + 4 + 8 || std::memcmp(data.data(), kMagic, 8) != 0)
    throw Error(path.string(), "not a GOR-IS checkpoint");
  std::uint64_t stored_sum;
  std::memcpy(&stored_sum, data.data() + data.size() - 8, 8);
  if (fnv1a(data.substr(0, data.size() - 8)) != stored_sum)
    throw Error(path.string(), "checkpoint is corrupted or truncated (checksum mismatch)");

  Reader r(data, path);
  const auto version = r.pod<std::uint32_t>();
  if (version < 1 || version > kVersion)
    r.fail("has format version " + std::to_string(version) + " (this build reads versions 1 to " + std::to_string(kVersion) + ")");
  Checkpoint ck;
  try {
    nlohmann::json j = nlohmann::json::parse(r.str());
    print_config_migration_notes(path.string(), migrate_config_json(j));
    from_json(j, ck.config);
  } catch (const std::exception& e) {
    r.fail(std::string("configuration is invalid: ") + e.what());
  }
  TrainerState& st = ck.state;
  st.iteration = r.pod<std::int32_t>();
  std::istringstream rng(r.str());
  rng >> st.rng;
  if (!rng) r.fail("RNG state is invalid");
  const auto stack = r.pod<std::uint64_t>();
  if (stack > data.size()) r.fail("view list is invalid");
  st.view_stack.resize(stack);
  for (auto& v : st.view_stack) v = r.pod<std::uint32_t>();
  st.ema_loss = r.pod<double>();
  st.ema_psnr = r.pod<double>();
  st.elapsed_s = r.pod<double>();

  const auto n = r.pod<std::uint64_t>();
  if (n > data.size()) r.fail("Gaussian count is invalid");
  GaussianModel m(device);
  m.allocate(n);
  m.sh_degree = r.pod<std::int32_t>();
  m.max_sh_degree = r.pod<std::int32_t>();
  if (m.sh_degree < 0 || m.sh_degree > 3 || m.max_sh_degree < 0 || m.max_sh_degree > 3) r.fail("SH degree is invalid");
  for (int p = 0; p < kParamCount; ++p) {
    ParamTensor& t = m.tensor(Param(p));
    if (r.pod<std::int32_t>() != t.width) r.fail(std::string("parameter ") + param_name(Param(p)) + " has the wrong width");
    t.value = r.floats(n * t.width, device, param_name(Param(p)));
    t.adam_m = r.floats(n * t.width, device, param_name(Param(p)));
    t.adam_v = r.floats(n * t.width, device, param_name(Param(p)));
  }
  m.filter3d_var = r.floats(n, device, "3D filter", /*allow_empty=*/true);
  st.model = std::move(m);
  st.adam.beta1 = r.pod<float>();
  st.adam.beta2 = r.pod<float>();
  st.adam.eps = r.pod<float>();
  for (int& s : st.adam.steps) s = r.pod<std::int32_t>();
  st.stats.grad_accum = r.floats(n, device, "densification statistics", true);
  st.stats.denom = r.floats(n, device, "densification statistics", true);
  st.stats.max_radii = r.floats(n, device, "densification statistics", true);
  if (version >= 2) {
    st.lr_scale = r.pod<double>();
    st.skipped_steps = r.pod<std::int32_t>();
    if (!(st.lr_scale > 0 && st.lr_scale <= 1)) r.fail("learning-rate scale is invalid");
  }
  if (version == 3 || version == 4) {  // the adaptive densification record: held-out checks, stop iteration
    const auto checks = r.pod<std::uint64_t>();
    if (checks > data.size()) r.fail("adaptive densification record is invalid");
    for (std::uint64_t c = 0; c < checks; ++c) {
      r.pod<std::int32_t>();
      r.pod<double>();
      r.pod<std::uint64_t>();
    }
    const auto stopped_at = r.pod<std::int32_t>();
    if (stopped_at < 0 || stopped_at > st.iteration) r.fail("adaptive densification stop iteration is invalid");
  }
  if (version >= 4) {  // the emit-weights hook's state: weights of the model when they were set, any count
    std::string emit = r.float_block();
    if (emit.size() > sizeof(std::uint64_t)) st.hooks[EmitWeightsHook::kName] = std::move(emit);
  }
  return ck;
}

std::filesystem::path checkpoint_path(const std::filesystem::path& run_dir, int iteration) {
  char name[32];
  std::snprintf(name, sizeof name, "iter_%08d.ckpt", iteration);
  return run_dir / "checkpoints" / name;
}

namespace {
std::vector<std::pair<int, std::filesystem::path>> list_checkpoints(const std::filesystem::path& run_dir) {
  std::vector<std::pair<int, std::filesystem::path>> out;
  const auto dir = run_dir / "checkpoints";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return out;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    int it = 0;
    char tail[8] = {};
    if (name.size() == 18 && std::sscanf(name.c_str(), "iter_%8d.%4s", &it, tail) == 2 && std::string(tail) == "ckpt")
      out.emplace_back(it, e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}
}  // namespace

namespace {
// What is wrong with a checkpoint file, "" when it is intact: a FIFO, device or folder under a checkpoint's
// name is refused by its type before anything opens it (opening a FIFO would wait for a writer forever);
// a regular file needs the magic and the trailing checksum, read in chunks (no copy of the file in memory).
// Results are kept per (path, size, modification time): a command asks several times, a checkpoint is large.
std::string checkpoint_problem(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  if (std::string type = regular_file_problem(path, "checkpoint file"); !type.empty()) return type;
  std::error_code size_ec, time_ec;  // one each: a later call's success would clear an earlier failure
  const auto size = fs::file_size(path, size_ec);
  const auto mtime = fs::last_write_time(path, time_ec);
  if (size_ec || time_ec) return "cannot be read (" + (size_ec ? size_ec : time_ec).message() + ")";
  const std::string truncated = "is truncated or corrupted (its magic or checksum does not match)";
  if (size < 8 + 4 + 8) return truncated;
  static std::mutex mutex;
  static std::map<std::string, std::tuple<std::uintmax_t, fs::file_time_type, bool>> known;
  const std::string key = path.string();
  {
    std::lock_guard lk(mutex);
    if (auto it = known.find(key); it != known.end() && std::get<0>(it->second) == size && std::get<1>(it->second) == mtime)
      return std::get<2>(it->second) ? "" : truncated;
  }
  std::ifstream f(path, std::ios::binary);
  std::vector<char> buf(1 << 20);
  Fnv1a h;
  std::uintmax_t left = size - 8;
  char magic[8] = {};
  bool ok = bool(f.read(magic, 8)) && std::memcmp(magic, kMagic, 8) == 0;
  if (ok) {
    for (unsigned char c : std::string_view(magic, 8)) h.byte(c);
    left -= 8;
  }
  while (ok && left > 0) {
    const std::size_t n = std::size_t(std::min<std::uintmax_t>(left, buf.size()));
    ok = bool(f.read(buf.data(), std::streamsize(n)));
    for (std::size_t i = 0; ok && i < n; ++i) h.byte(static_cast<unsigned char>(buf[i]));
    left -= n;
  }
  std::uint64_t stored = 0;
  ok = ok && bool(f.read(reinterpret_cast<char*>(&stored), 8)) && stored == h.value;
  std::lock_guard lk(mutex);
  known[key] = {size, mtime, ok};
  return ok ? "" : truncated;
}
}  // namespace

std::optional<std::filesystem::path> latest_checkpoint(const std::filesystem::path& run_dir) {
  const auto all = list_checkpoints(run_dir);
  if (all.empty()) return std::nullopt;
  std::vector<std::pair<std::filesystem::path, std::string>> bad;  // newest first, with what is wrong
  for (auto it = all.rbegin(); it != all.rend(); ++it) {
    std::string problem = checkpoint_problem(it->second);
    if (!problem.empty()) {
      bad.emplace_back(it->second, std::move(problem));
      continue;
    }
    static std::mutex mutex;
    static std::set<std::string> warned;  // once per file, though a command asks several times
    std::lock_guard lk(mutex);
    for (const auto& [file, why] : bad)
      if (warned.insert(file.string()).second)
        std::fprintf(stderr, "warning: %s %s; using %s\n", file.string().c_str(),
                     why.c_str(), it->second.filename().string().c_str());
    return it->second;
  }
  std::string list;
  for (const auto& [file, why] : bad) list += (list.empty() ? "" : "; ") + file.filename().string() + " " + why;
  throw Error((run_dir / "checkpoints").string(),
              "no intact checkpoint to continue from: " + list +
                  ". Start the run over with --restart (goris train DATA --out RUN --restart), or move these files "
                  "away");
}

bool has_checkpoint_files(const std::filesystem::path& run_dir) { return !list_checkpoints(run_dir).empty(); }

std::filesystem::path renderer_state_path(const std::filesystem::path& checkpoint) {
  std::filesystem::path p = checkpoint;
  p += ".renderer";
  return p;
}

void remove_old_checkpoints(const std::filesystem::path& run_dir, int keep) {
  const auto all = list_checkpoints(run_dir);
  for (size_t i = 0; i + size_t(std::max(keep, 1)) < all.size(); ++i) {
    std::error_code ec;
    std::filesystem::remove(all[i].second, ec);
    std::filesystem::remove(renderer_state_path(all[i].second), ec);
  }
}

}  // namespace goris
