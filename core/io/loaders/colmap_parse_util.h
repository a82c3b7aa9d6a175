#pragma once
// Internal helpers of the COLMAP parsers (not part of the public API).
#include <cmath>
#include <string>
#include <string_view>

#include "core/io/loaders/colmap_model.h"
#include "core/util/error.h"

namespace goris::colmap_detail {

// The model for `id` when it is one of the supported five; otherwise an error naming it.
ColmapModel supported_model(int id, uint32_t camera_id, const std::string& name, const std::string& where);
int model_id_from_name(std::string_view model, uint32_t camera_id, const std::string& name, const std::string& where);
// Validity checks shared by both formats; `where` is "byte offset N" or "line N".
void check_camera(const ColmapCamera& c, const std::string& name, const std::string& where);
void check_image(const ColmapImage& im, const std::string& name, const std::string& where);
// `where()` is only called to build an error message.
template <class Where>
void check_point(const ColmapPoint& p, const std::string& name, Where&& where) {
  for (double v : p.xyz)
    if (!std::isfinite(v)) throw Error(name, where() + ": point " + std::to_string(p.id) + " has a non-finite position");
}

}  // namespace goris::colmap_detail
