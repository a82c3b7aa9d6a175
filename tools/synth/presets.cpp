#include "tools/synth/presets.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "core/util/error.h"
#include "tools/synth/cameras.h"
#include "tools/synth/random.h"

namespace goris::synth {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kTableRadius = 1.5;

Vec3 hsv(double h, double s, double v) {
  double c = v * s, hp = std::fmod(h, 1.0) * 6.0, x = c * (1 - std::abs(std::fmod(hp, 2.0) - 1)), m = v - c;
  Vec3 rgb = hp < 1 ? Vec3{c, x, 0} : hp < 2 ? Vec3{x, c, 0} : hp < 3 ? Vec3{0, c, x}
           : hp < 4 ? Vec3{0, x, c} : hp < 5 ? Vec3{x, 0, c} : Vec3{c, 0, x};
  return {rgb[0] + m, rgb[1] + m, rgb[2] + m};
}

Vec3 vivid(Rng& rng) { return hsv(rng.unit(), rng.uniform(0.5, 0.9), rng.uniform(0.45, 0.85)); }

// A rough, textured dielectric: the "diffuse objects" of the scenes.
Material diffuse_material(Rng& rng) {
  Material m;
  m.color = vivid(rng);
  m.roughness = rng.uniform(0.5, 0.9);
  m.specular = rng.uniform(0.2, 0.5);
  Texture t;
  t.kind = rng.pick(std::vector<std::string>{"checker", "noise", "brick"});
  t.color1 = m.color;
  t.color2 = rng.chance(0.5) ? vivid(rng) : hsv(rng.unit(), 0.1, rng.uniform(0.7, 0.95));
  t.scale = t.kind == "noise" ? rng.uniform(3, 8) : rng.uniform(2, 5);
  m.texture = t;
  return m;
}

Material metal_top(Rng& rng, double roughness) {
  Material m;
  double tint = rng.uniform(0.0, 0.12);
  m.color = hsv(rng.unit(), tint, rng.uniform(0.75, 0.95));
  m.metallic = 1.0;
  m.roughness = roughness;
  return m;
}

Material marble_top(Rng& rng, double roughness) {
  Material m;
  m.roughness = roughness;
  m.specular = rng.uniform(0.6, 1.0);  // F0 0.048-0.08: polished stone
  Texture t;
  t.kind = "marble";
  t.color1 = hsv(rng.unit(), rng.uniform(0.0, 0.1), rng.uniform(0.85, 0.95));
  t.color2 = hsv(rng.unit(), rng.uniform(0.0, 0.2), rng.uniform(0.25, 0.5));
  t.scale = rng.uniform(1.0, 2.5);
  m.color = t.color1;
  m.texture = t;
  return m;
}

// A dark glossy dielectric (lacquer, plastic): F0 0.04-0.08, so the reflections are dimmer than a metal's and
// uncoloured, over a dark base colour.
Material dielectric_top(Rng& rng, double roughness) {
  Material m;
  m.color = hsv(rng.unit(), rng.uniform(0.2, 0.6), rng.uniform(0.05, 0.25));
  m.roughness = roughness;
  m.specular = rng.uniform(0.5, 1.0);
  return m;
}

SceneObject table_top(const Material& m) {
  SceneObject o{"table", "cylinder", {0, 0, -0.04}, {0, 0, 0}, {kTableRadius, kTableRadius, 0.04}, m, false, true};
  return o;
}

// Height of an object's origin above its base, for a uniform scale s (Blender's primitive sizes).
double rest_height(const std::string& shape, double s) {
  if (shape == "torus") return 0.3 * s;
  if (shape == "monkey") return 0.75 * s;
  return s;  // cube (size 2), spheres, cylinder and cone (depth 2)
}

SceneObject object_on_table(Rng& rng, const std::string& name, const std::string& shape, double x, double y, double s) {
  SceneObject o;
  o.name = name;
  o.shape = shape;
  o.scale = {s, s, s};
  if (shape == "cylinder" || shape == "cone") o.scale[2] = s * rng.uniform(0.8, 1.4);
  o.location = {x, y, rest_height(shape, o.scale[2])};
  o.rotation = {0, 0, rng.uniform(0, 2 * kPi)};
  if (shape == "monkey") o.rotation[0] = 0.25;  // tilt Suzanne back so she rests on her chin
  o.material = diffuse_material(rng);
  return o;
}

// Fills the table with `count` objects around the centre, keeping them apart (rejection sampling with a
// bounded number of tries, so a seed always gives a scene).
void scatter_objects(Rng& rng, SceneDescription& s, int count, double inner, double outer) {
  const std::vector<std::string> shapes{"cube", "sphere", "cylinder", "cone", "torus", "ico_sphere"};
  for (int i = 0; i < count; ++i) {
    double size = rng.uniform(0.18, 0.32), x = 0, y = 0;
    for (int tries = 0; tries < 64; ++tries) {
      double r = rng.uniform(inner, outer), a = rng.uniform(0, 2 * kPi);
      x = r * std::cos(a), y = r * std::sin(a);
      bool clear = true;
      for (const auto& o : s.objects)
        if (o.name != "table" && o.name != "floor" && o.name != "wall" && o.name != "mirror" &&
            std::hypot(o.location[0] - x, o.location[1] - y) < size + std::max(o.scale[0], o.scale[1]) + 0.1)
          clear = false;
      if (clear) break;
    }
    s.objects.push_back(object_on_table(rng, "object_" + std::to_string(i + 1), rng.pick(shapes), x, y, size));
  }
}

void add_environment(Rng& rng, SceneDescription& s) {
  if (rng.chance(0.5)) {
    s.world.kind = "sky";
    double elevation = rng.uniform(0.35, 1.1), azimuth = rng.uniform(0, 2 * kPi);
    s.world.sun_direction = {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
    s.world.turbidity = rng.uniform(2.0, 5.0);
    s.world.strength = rng.uniform(0.25, 0.45);
  } else {
    s.world.kind = "gradient";
    s.world.horizon = hsv(rng.uniform(0.05, 0.15), rng.uniform(0.05, 0.3), rng.uniform(0.7, 1.0));
    s.world.zenith = hsv(rng.uniform(0.55, 0.65), rng.uniform(0.3, 0.7), rng.uniform(0.5, 0.9));
    s.world.strength = rng.uniform(0.6, 1.0);
  }
  double a = rng.uniform(0, 2 * kPi), r = rng.uniform(1.5, 2.5);
  AreaLight l;
  l.location = {r * std::cos(a), r * std::sin(a), rng.uniform(3.5, 4.5)};
  l.look_at = {0, 0, 0};
  l.size = rng.uniform(1.5, 3.0);
  l.energy = rng.uniform(250, 450);
  l.color = hsv(rng.uniform(0.05, 0.15), rng.uniform(0.0, 0.15), 1.0);
  s.lights.push_back(l);
}

SceneObject make_target(Rng& rng, const std::string& shape, double x, double y, double size, const Vec3& color) {
  SceneObject t = object_on_table(rng, "target", shape, x, y, size);
  t.target = true;
  t.material.color = color;
  t.material.texture->color1 = color;
  return t;
}

double table_roughness(Rng& rng) { return rng.uniform(0.01, 0.25); }

CameraRing table_ring() {
  CameraRing ring;
  ring.look_at = {0, 0, 0.15};
  ring.radius = 5.2;
  ring.min_elevation = 0.35;  // 20 degrees
  ring.max_elevation = 1.22;  // 70 degrees
  return ring;
}

CameraRing glossy_table(Rng& rng, SceneDescription& s, bool force_marble) {
  double roughness = table_roughness(rng);
  bool marble = force_marble || rng.chance(0.5);
  s.objects.push_back(table_top(marble ? marble_top(rng, roughness) : metal_top(rng, roughness)));
  double r = rng.uniform(0.0, 0.3), a = rng.uniform(0, 2 * kPi);
  std::string shape = force_marble ? "monkey" : rng.pick(std::vector<std::string>{"monkey", "sphere", "cube", "cylinder", "torus"});
  s.objects.push_back(make_target(rng, shape, r * std::cos(a), r * std::sin(a), rng.uniform(0.3, 0.4), vivid(rng)));
  scatter_objects(rng, s, rng.integer(2, 4), 0.75, 1.2);
  add_environment(rng, s);
  return table_ring();
}

CameraRing lambert_room(Rng& rng, SceneDescription& s) {
  Material floor = diffuse_material(rng), wall = diffuse_material(rng);
  floor.specular = wall.specular = 0.0;
  floor.roughness = wall.roughness = 1.0;
  wall.texture.reset();
  s.objects.push_back({"floor", "plane", {0, 0, 0}, {0, 0, 0}, {3, 3, 1}, floor, false, false});
  s.objects.push_back({"wall", "plane", {0, 1.8, 1.5}, {kPi / 2, 0, 0}, {3, 1.5, 1}, wall, false, false});
  s.objects.push_back(make_target(rng, "cube", rng.uniform(-0.3, 0.3), rng.uniform(0.0, 0.4), rng.uniform(0.3, 0.4), {0.8, 0.08, 0.05}));
  scatter_objects(rng, s, rng.integer(2, 4), 0.8, 1.3);
  for (auto& o : s.objects) o.material.specular = 0.0, o.material.roughness = 1.0;
  add_environment(rng, s);
  s.world.strength *= 0.5;
  s.lights[0].location[1] = -std::abs(s.lights[0].location[1]);  // light in front of the wall
  CameraRing ring = table_ring();
  ring.radius = 5.5;
  ring.min_azimuth = -kPi + 0.35, ring.max_azimuth = -0.35;  // in front of the wall (wall at +Y)
  ring.max_elevation = 1.0;
  return ring;
}

// A matte material (no specular lobe) coloured by a noise texture between two colours.
Material matte_noise(const Vec3& color1, const Vec3& color2, double scale) {
  Material m;
  m.roughness = 1.0, m.specular = 0.0;
  m.color = color1;
  m.texture = Texture{"noise", color1, color2, scale};
  return m;
}

// Outdoors, nothing glossy: a box in front of a bench on a wide textured lawn under a sky. The case where a
// large flat ground with fine texture must not be taken for a glossy plane (`--mode auto`).
CameraRing lambert_ground(Rng& rng, SceneDescription& s) {
  // One draw per statement: the order of the random draws is the scene (arguments have no fixed order).
  const Vec3 grass1 = hsv(rng.uniform(0.22, 0.30), rng.uniform(0.5, 0.8), rng.uniform(0.25, 0.45));
  const Vec3 grass2 = hsv(rng.uniform(0.17, 0.25), rng.uniform(0.4, 0.7), rng.uniform(0.45, 0.65));
  const double blades = rng.uniform(20, 40);
  s.objects.push_back({"floor", "plane", {0, 0, 0}, {0, 0, 0}, {6, 6, 1}, matte_noise(grass1, grass2, blades), false, false});
  const Vec3 wood1 = hsv(rng.uniform(0.05, 0.09), rng.uniform(0.5, 0.7), rng.uniform(0.35, 0.5));
  const Vec3 wood2 = hsv(rng.uniform(0.05, 0.09), rng.uniform(0.4, 0.6), rng.uniform(0.55, 0.7));
  const Material wood = matte_noise(wood1, wood2, rng.uniform(4, 8));
  const double turn = rng.uniform(-0.4, 0.4), c = std::cos(turn), sn = std::sin(turn), back = 0.7;
  auto on_bench = [&](const std::string& name, double along, double z, const Vec3& scale) {
    return SceneObject{name, "cube", {along * c - back * sn, along * sn + back * c, z}, {0, 0, turn}, scale, wood, false, false};
  };
  s.objects.push_back(on_bench("bench_seat", 0.0, 0.45, {0.75, 0.2, 0.04}));
  s.objects.push_back(on_bench("bench_back", 0.0, 0.75, {0.75, 0.03, 0.2}));
  for (int side : {-1, 1}) s.objects.push_back(on_bench(side < 0 ? "bench_leg_1" : "bench_leg_2", 0.65 * side, 0.2, {0.04, 0.18, 0.2}));
  // The target: a cardboard box on the grass in front of the bench.
  s.objects.push_back(make_target(rng, "cube", rng.uniform(-0.4, 0.4), rng.uniform(-0.3, 0.1), rng.uniform(0.2, 0.28),
                                  hsv(rng.uniform(0.07, 0.1), rng.uniform(0.4, 0.6), rng.uniform(0.55, 0.75))));
  scatter_objects(rng, s, rng.integer(1, 3), 1.0, 1.6);
  for (auto& o : s.objects) o.material.specular = 0.0, o.material.roughness = 1.0;
  add_environment(rng, s);
  s.world.kind = "sky";
  const double elevation = rng.uniform(0.5, 1.1), azimuth = rng.uniform(0, 2 * kPi);
  s.world.sun_direction = {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
  s.world.turbidity = rng.uniform(2.0, 4.0);
  s.world.strength = rng.uniform(0.5, 0.8);
  CameraRing ring = table_ring();
  ring.look_at = {0, 0.2, 0.3};
  ring.radius = 5.5;
  ring.min_elevation = 0.3, ring.max_elevation = 0.9;
  return ring;
}

CameraRing twin_mirrors(Rng& rng, SceneDescription& s) {
  s.objects.push_back(table_top(metal_top(rng, 0.02)));
  Material mirror;
  mirror.color = {0.95, 0.95, 0.95};
  mirror.metallic = 1.0;
  mirror.roughness = 0.0;
  s.objects.push_back({"mirror", "plane", {0, 1.6, 0.7}, {kPi / 2, 0, 0}, {1.3, 0.7, 1}, mirror, false, true});
  s.objects.push_back(make_target(rng, "sphere", rng.uniform(-0.3, 0.3), rng.uniform(-0.2, 0.3), rng.uniform(0.25, 0.35), {0.85, 0.05, 0.05}));
  scatter_objects(rng, s, rng.integer(2, 3), 0.75, 1.15);
  add_environment(rng, s);
  CameraRing ring = table_ring();
  ring.min_azimuth = -kPi + 0.3, ring.max_azimuth = -0.3;  // in front of the mirror (mirror at +Y)
  ring.max_elevation = 1.0;
  return ring;
}

CameraRing occluded(Rng& rng, SceneDescription& s) {
  double roughness = table_roughness(rng);
  s.objects.push_back(table_top(rng.chance(0.5) ? marble_top(rng, roughness) : metal_top(rng, roughness)));
  // The cameras look from -Y over a +-75 degree sector; a tall block stands between them and the small
  // target. The block (0.9 wide, 1.1 high) hides the target from the middle of the sector and from every
  // elevation used (seeing over it would take ~60 degrees); only the outer views see past its sides, so
  // the target is visible in about a quarter to a third of the views - enough to select it, too few to see behind it.
  SceneObject block = object_on_table(rng, "occluder", "cube", 0, -0.1, 0.45);
  block.scale = {0.45, 0.25, 0.55};
  block.location[2] = 0.55;
  block.rotation = {0, 0, 0};
  s.objects.push_back(block);
  s.objects.push_back(make_target(rng, rng.pick(std::vector<std::string>{"sphere", "cube", "torus"}), rng.uniform(-0.1, 0.1), 0.55, 0.18, vivid(rng)));
  scatter_objects(rng, s, rng.integer(1, 3), 1.0, 1.25);
  add_environment(rng, s);
  CameraRing ring = table_ring();
  ring.min_azimuth = -kPi / 2 - 1.3, ring.max_azimuth = -kPi / 2 + 1.3;
  ring.min_elevation = 0.2, ring.max_elevation = 0.9;
  return ring;
}

using PresetFn = std::function<CameraRing(Rng&, SceneDescription&)>;

const std::map<std::string, PresetFn>& presets() {
  static const std::map<std::string, PresetFn> p{
      {"glossy-table", [](Rng& r, SceneDescription& s) { return glossy_table(r, s, false); }},
      {"marble", [](Rng& r, SceneDescription& s) { return glossy_table(r, s, true); }},
      {"lambert-room", lambert_room},
      {"lambert-ground", lambert_ground},
      {"twin-mirrors", twin_mirrors},
      {"occluded", occluded},
  };
  return p;
}

void check_name(const char* what, const std::optional<std::string>& v, const std::vector<std::string>& names) {
  if (!v || std::find(names.begin(), names.end(), *v) != names.end()) return;
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  throw Error("goris synth", std::string(what) + ": unknown value '" + *v + "' (" + list + ")");
}

bool is_diffuse_extra(const SceneObject& o) { return o.name.rfind("object_", 0) == 0; }

// The overrides of SynthOptions, applied after the preset drew its scene. Their own random choices come
// from a second generator, so the preset's draws - and a scene without overrides - stay the seed's.
void apply_overrides(const SynthOptions& o, SceneDescription& s, CameraRing& ring) {
  Rng rng(o.seed ^ 0x9e3779b9u);
  auto table = std::find_if(s.objects.begin(), s.objects.end(), [](const SceneObject& x) { return x.name == "table"; });
  const bool table_override = o.table_material || o.table_shape || o.table_roughness;
  if (table_override && table == s.objects.end())
    throw Error("goris synth", "--table-*: preset '" + o.preset + "' has no table top");
  if (o.table_material) {
    const double r = table->material.roughness;
    table->material = *o.table_material == "metal"    ? metal_top(rng, r)
                      : *o.table_material == "marble" ? marble_top(rng, r)
                                                      : dielectric_top(rng, r);
  }
  if (o.table_roughness) {
    const double r = *o.table_roughness;
    if (!(r >= 0.0 && r <= 1.0))
      throw Error("goris synth", "--table-roughness must be between 0 and 1, got " + std::to_string(r));
    table->material.roughness = r;
  }
  if (o.table_shape == "rect") {
    table->shape = "cube";
    table->scale = {1.8, 1.3, 0.04};
    table->rotation = {0, 0, rng.uniform(0, kPi)};
  } else if (o.table_shape == "floor") {
    table->shape = "plane";
    table->scale = {3.5, 3.5, 1};
    table->location = {0, 0, 0};
  }
  auto target = std::find_if(s.objects.begin(), s.objects.end(), [](const SceneObject& x) { return x.target; });
  if (o.target_shape && target != s.objects.end()) {
    SceneObject& t = *target;
    const double a = rng.uniform(0, 2 * kPi);
    t.rotation = {0, 0, a};
    if (*o.target_shape == "convex") {
      const double size = rng.uniform(0.3, 0.4);
      t.shape = rng.chance(0.5) ? "sphere" : "cube";
      t.scale = {size, size, size};
    } else if (*o.target_shape == "thin") {
      t.shape = "cylinder", t.scale = {0.06, 0.06, 0.45};
    } else if (*o.target_shape == "holed") {
      t.shape = "torus", t.scale = {0.42, 0.42, 0.42};
      t.rotation = {kPi / 2, 0, a};  // upright: the hole faces the views
    } else if (*o.target_shape == "tall") {
      t.shape = "cylinder", t.scale = {0.2, 0.2, 0.7};
    } else {  // small
      t.shape = "sphere", t.scale = {0.15, 0.15, 0.15};
    }
    // Resting on the surface: an upright torus stands on its rim (major + minor radius = 1.0 x scale).
    t.location[2] = t.shape == "torus" && t.rotation[0] != 0 ? t.scale[2] : rest_height(t.shape, t.scale[2]);
  }
  if (o.objects) {
    s.objects.erase(std::remove_if(s.objects.begin(), s.objects.end(), is_diffuse_extra), s.objects.end());
    scatter_objects(rng, s, *o.objects, 0.75, 1.2);
  }
  if (o.camera_elevation == "low") ring.min_elevation = 0.21, ring.max_elevation = 0.61;
  if (o.camera_elevation == "high") ring.min_elevation = 0.79, ring.max_elevation = 1.36;
}

void check_range(const char* what, int v, int lo, int hi) {
  if (v < lo || v > hi)
    throw Error(std::string("goris synth"), std::string(what) + " must be between " + std::to_string(lo) + " and " +
                                                std::to_string(hi) + ", got " + std::to_string(v));
}
}  // namespace

const std::vector<std::string>& table_material_names() {
  static const std::vector<std::string> n{"metal", "dielectric", "marble"};
  return n;
}
const std::vector<std::string>& table_shape_names() {
  static const std::vector<std::string> n{"round", "rect", "floor"};
  return n;
}
const std::vector<std::string>& target_shape_names() {
  static const std::vector<std::string> n{"convex", "thin", "holed", "tall", "small"};
  return n;
}
const std::vector<std::string>& camera_elevation_names() {
  static const std::vector<std::string> n{"low", "mid", "high"};
  return n;
}

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names{"glossy-table", "marble", "lambert-room", "lambert-ground", "twin-mirrors",
                                              "occluded"};
  return names;
}

SceneDescription make_scene(const SynthOptions& o) {
  auto it = presets().find(o.preset);
  if (it == presets().end()) {
    std::string list;
    for (const auto& n : preset_names()) list += (list.empty() ? "" : ", ") + n;
    throw Error("goris synth", "unknown preset '" + o.preset + "' (presets: " + list + ")");
  }
  check_range("--res", o.resolution, 8, 4096);
  check_range("--spp", o.samples, 1, 65536);
  check_range("--train", o.train_views, 1, 1000);
  check_range("--test", o.test_views, 1, 1000);
  check_name("--table-material", o.table_material, table_material_names());
  check_name("--table-shape", o.table_shape, table_shape_names());
  check_name("--target-shape", o.target_shape, target_shape_names());
  check_name("--camera-elevation", o.camera_elevation, camera_elevation_names());
  if (o.objects) check_range("--objects", *o.objects, 0, 6);

  SceneDescription s;
  s.preset = o.preset;
  s.seed = o.seed;
  s.ground_truth_maps = o.ground_truth_maps;
  s.render.resolution = o.resolution;
  s.render.samples = o.samples;
  s.render.mask_samples = 16;
  s.render.seed = int(o.seed % 100000);
  s.camera_angle_x = 0.6911112070083618;  // the 50 mm lens of the shared GOR-IS scenes
  Rng rng(o.seed);
  CameraRing ring = it->second(rng, s);
  apply_overrides(o, s, ring);
  s.train_cameras = hemisphere_cameras(ring, o.train_views, 0.0);
  s.test_cameras = hemisphere_cameras(ring, o.test_views, 0.5);
  return s;
}

}  // namespace goris::synth
