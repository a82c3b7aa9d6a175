#pragma once
// A selection stored in a run folder (written by `goris select`, read by `goris remove` and the editor):
//   RUN/selection.json  what was selected and how: method, parameters, counts, and the model it belongs to
//                       (its file, Gaussian count and a fingerprint of the centres, so that a selection made
//                       before the model changed is detected instead of deleting the wrong Gaussians);
//   RUN/selection.npy   the per-Gaussian mask, uint8 [N] (1 = target), readable by NumPy.
// Both are written through temporary files (the mask first, so a selection.json never names a mask that is
// not complete).
#include <cstddef>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "core/scene/selection_points.h"

namespace goris {

class GaussianModel;

struct SelectionRecord {
  std::string method;             // "labels", "masks", "click", ... (what the seeds came from)
  nlohmann::json parameters = nlohmann::json::object();  // the method's settings (threshold, view, grow...)
  nlohmann::json summary = nlohmann::json::object();     // counts (SelectionSummary and growth)
  std::string model_source;       // the checkpoint / PLY the selection was made on
  std::size_t gaussian_count = 0;
  std::string model_fingerprint;  // model_fingerprint() of that model
  std::size_t selected = 0;       // ones in the mask
  std::string mask_file;          // the .npy beside the .json (file name only)
};

struct StoredSelection {
  SelectionRecord record;
  SelectionMask mask;
};

std::filesystem::path selection_json_path(const std::filesystem::path& run_dir);  // RUN/selection.json

// FNV-1a 64-bit hash of the centres' float bits, as 16 hex digits: equal models give equal fingerprints
// on every device; any moved, added or removed Gaussian changes it.
std::string model_fingerprint(const GaussianModel& model);

// Writes `mask` as <json stem>.npy beside `json_path`, then the record (mask_file, selected and
// gaussian_count are filled in from the mask). Throws goris::Error naming the file on failure.
void write_selection(const std::filesystem::path& json_path, SelectionRecord record, const SelectionMask& mask);

// Reads a selection written by write_selection and checks it against `model`: the Gaussian count and the
// fingerprint must match, the mask must be 0/1 with as many ones as the record says. Every mismatch is a
// goris::Error naming the file and saying what to do (select again on the current model).
StoredSelection read_selection_file(const std::filesystem::path& json_path, const GaussianModel& model);
// The same for RUN/selection.json.
StoredSelection read_selection(const std::filesystem::path& run_dir, const GaussianModel& model);

}  // namespace goris
