#pragma once
// Scene presets of `goris synth`: procedural, and deterministic for a seed (same options -> identical
// scene description on every platform).
//   glossy-table  round table top, polished metal or marble by seed (roughness 0.01-0.25), 3-5 textured
//                 diffuse objects, one of them (near the centre) the target
//   marble        the same with a marble top and Suzanne as the target
//   lambert-room  diffuse floor and wall, area light, no glossy surface (a failure case of the method)
//   twin-mirrors  steel table and a vertical mirror facing it (the other failure case)
//   occluded      the target sits behind a bigger object, hidden from most views
// The optional fields override one choice of the seed's scene (presets with a table top only) and leave
// the seed's other random choices as they were; unset, the scene is the seed's own.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tools/synth/scene_description.h"

namespace goris::synth {

struct SynthOptions {
  std::string preset = "glossy-table";
  int resolution = 128;
  int samples = 64;
  int train_views = 40;
  int test_views = 20;
  uint32_t seed = 1;
  bool ground_truth_maps = true;
  // The glossy surface's roughness in [0, 1] (0 = mirror; the stability bench's extremes 0.0 and 1.0).
  std::optional<double> table_roughness;
  // The glossy surface's material: "metal" (metallic, tinted grey), "dielectric" (dark lacquer, F0 0.04-0.08)
  // or "marble" (polished stone with veins).
  std::optional<std::string> table_material;
  // The glossy surface's shape: "round" (a 1.5 m radius disc), "rect" (a 3.6 x 2.6 m slab) or "floor" (a
  // 7 x 7 m plane reaching past the views' edges).
  std::optional<std::string> table_shape;
  // The target's shape: "convex" (sphere or cube), "thin" (a post 0.12 m across), "holed" (an upright
  // torus: the hole shows the table through it), "tall" (a 1.4 m column) or "small" (a 0.3 m sphere).
  std::optional<std::string> target_shape;
  // Diffuse objects besides the target, 0-6.
  std::optional<int> objects;
  // Camera elevations: "low" (12-35 degrees: grazing views, long reflections), "mid" (20-70, the
  // default) or "high" (45-78).
  std::optional<std::string> camera_elevation;
};

// The names each override accepts, for help texts and errors.
const std::vector<std::string>& table_material_names();
const std::vector<std::string>& table_shape_names();
const std::vector<std::string>& target_shape_names();
const std::vector<std::string>& camera_elevation_names();

const std::vector<std::string>& preset_names();

// Throws goris::Error for an unknown preset (the message lists the presets), out-of-range options or a
// table roughness for a preset without a table top.
SceneDescription make_scene(const SynthOptions& options);

}  // namespace goris::synth
