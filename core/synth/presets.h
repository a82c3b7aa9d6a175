#pragma once
// Scene presets of `goris synth`: procedural, and deterministic for a seed (same options -> identical
// scene description on every platform).
//   glossy-table  round table top, polished metal or marble by seed (roughness 0.01-0.25), 3-5 textured
//                 diffuse objects, one of them (near the centre) the target
//   marble        the same with a marble top and Suzanne as the target
//   lambert-room  diffuse floor and wall, area light, no glossy surface (a failure case of the method)
//   twin-mirrors  steel table and a vertical mirror facing it (the other failure case)
//   occluded      the target sits behind a bigger object, hidden from most views
// table_roughness overrides the glossy table top's roughness (the stability bench's extreme 0.0 and 1.0)
// and leaves everything else of the seed's scene as it was.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/synth/scene_description.h"

namespace goris::synth {

struct SynthOptions {
  std::string preset = "glossy-table";
  int resolution = 128;
  int samples = 64;
  int train_views = 40;
  int test_views = 20;
  uint32_t seed = 1;
  bool ground_truth_maps = true;
  std::optional<double> table_roughness;  // in [0, 1]; presets with a table top only
};

const std::vector<std::string>& preset_names();

// Throws goris::Error for an unknown preset (the message lists the presets), out-of-range options or a
// table roughness for a preset without a table top.
SceneDescription make_scene(const SynthOptions& options);

}  // namespace goris::synth
