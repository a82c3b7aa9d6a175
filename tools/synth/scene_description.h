#pragma once
// The scene `goris synth` renders: plain data written as scene.json, which resources/synth/render_scene.py
// (run inside Blender) reads to build and render the scene. Units are Blender's (metres, Z up).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace goris::synth {

using Vec3 = std::array<double, 3>;

// A procedural colour texture mixed between two colours (Blender shader nodes).
struct Texture {
  std::string kind;  // "checker", "noise", "brick", "marble"
  Vec3 color1{}, color2{};
  double scale = 1.0;
};

// Principled BSDF parameters; `texture`, when present, drives the base colour.
struct Material {
  Vec3 color{0.8, 0.8, 0.8};
  double metallic = 0.0;
  double roughness = 0.5;
  double specular = 0.5;  // Blender's "Specular": dielectric F0 = 0.08 * specular
  std::optional<Texture> texture;
};

struct SceneObject {
  std::string name;
  std::string shape;  // "cube", "sphere", "ico_sphere", "cylinder", "cone", "torus", "monkey", "plane"
  Vec3 location{}, rotation{}, scale{1, 1, 1};  // rotation: XYZ Euler angles in radians
  Material material;
  bool target = false;  // the object to remove (exactly one per scene)
  bool glossy = false;  // counted in the glossy-surface mask (gloss_XXX.png)
};

struct AreaLight {
  Vec3 location{}, look_at{};
  double size = 2.0;      // side of the square emitter
  double energy = 300.0;  // watts
  Vec3 color{1, 1, 1};
};

// The environment: Blender's Hosek-Wilkie sky ("sky") or a horizon-to-zenith gradient ("gradient").
struct World {
  std::string kind = "sky";
  double strength = 0.5;
  Vec3 sun_direction{0, 0, 1};  // sky
  double turbidity = 3.0;       // sky
  Vec3 horizon{}, zenith{};     // gradient
};

struct CameraView {
  Vec3 location{}, look_at{};
};

struct RenderSettings {
  int resolution = 128;  // square images
  int samples = 64;      // Cycles samples per pixel of the colour renders
  int mask_samples = 16; // samples of the mask render (no bounces: cheap; sets the anti-aliasing steps)
  int threads = 2;
  int tile = 64;
  int seed = 0;          // Cycles' sampling seed
};

struct SceneDescription {
  std::string preset;
  uint32_t seed = 0;
  RenderSettings render;
  World world;
  std::vector<AreaLight> lights;
  std::vector<SceneObject> objects;
  double camera_angle_x = 0.69;  // horizontal field of view, radians
  std::vector<CameraView> train_cameras, test_cameras;
  bool ground_truth_maps = true;  // train/gt/{diffcol,glosscol,normal,depth}_XXX.exr
};

nlohmann::json to_json(const SceneDescription& scene);

}  // namespace goris::synth
