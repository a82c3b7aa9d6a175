// `goris bench compute`: medians of the compute primitives on each available backend, with CPU/CUDA
// ratios, so a regression in sort/scan/reduce (the rasterizer's binning path) is visible on its own.
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "app/bench/bench_child.h"
#include "app/cli_common/command.h"
#include "core/compute/primitives.h"
#include "core/compute/bench.h"

namespace {

struct Row {
  std::string op;
  double cpu_ms = -1, cuda_ms = -1;
};

void run_compute_bench(std::size_t n, int repeats) {
  std::mt19937_64 rng(42);
  std::vector<std::uint64_t> keys(n);
  for (auto& k : keys) k = rng() & ((1ull << 48) - 1);
  std::vector<std::uint32_t> vals(n);
  std::vector<float> fl(n);
  for (std::size_t i = 0; i < n; ++i) {
    vals[i] = std::uint32_t(i);
    fl[i] = float(rng() % 1000) * 1e-3f;
  }
  std::vector<goris::Device> devices = {goris::Device::CPU};
  if (goris::cuda_device_count() > 0) devices.push_back(goris::Device::CUDA);

  std::vector<Row> rows = {{"sort_by_key (48-bit keys)"}, {"exclusive_scan (u32)"}, {"reduce_sum (f32)"}, {"reduce_max (f32)"}};
  for (goris::Device d : devices) {
    auto sync = [d] { goris::device_synchronize(d); };
    goris::Buffer<std::uint64_t> k(n, d);
    goris::Buffer<std::uint32_t> v(vals, d), out(n, d);
    goris::Buffer<float> f(fl, d);
    // each sort starts from the same unsorted keys
    auto t_sort = goris::time_repeated([&] { k.upload(keys.data(), n); sort_by_key(k, v, 48); }, repeats, 1, sync);
    auto t_scan = goris::time_repeated([&] { goris::exclusive_scan(v, out); }, repeats, 1, sync);
    auto t_sum = goris::time_repeated([&] { (void)goris::reduce_sum(f); }, repeats, 1, sync);
    auto t_max = goris::time_repeated([&] { (void)goris::reduce_max(f); }, repeats, 1, sync);
    double* slot[4];
    for (int i = 0; i < 4; ++i) slot[i] = d == goris::Device::CPU ? &rows[i].cpu_ms : &rows[i].cuda_ms;
    *slot[0] = t_sort.median_ms;
    *slot[1] = t_scan.median_ms;
    *slot[2] = t_sum.median_ms;
    *slot[3] = t_max.median_ms;
  }
  std::printf("# goris bench compute: n = %zu, median of %d runs\n", n, repeats);
  std::printf("# CPU: %s\n# CUDA: %s\n\n", goris::cpu_description().c_str(), goris::cuda_device_description().c_str());
  std::printf("| op | CPU ms | CUDA ms | CPU/CUDA |\n|---|---|---|---|\n");
  for (auto& r : rows) {
    if (r.cuda_ms >= 0)
      std::printf("| %s | %.3f | %.3f | %.1fx |\n", r.op.c_str(), r.cpu_ms, r.cuda_ms, r.cpu_ms / r.cuda_ms);
    else
      std::printf("| %s | %.3f | - | - |\n", r.op.c_str(), r.cpu_ms);
  }
  std::printf("\npeak memory: %s\n", goris::peak_memory_text().c_str());
}

void setup_bench_compute(CLI::App& root) {
  auto& bench = goris::bench::bench_group(root);
  auto* c = bench.add_subcommand("compute", "Sort-by-key, scan and reductions on every available backend");
  auto n = std::make_shared<double>(4e6);
  auto repeats = std::make_shared<int>(11);
  c->add_option("--n", *n, "elements")->capture_default_str();
  c->add_option("--repeats", *repeats, "timed runs (median reported)")->capture_default_str();
  c->callback([n, repeats] { run_compute_bench(std::size_t(*n), *repeats); });
}

}  // namespace
GORIS_COMMAND(81, setup_bench_compute);
