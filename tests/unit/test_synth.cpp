// Scene presets of `goris synth`: deterministic for a seed, varied across seeds, every preset well formed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/util/error.h"
#include "tools/synth/presets.h"

using namespace goris::synth;

namespace {
std::string scene_json(const std::string& preset, uint32_t seed) {
  SynthOptions o;
  o.preset = preset;
  o.seed = seed;
  return to_json(make_scene(o)).dump();
}

// make_scene's error message for options it must refuse ("" when it accepted them).
std::string error_of(const SynthOptions& o) {
  try {
    make_scene(o);
  } catch (const goris::Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(SynthPresets, SameSeedGivesIdenticalSceneJson) {
  for (const auto& p : preset_names()) EXPECT_EQ(scene_json(p, 7), scene_json(p, 7)) << p;
}

TEST(SynthPresets, DifferentSeedsGiveDifferentScenes) {
  for (const auto& p : preset_names()) EXPECT_NE(scene_json(p, 1), scene_json(p, 2)) << p;
}

TEST(SynthPresets, UnknownPresetListsThePresets) {
  SynthOptions o;
  o.preset = "no-such-scene";
  const std::string msg = error_of(o);
  EXPECT_NE(msg.find("no-such-scene"), std::string::npos) << msg;
  for (const auto& p : preset_names()) EXPECT_NE(msg.find(p), std::string::npos) << msg;
}

TEST(SynthPresets, BadCountsAreErrors) {
  SynthOptions o;
  o.train_views = 0;
  EXPECT_THROW(make_scene(o), goris::Error);
  o = {};
  o.resolution = 2;
  EXPECT_THROW(make_scene(o), goris::Error);
}

TEST(SynthPresets, EveryPresetSerialisesAWellFormedScene) {
  for (const auto& p : preset_names()) {
    SynthOptions o;
    o.preset = p;
    o.train_views = 12;
    o.test_views = 5;
    for (uint32_t seed : {1u, 2u, 3u, 99u}) {
      o.seed = seed;
      SceneDescription s = make_scene(o);
      nlohmann::json j = nlohmann::json::parse(to_json(s).dump());
      EXPECT_EQ(j["preset"], p);
      EXPECT_EQ(j["cameras"]["train"].size(), 12u);
      EXPECT_EQ(j["cameras"]["test"].size(), 5u);
      EXPECT_EQ(j["lights"].size(), 1u);
      int targets = 0, glossy = 0;
      for (const auto& obj : j["objects"]) {
        targets += obj["target"].get<bool>();
        glossy += obj["glossy"].get<bool>();
        double rough = obj["material"]["roughness"];
        EXPECT_GE(rough, 0.0);
        EXPECT_LE(rough, 1.0);
      }
      EXPECT_EQ(targets, 1) << p;
      EXPECT_EQ(glossy, p == "lambert-room" || p == "lambert-ground" ? 0 : p == "twin-mirrors" ? 2 : 1) << p;
      for (const auto& obj : j["objects"])
        if (obj["glossy"].get<bool>() && obj["name"] == "table") {
          double rough = obj["material"]["roughness"];
          EXPECT_GE(rough, 0.01);
          EXPECT_LE(rough, 0.25);
        }
      // Cameras on the upper hemisphere, train and test at different places.
      for (const auto* split : {&s.train_cameras, &s.test_cameras})
        for (const auto& c : *split) EXPECT_GT(c.location[2], c.look_at[2] + 0.5);
      for (const auto& a : s.test_cameras)
        for (const auto& b : s.train_cameras)
          EXPECT_GT(std::abs(a.location[0] - b.location[0]) + std::abs(a.location[1] - b.location[1]) +
                        std::abs(a.location[2] - b.location[2]),
                    1e-3);
    }
  }
}

TEST(SynthPresets, GlossyTableVariesMetalAndMarbleBySeed) {
  int metal = 0, marble = 0;
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    SynthOptions o;
    o.seed = seed;
    for (const auto& obj : make_scene(o).objects)
      if (obj.name == "table") (obj.material.metallic > 0.5 ? metal : marble)++;
  }
  EXPECT_GT(metal, 0);
  EXPECT_GT(marble, 0);
}

namespace {
// Whether the segment a -> b passes through the axis-aligned box centre +- half (slab test).
bool segment_hits_box(const Vec3& a, const Vec3& b, const Vec3& centre, const Vec3& half) {
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 3; ++k) {
    double d = b[k] - a[k], lo = centre[k] - half[k], hi = centre[k] + half[k];
    if (std::abs(d) < 1e-12) {
      if (a[k] < lo || a[k] > hi) return false;
      continue;
    }
    double u = (lo - a[k]) / d, v = (hi - a[k]) / d;
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u), t1 = std::min(t1, v);
    if (t0 > t1) return false;
  }
  return true;
}
}  // namespace

TEST(SynthPresets, OccludedHidesTheTargetFromMostButNotAllViews) {
  for (uint32_t seed : {1u, 2u, 3u, 4u, 5u}) {
    SynthOptions o;
    o.preset = "occluded";
    o.seed = seed;
    o.train_views = 40;
    SceneDescription s = make_scene(o);
    const SceneObject *block = nullptr, *target = nullptr;
    for (const auto& obj : s.objects) {
      if (obj.name == "occluder") block = &obj;
      if (obj.target) target = &obj;
    }
    ASSERT_TRUE(block && target);
    ASSERT_EQ(block->rotation[2], 0.0);  // the slab test below needs the block axis-aligned
    int hidden = 0;
    for (const auto& c : s.train_cameras) hidden += segment_hits_box(c.location, target->location, block->location, block->scale);
    EXPECT_GE(hidden, 40 / 2) << "seed " << seed;  // hidden from most views...
    EXPECT_LE(hidden, 40 - 4) << "seed " << seed;  // ...but some see it, so it can be selected
  }
}

TEST(SynthPresets, TableRoughnessOverridesOnlyTheTableTop) {
  for (const std::string preset : {"glossy-table", "twin-mirrors", "occluded"}) {
    SynthOptions o;
    o.preset = preset;
    o.seed = 5;
    const nlohmann::json base = to_json(make_scene(o));
    for (double r : {0.0, 1.0}) {
      o.table_roughness = r;
      nlohmann::json j = to_json(make_scene(o));
      int tables = 0;
      for (auto& obj : j["objects"])
        if (obj["name"] == "table") {
          EXPECT_EQ(obj["material"]["roughness"].get<double>(), r) << preset;
          obj["material"]["roughness"] = 0.5;
          ++tables;
        }
      EXPECT_EQ(tables, 1) << preset;
      nlohmann::json expected = base;  // everything else is the seed's scene unchanged
      for (auto& obj : expected["objects"])
        if (obj["name"] == "table") obj["material"]["roughness"] = 0.5;
      EXPECT_EQ(j.dump(), expected.dump()) << preset << " roughness " << r;
    }
  }
}

TEST(SynthPresets, TableRoughnessOutOfRangeOrWithoutATableIsAnError) {
  SynthOptions o;
  o.table_roughness = 1.5;
  EXPECT_THROW(make_scene(o), goris::Error);
  o.table_roughness = -0.1;
  EXPECT_THROW(make_scene(o), goris::Error);
  o.preset = "lambert-room";
  o.table_roughness = 0.5;
  try {
    make_scene(o);
    FAIL() << "expected an error";
  } catch (const goris::Error& e) {
    EXPECT_NE(std::string(e.what()).find("lambert-room"), std::string::npos) << e.what();
  }
}

namespace {
const nlohmann::json* object_named(const nlohmann::json& scene, const std::string& name) {
  for (const auto& o : scene["objects"])
    if (o["name"] == name) return &o;
  return nullptr;
}
const nlohmann::json* target_of(const nlohmann::json& scene) {
  for (const auto& o : scene["objects"])
    if (o["target"].get<bool>()) return &o;
  return nullptr;
}
}  // namespace

TEST(SynthPresets, OverridesChangeTheirChoiceAndKeepTheRestOfTheScene) {
  SynthOptions o;
  o.seed = 9;
  const nlohmann::json base = to_json(make_scene(o));
  o.table_material = "dielectric";
  o.table_roughness = 0.01;
  const nlohmann::json d = to_json(make_scene(o));
  const auto* table = object_named(d, "table");
  ASSERT_TRUE(table);
  EXPECT_EQ((*table)["material"]["metallic"].get<double>(), 0.0);
  EXPECT_EQ((*table)["material"]["roughness"].get<double>(), 0.01);
  EXPECT_GE((*table)["material"]["specular"].get<double>(), 0.5);  // F0 >= 0.04
  EXPECT_EQ((*target_of(d)).dump(), (*target_of(base)).dump());       // the target is the seed's
  EXPECT_EQ(d["cameras"].dump(), base["cameras"].dump());

  o = SynthOptions{};
  o.seed = 9;
  o.table_shape = "floor";
  const nlohmann::json floor_scene = to_json(make_scene(o));
  const auto* floor = object_named(floor_scene, "table");
  o.table_shape = "rect";
  const nlohmann::json rect = to_json(make_scene(o));
  EXPECT_EQ((*object_named(rect, "table"))["shape"], "cube");
  EXPECT_EQ((*floor)["shape"], "plane");
  EXPECT_TRUE((*floor)["glossy"].get<bool>());
}

TEST(SynthPresets, TargetShapesRestOnTheTable) {
  for (const auto& shape : target_shape_names()) {
    SynthOptions o;
    o.seed = 4;
    o.target_shape = shape;
    const nlohmann::json j = to_json(make_scene(o));
    const auto* t = target_of(j);
    ASSERT_TRUE(t) << shape;
    const double z = (*t)["location"][2].get<double>(), sz = (*t)["scale"][2].get<double>();
    EXPECT_GT(z, 0.0) << shape;
    if (shape == "tall") EXPECT_GE(2 * sz, 1.2) << "a tall target stands over 1.2 m";
    if (shape == "thin") EXPECT_LE((*t)["scale"][0].get<double>(), 0.1) << "a thin target";
    if (shape == "holed") EXPECT_EQ((*t)["shape"], "torus");
    if (shape == "small") EXPECT_LE(sz, 0.2);
  }
}

TEST(SynthPresets, ObjectCountAndElevationOverrides) {
  SynthOptions o;
  o.seed = 3;
  o.objects = 6;
  o.camera_elevation = "low";
  const nlohmann::json j = to_json(make_scene(o));
  int extras = 0;
  for (const auto& obj : j["objects"]) extras += obj["name"].get<std::string>().rfind("object_", 0) == 0;
  EXPECT_EQ(extras, 6);
  for (const auto& c : j["cameras"]["train"]) {
    const double dx = c["location"][0].get<double>(), dy = c["location"][1].get<double>();
    const double dz = c["location"][2].get<double>() - 0.15;
    EXPECT_LE(std::atan2(dz, std::hypot(dx, dy)), 0.62);  // 35 degrees
  }
}

TEST(SynthPresets, UnknownOverrideValuesListTheKnownOnes) {
  SynthOptions o;
  o.table_shape = "hexagon";
  const std::string m = error_of(o);
  EXPECT_NE(m.find("hexagon"), std::string::npos) << m;
  EXPECT_NE(m.find("floor"), std::string::npos) << m;
  o = SynthOptions{};
  o.objects = 9;
  EXPECT_THROW(make_scene(o), goris::Error);
  o = SynthOptions{};
  o.preset = "lambert-room";
  o.table_material = "metal";
  EXPECT_THROW(make_scene(o), goris::Error);
}

TEST(SynthPresets, LambertGroundIsAMatteLawnWithABenchAndABox) {
  SynthOptions o;
  o.preset = "lambert-ground";
  for (uint32_t seed : {1u, 7u, 113u}) {
    o.seed = seed;
    const SceneDescription s = make_scene(o);
    int bench = 0;
    for (const auto& obj : s.objects) {
      EXPECT_FALSE(obj.glossy) << obj.name;
      EXPECT_EQ(obj.material.specular, 0.0) << obj.name << ": nothing reflects";
      bench += obj.name.rfind("bench", 0) == 0;
      if (obj.name == "floor") {
        ASSERT_TRUE(obj.material.texture) << "a lawn, not a plain floor";
        EXPECT_GE(obj.material.texture->scale, 20.0) << "fine texture: the case auto mode must not take for a glossy plane";
        EXPECT_GE(obj.scale[0], 6.0);
      }
      if (obj.target) EXPECT_EQ(obj.shape, "cube");
    }
    EXPECT_EQ(bench, 4);
    EXPECT_EQ(s.world.kind, "sky");
  }
}
