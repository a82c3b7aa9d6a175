#pragma once
// Scene presets of `goris synth`: procedural, and deterministic for a seed (same options -> identical
// scene description on every platform).
//   glossy-table  round table top, polished metal or marble by seed (roughness 0.01-0.25), 3-5 textured
//                 diffuse objects, one of them (near the centre) the target
//   marble        the same with a marble top and Suzanne as the target
//   lambert-room  diffuse floor and wall, area light, no glossy surface (a failure case of the method)
//   twin-mirrors  steel table and a vertical mirror facing it (the other failure case)
//   occluded      the target sits behind a bigger object, hidden from most views
#include <cstdint>
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
};

const std::vector<std::string>& preset_names();

// Throws goris::Error for an unknown preset (the message lists the presets) or out-of-range options.
SceneDescription make_scene(const SynthOptions& options);

}  // namespace goris::synth
