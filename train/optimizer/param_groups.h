#pragma once
// Optimiser parameter groups: each is a column range of one of the model's tensors with its own learning
// rate (docs/design/conventions.md, Learning rates). SH is split into the DC coefficient and the rest; the
// extras into materials (diffuse, F0, roughness), region and label.
#include <array>

#include "core/scene/gaussians.h"

namespace goris {

enum class ParamGroup : int { Position, Scale, Rotation, Opacity, ShDc, ShRest, Materials, Region, Label };
constexpr int kGroupCount = 9;

struct GroupSpan {
  Param param;
  int col_begin, col_end;  // columns [begin, end) of the tensor's rows
};

inline GroupSpan group_span(ParamGroup g) {
  switch (g) {
    case ParamGroup::Position: return {Param::Position, 0, 3};
    case ParamGroup::Scale: return {Param::LogScale, 0, 3};
    case ParamGroup::Rotation: return {Param::Rotation, 0, 4};
    case ParamGroup::Opacity: return {Param::OpacityLogit, 0, 1};
    case ParamGroup::ShDc: return {Param::Sh, 0, 3};
    case ParamGroup::ShRest: return {Param::Sh, 3, kMaxShCoeffs * 3};
    case ParamGroup::Materials: return {Param::ExtraLogit, extra::kDiffuse, extra::kRegion};
    case ParamGroup::Region: return {Param::ExtraLogit, extra::kRegion, extra::kRegion + 1};
    case ParamGroup::Label: return {Param::ExtraLogit, extra::kLabel, extra::kLabel + 1};
  }
  return {Param::Position, 0, 0};
}

inline const char* group_name(ParamGroup g) {
  constexpr std::array<const char*, kGroupCount> names = {"position", "scale",     "rotation", "opacity", "sh_dc",
                                                          "sh_rest",  "materials", "region",   "label"};
  return names[int(g)];
}

}  // namespace goris
