// Scene presets of `goris synth`: deterministic for a seed, varied across seeds, every preset well formed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/synth/presets.h"
#include "core/util/error.h"

using namespace goris::synth;

namespace {
std::string scene_json(const std::string& preset, uint32_t seed) {
  SynthOptions o;
  o.preset = preset;
  o.seed = seed;
  return to_json(make_scene(o)).dump();
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
  try {
    make_scene(o);
    FAIL() << "expected an error";
  } catch (const goris::Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("no-such-scene"), std::string::npos) << msg;
    for (const auto& p : preset_names()) EXPECT_NE(msg.find(p), std::string::npos) << msg;
  }
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
      EXPECT_EQ(glossy, p == "lambert-room" ? 0 : p == "twin-mirrors" ? 2 : 1) << p;
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
