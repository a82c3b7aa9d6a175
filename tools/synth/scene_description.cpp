#include "tools/synth/scene_description.h"

namespace goris::synth {
namespace {
using nlohmann::json;

json material_json(const Material& m) {
  json j{{"color", m.color}, {"metallic", m.metallic}, {"roughness", m.roughness}, {"specular", m.specular}};
  if (m.texture)
    j["texture"] = {{"kind", m.texture->kind}, {"color1", m.texture->color1}, {"color2", m.texture->color2},
                    {"scale", m.texture->scale}};
  else
    j["texture"] = nullptr;
  return j;
}

json cameras_json(const std::vector<CameraView>& views) {
  json a = json::array();
  for (const auto& v : views) a.push_back({{"location", v.location}, {"look_at", v.look_at}});
  return a;
}
}  // namespace

json to_json(const SceneDescription& s) {
  json objects = json::array();
  for (const auto& o : s.objects)
    objects.push_back({{"name", o.name}, {"shape", o.shape}, {"location", o.location}, {"rotation", o.rotation},
                       {"scale", o.scale}, {"material", material_json(o.material)}, {"target", o.target},
                       {"glossy", o.glossy}});
  json lights = json::array();
  for (const auto& l : s.lights)
    lights.push_back({{"location", l.location}, {"look_at", l.look_at}, {"size", l.size}, {"energy", l.energy},
                      {"color", l.color}});
  json world{{"kind", s.world.kind}, {"strength", s.world.strength}};
  if (s.world.kind == "sky") {
    world["sun_direction"] = s.world.sun_direction;
    world["turbidity"] = s.world.turbidity;
  } else {
    world["horizon"] = s.world.horizon;
    world["zenith"] = s.world.zenith;
  }
  const auto& r = s.render;
  return json{{"format", "goris-synth-scene"},
              {"version", 1},
              {"preset", s.preset},
              {"seed", s.seed},
              {"render",
               {{"res", r.resolution}, {"spp", r.samples}, {"mask_spp", r.mask_samples}, {"threads", r.threads},
                {"tile", r.tile}, {"seed", r.seed}}},
              {"world", world},
              {"lights", lights},
              {"objects", objects},
              {"camera_angle_x", s.camera_angle_x},
              {"cameras", {{"train", cameras_json(s.train_cameras)}, {"test", cameras_json(s.test_cameras)}}},
              {"ground_truth_maps", s.ground_truth_maps}};
}

}  // namespace goris::synth
