// glTF 2.0 binary (GLB) with KHR_gaussian_splatting (core/io/splat_formats.h has the layout): one mesh
// primitive of mode POINTS whose attributes carry the Gaussians, float32 throughout.
#include <cmath>
#include <cstring>
#include <map>

#include <nlohmann/json.hpp>

#include "core/io/splat_codec.h"
#include "core/io/splat_formats.h"

namespace goris {
namespace {
using namespace splat_detail;
using nlohmann::json;

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;
constexpr int kFloat = 5126, kUnsignedByte = 5121;
const std::string kExt = "KHR_gaussian_splatting";
const std::string kPrefix = "KHR_gaussian_splatting:";

// PLY (RDF) <-> glTF (LUF): the 180-degree turn about z. x and y change sign, so do the quaternion's x and
// y, and SH coefficient k >= 1 when its basis function is odd in x and y together (3DGS order y z x, ...).
constexpr float kFlipP[3] = {-1, -1, 1};
constexpr float kFlipSh[15] = {-1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1};
constexpr int kCoeffsOfDegree[4] = {1, 3, 5, 7};

size_t align4(size_t n) { return (n + 3) & ~size_t(3); }

std::string sh_name(int degree, int coef) {
  return kPrefix + "SH_DEGREE_" + std::to_string(degree) + "_COEF_" + std::to_string(coef);
}

}  // namespace

std::vector<uint8_t> encode_glb(const GaussianPly& g, const std::string& name) {
  check_encodable(g, name);
  if (g.count == 0) throw Error(name, "a glTF accessor cannot hold an empty model");
  const size_t n = g.count, coeffs = size_t((g.sh_degree + 1) * (g.sh_degree + 1) - 1),
               rest = GaussianPly::rest_per_gaussian(g.sh_degree);
  std::vector<uint8_t> bin;
  json accessors = json::array(), views = json::array(), attributes = json::object();
  // One tightly packed buffer view and accessor per attribute, each 4-byte aligned.
  auto add = [&](const std::string& attr, const std::vector<float>& v, const char* type, bool bounds) {
    bin.resize(align4(bin.size()));
    const size_t offset = bin.size();
    bin.resize(offset + v.size() * 4);
    std::memcpy(bin.data() + offset, v.data(), v.size() * 4);
    views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", v.size() * 4}, {"target", 34962}});
    json a = {{"bufferView", views.size() - 1}, {"componentType", kFloat}, {"count", n}, {"type", type}};
    if (bounds) {
      float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
      for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], v[i * 3 + k]), hi[k] = std::max(hi[k], v[i * 3 + k]);
      a["min"] = {lo[0], lo[1], lo[2]};
      a["max"] = {hi[0], hi[1], hi[2]};
    }
    accessors.push_back(a);
    attributes[attr] = accessors.size() - 1;
  };
  std::vector<float> pos(n * 3), rot(n * 4), scale(n * 3), alpha(n), dc(n * 3), sh(n * 3);
  for (size_t i = 0; i < n; ++i) {
    float q[4];
    unit_quaternion(g, i, q);  // w x y z
    rot[i * 4 + 0] = -q[1], rot[i * 4 + 1] = -q[2], rot[i * 4 + 2] = q[3], rot[i * 4 + 3] = q[0];
    alpha[i] = sigmoid(g.opacity[i]);
    for (int a = 0; a < 3; ++a) {
      pos[i * 3 + a] = kFlipP[a] * g.positions[i * 3 + a];
      scale[i * 3 + a] = std::exp(g.scales[i * 3 + a]);
      if (!std::isfinite(scale[i * 3 + a]))
        throw Error(name, "cannot encode: the scale of Gaussian " + std::to_string(i) + " overflows a float");
      dc[i * 3 + a] = g.f_dc[i * 3 + a];
    }
  }
  add("POSITION", pos, "VEC3", true);
  add(kPrefix + "ROTATION", rot, "VEC4", false);
  add(kPrefix + "SCALE", scale, "VEC3", false);
  add(kPrefix + "OPACITY", alpha, "SCALAR", false);
  add(sh_name(0, 0), dc, "VEC3", false);
  for (int l = 1, k = 0; l <= g.sh_degree; ++l)
    for (int c = 0; c < kCoeffsOfDegree[l]; ++c, ++k) {
      for (size_t i = 0; i < n; ++i)
        for (int ch = 0; ch < 3; ++ch) sh[i * 3 + size_t(ch)] = kFlipSh[k] * g.f_rest[i * rest + size_t(ch) * coeffs + size_t(k)];
      add(sh_name(l, c), sh, "VEC3", false);
    }
  bin.resize(align4(bin.size()));
  // Built step by step: nested brace lists are ambiguous between arrays and objects in nlohmann::json.
  const json splat_ext = {{"kernel", "ellipse"}, {"colorSpace", "srgb_rec709_display"},
                          {"sortingMethod", "cameraDistance"}, {"projection", "perspective"}};
  json prim = json::object();
  prim["attributes"] = attributes;
  prim["mode"] = 0;  // POINTS
  prim["extensions"] = json::object();
  prim["extensions"][kExt] = splat_ext;
  json mesh = json::object();
  mesh["primitives"] = json::array({prim});
  json gltf = json::object();
  gltf["asset"] = {{"version", "2.0"}, {"generator", "GOR-IS Studio"}};
  gltf["extensionsUsed"] = json::array({kExt});
  gltf["scene"] = 0;
  gltf["scenes"] = json::array({json{{"nodes", json::array({0})}}});
  gltf["nodes"] = json::array({json{{"mesh", 0}}});
  gltf["buffers"] = json::array({json{{"byteLength", bin.size()}}});
  gltf["bufferViews"] = views;
  gltf["accessors"] = accessors;
  gltf["meshes"] = json::array({mesh});
  std::string text = gltf.dump();
  text.resize(align4(text.size()), ' ');
  std::vector<uint8_t> out;
  put_u32(out, kGlbMagic);
  put_u32(out, 2);
  put_u32(out, uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  put_u32(out, uint32_t(text.size()));
  put_u32(out, kJsonChunk);
  out.insert(out.end(), text.begin(), text.end());
  put_u32(out, uint32_t(bin.size()));
  put_u32(out, kBinChunk);
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

GaussianPly decode_glb(const uint8_t* data, size_t size, const std::string& name) {
  if (size < 12 || get_u32(data) != kGlbMagic) throw Error(name, "not a GLB file (no glTF magic number)");
  if (get_u32(data + 4) != 2) throw Error(name, "glTF version " + std::to_string(get_u32(data + 4)) + " is not supported (2 is)");
  if (get_u32(data + 8) > size)
    throw Error(name, "truncated: the GLB header says " + std::to_string(get_u32(data + 8)) + " bytes, the file has " +
                          std::to_string(size));
  // Chunks: JSON first, then BIN.
  const uint8_t *json_at = nullptr, *bin_at = nullptr;
  size_t json_len = 0, bin_len = 0;
  for (size_t at = 12; at < size;) {
    if (size - at < 8) throw Error(name, "truncated GLB chunk header at byte " + std::to_string(at));
    const size_t len = get_u32(data + at);
    const uint32_t type = get_u32(data + at + 4);
    if (len > size - at - 8) throw Error(name, "truncated: a GLB chunk of " + std::to_string(len) + " bytes runs past the end");
    if (type == kJsonChunk && !json_at) json_at = data + at + 8, json_len = len;
    else if (type == kBinChunk && !bin_at) bin_at = data + at + 8, bin_len = len;
    at += 8 + len;
  }
  if (!json_at) throw Error(name, "GLB without a JSON chunk");

  try {
    const json j = json::parse(json_at, json_at + json_len);
    const json* prim = nullptr;
    static const json kNone = json::array();
    auto list = [](const json& parent, const char* key) -> const json& {
      return parent.is_object() && parent.contains(key) && parent[key].is_array() ? parent[key] : kNone;
    };
    for (const json& mesh : list(j, "meshes"))
      for (const json& p : list(mesh, "primitives"))
        if (!prim && p.is_object() && p.contains("attributes") && p["attributes"].is_object() &&
            p["attributes"].contains("POSITION") && p["attributes"].contains(kPrefix + "SCALE"))
          prim = &p;
    if (!prim) throw Error(name, "no mesh primitive with KHR_gaussian_splatting (POSITION and the splat attributes)");
    const json& attrs = (*prim)["attributes"];
    const json& accessors = j.at("accessors");
    const json& views = j.at("bufferViews");
    size_t n = 0;
    // The floats of attribute `attr` (`comps` per Gaussian), bounds-checked against the BIN chunk.
    auto read = [&](const std::string& attr, int comps, bool required) -> std::vector<float> {
      if (!attrs.contains(attr)) {
        if (required) throw Error(name, "glTF: the splat attribute " + attr + " is missing");
        return {};
      }
      const json& a = accessors.at(attrs[attr].get<size_t>());
      static const std::map<std::string, int> kComps = {{"SCALAR", 1}, {"VEC3", 3}, {"VEC4", 4}};
      const auto t = kComps.find(a.at("type").get<std::string>());
      if (t == kComps.end() || t->second != comps)
        throw Error(name, "glTF: " + attr + " has type " + a.at("type").get<std::string>() + ", expected " +
                              (comps == 1 ? "SCALAR" : comps == 3 ? "VEC3" : "VEC4"));
      const int ct = a.at("componentType").get<int>();
      if (ct != kFloat && !(ct == kUnsignedByte && a.value("normalized", false)))
        throw Error(name, "glTF: " + attr + " has component type " + std::to_string(ct) + "; float (5126) is supported");
      const size_t count = a.at("count").get<size_t>();
      if (attr == "POSITION") n = count;
      if (count != n) throw Error(name, "glTF: " + attr + " has " + std::to_string(count) + " items, POSITION " + std::to_string(n));
      const json& v = views.at(a.at("bufferView").get<size_t>());
      if (v.value("buffer", 0) != 0 || !bin_at) throw Error(name, "glTF: " + attr + " is not in the GLB's binary chunk");
      const size_t csize = ct == kFloat ? 4 : 1, item = size_t(comps) * csize;
      const size_t stride = v.value("byteStride", item);
      const size_t view_at = v.value("byteOffset", size_t(0)), view_len = v.at("byteLength").get<size_t>();
      const size_t at = a.value("byteOffset", size_t(0));
      auto outside = [&] {
        return Error(name, "truncated or corrupt: the data of " + attr + " lies outside its buffer view or the binary chunk");
      };
      if (stride < item || view_at > bin_len || view_len > bin_len - view_at || at > view_len) throw outside();
      const size_t span = view_len - at;  // bytes from the first item to the view's end
      if (count > 0 && (span < item || count - 1 > (span - item) / stride)) throw outside();
      const size_t start = view_at + at;
      std::vector<float> out(count * size_t(comps));
      for (size_t i = 0; i < count; ++i)
        for (int k = 0; k < comps; ++k) {
          const uint8_t* p = bin_at + start + i * stride + size_t(k) * csize;
          out[i * size_t(comps) + size_t(k)] = ct == kFloat ? get_f32(p) : float(*p) / 255.0f;
        }
      return out;
    };
    const std::vector<float> pos = read("POSITION", 3, true);
    const std::vector<float> rot = read(kPrefix + "ROTATION", 4, true), scale = read(kPrefix + "SCALE", 3, true);
    std::vector<float> alpha = read(kPrefix + "OPACITY", 1, false), dc = read(sh_name(0, 0), 3, false);
    if (alpha.empty() || dc.empty()) {  // the COLOR_0 fallback: display colour and alpha
      const std::vector<float> color = read("COLOR_0", 4, true);
      if (alpha.empty())
        for (size_t i = 0; i < n; ++i) alpha.push_back(color[i * 4 + 3]);
      if (dc.empty())
        for (size_t i = 0; i < n; ++i)
          for (int a = 0; a < 3; ++a) dc.push_back((color[i * 4 + size_t(a)] - 0.5f) / kShC0);
    }
    int degree = 0;
    while (degree < 3 && attrs.contains(sh_name(degree + 1, 0))) ++degree;
    GaussianPly g = sized_model(n, degree);
    const size_t coeffs = size_t((degree + 1) * (degree + 1) - 1), rest = GaussianPly::rest_per_gaussian(degree);
    for (int l = 1, k = 0; l <= degree; ++l)
      for (int c = 0; c < kCoeffsOfDegree[l]; ++c, ++k) {
        const std::vector<float> sh = read(sh_name(l, c), 3, true);
        for (size_t i = 0; i < n; ++i)
          for (size_t ch = 0; ch < 3; ++ch) g.f_rest[i * rest + ch * coeffs + size_t(k)] = kFlipSh[k] * sh[i * 3 + ch];
      }
    for (size_t i = 0; i < n; ++i) {
      for (int a = 0; a < 3; ++a) {
        g.positions[i * 3 + a] = kFlipP[a] * pos[i * 3 + a];
        const float s = scale[i * 3 + a];
        if (!(s > 0) || !std::isfinite(s))
          throw Error(name, "Gaussian " + std::to_string(i) + ": scale " + std::to_string(s) + " is not a positive finite number");
        g.scales[i * 3 + a] = std::log(s);
        g.f_dc[i * 3 + a] = dc[i * 3 + a];
      }
      g.opacity[i] = logit_of_alpha(alpha[i]);
      const float* q = &rot[i * 4];  // x y z w
      float* r = &g.rotations[i * 4];
      r[0] = q[3], r[1] = -q[0], r[2] = -q[1], r[3] = q[2];
    }
    check_decoded(g, name);
    return g;
  } catch (const json::exception& e) {
    throw Error(name, std::string("glTF JSON: ") + e.what());
  }
}

}  // namespace goris
