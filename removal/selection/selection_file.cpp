#include "core/io/json_file.h"
#include "removal/selection/selection_file.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "core/io/file_bytes.h"
#include "core/io/npy.h"
#include "core/io/npy_write.h"
#include "core/scene/gaussians.h"
#include "core/util/error.h"
#include "core/util/fnv1a.h"

namespace goris {

namespace fs = std::filesystem;

namespace {

std::vector<std::uint8_t> npy_u8(const SelectionMask& mask) {
  return npy_bytes("|u1", {mask.size()}, mask.data(), mask.size());
}

std::string stale_hint() { return " - the model changed since this selection was made: run `goris select` again"; }

}  // namespace

fs::path selection_json_path(const fs::path& run_dir) { return run_dir / "selection.json"; }

std::string model_fingerprint(const GaussianModel& model) {
  const std::vector<float> pos = model.tensor(Param::Position).value.to_host();
  Fnv1a hash;
  const std::uint64_t n = model.count();
  for (int k = 0; k < 8; ++k) hash.byte(std::uint8_t(n >> (8 * k)));  // little-endian on every machine
  for (float f : pos) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    for (int k = 0; k < 4; ++k) hash.byte(std::uint8_t(u >> (8 * k)));
  }
  return hash.hex();
}

void write_selection(const fs::path& json_path, SelectionRecord record, const SelectionMask& mask) {
  record.mask_file = json_path.stem().string() + ".npy";
  record.gaussian_count = mask.size();
  record.selected = count_selected(mask);
  SelectionMask binary(mask.size());
  for (std::size_t i = 0; i < mask.size(); ++i) binary[i] = mask[i] ? 1 : 0;
  const std::vector<std::uint8_t> npy = npy_u8(binary);
  write_file_bytes(json_path.parent_path() / record.mask_file, npy.data(), npy.size());

  nlohmann::json j;
  j["format"] = "goris-selection-1";
  j["method"] = record.method;
  j["parameters"] = record.parameters;
  j["summary"] = record.summary;
  j["model_source"] = record.model_source;
  j["gaussian_count"] = record.gaussian_count;
  j["model_fingerprint"] = record.model_fingerprint;
  j["selected"] = record.selected;
  j["mask_file"] = record.mask_file;
  write_json_file(json_path, j);
}

StoredSelection read_selection_file(const fs::path& json_path, const GaussianModel& model) {
  const std::string where = json_path.string();
  if (!fs::exists(json_path))
    throw Error(where, "no selection: run `goris select RUN --labels | --masks | --click VIEW X Y` first");
  StoredSelection s;
  SelectionRecord& r = s.record;
  try {
    const nlohmann::json j = nlohmann::json::parse(read_text_file(json_path));
    if (j.value("format", std::string()) != "goris-selection-1")
      throw Error(where, "not a goris selection (format is not goris-selection-1)");
    r.method = j.at("method").get<std::string>();
    r.parameters = j.at("parameters");
    r.summary = j.at("summary");
    r.model_source = j.at("model_source").get<std::string>();
    r.gaussian_count = j.at("gaussian_count").get<std::size_t>();
    r.model_fingerprint = j.at("model_fingerprint").get<std::string>();
    r.selected = j.at("selected").get<std::size_t>();
    r.mask_file = j.at("mask_file").get<std::string>();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(where, std::string("malformed selection file: ") + e.what());
  }
  if (r.mask_file.empty() || fs::path(r.mask_file).filename() != fs::path(r.mask_file))
    throw Error(where, "mask_file must be a file name beside the .json, got '" + r.mask_file + "'");
  if (r.gaussian_count != model.count())
    throw Error(where, "selection is for " + std::to_string(r.gaussian_count) + " Gaussians but the model has " +
                           std::to_string(model.count()) + stale_hint());
  const std::string fp = model_fingerprint(model);
  if (r.model_fingerprint != fp)
    throw Error(where, "selection was made on a model with fingerprint " + r.model_fingerprint + " (" +
                           r.model_source + "), the model now has " + fp + stale_hint());

  const fs::path npy_path = json_path.parent_path() / r.mask_file;
  const NpyArray a = load_npy(npy_path);
  if (a.shape.size() != 1 || a.shape[0] != r.gaussian_count)
    throw Error(npy_path.string(), "expected a 1-d mask of " + std::to_string(r.gaussian_count) + " entries");
  s.mask.resize(a.data.size());
  for (std::size_t i = 0; i < a.data.size(); ++i) {
    if (a.data[i] != 0.0 && a.data[i] != 1.0)
      throw Error(npy_path.string(), "entry " + std::to_string(i) + " is " + std::to_string(a.data[i]) +
                                         ", a selection mask holds only 0 and 1");
    s.mask[i] = a.data[i] != 0.0 ? 1 : 0;
  }
  if (count_selected(s.mask) != r.selected)
    throw Error(npy_path.string(), "holds " + std::to_string(count_selected(s.mask)) + " selected Gaussians but " +
                                       where + " says " + std::to_string(r.selected) +
                                       " (the two files are from different selections: run `goris select` again)");
  return s;
}

StoredSelection read_selection(const fs::path& run_dir, const GaussianModel& model) {
  return read_selection_file(selection_json_path(run_dir), model);
}

}  // namespace goris
