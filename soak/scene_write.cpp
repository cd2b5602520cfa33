#include "soak/scene_write.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "model/image_io.hpp"

namespace rastercmp::soak {
namespace {

using Json = nlohmann::ordered_json;

Json number(float v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return double(v);
}

bool needs_non_finite(const Scene& scene) {
  for (const Draw& d : scene.draws)
    for (const glm::vec4& p : d.positions_clip)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w) || p.w == 0)
        return true;
  return false;
}

// Adds the state keys that differ from the defaults to a draw object.
void add_state(const RasterState& s, Json& j) {
  const RasterState def;
  if (s.cull_mode != def.cull_mode) j["cull"] = to_string(s.cull_mode);
  if (s.front_face != def.front_face) j["front_face"] = to_string(s.front_face);
  if (s.polygon_mode != def.polygon_mode) j["polygon_mode"] = to_string(s.polygon_mode);
  if (s.line_mode != def.line_mode) j["line_mode"] = to_string(s.line_mode);
  if (s.line_width != def.line_width) j["line_width"] = double(s.line_width);
  if (s.depth.test_enable != def.depth.test_enable) j["depth_test"] = s.depth.test_enable;
  if (s.depth.write_enable != def.depth.write_enable) j["depth_write"] = s.depth.write_enable;
  if (s.depth.compare_op != def.depth.compare_op) j["depth_compare"] = to_string(s.depth.compare_op);
  if (s.depth_bias.enable) {
    Json b = Json::object();
    b["constant"] = double(s.depth_bias.constant_factor);
    b["slope"] = double(s.depth_bias.slope_factor);
    b["clamp"] = double(s.depth_bias.clamp);
    j["depth_bias"] = b;
  }
  if (s.depth_clamp) j["depth_clamp"] = true;
  if (s.depth_clip) j["depth_clip"] = *s.depth_clip;
}

}  // namespace

std::string scene_to_json_text(const Scene& scene) {
  Json j = Json::object();
  if (!scene.name.empty()) j["name"] = scene.name;
  if (!scene.description.empty()) j["description"] = scene.description;
  j["width"] = scene.width;
  j["height"] = scene.height;
  if (scene.depth_format != DepthFormat::D32Sfloat) j["depth_format"] = to_string(scene.depth_format);
  if (scene.depth_clear != 1.0f) j["depth_clear"] = double(scene.depth_clear);
  if (scene.samples != 1) j["samples"] = scene.samples;
  if (scene.viewport) {
    const Viewport& v = *scene.viewport;
    j["viewport"] = Json{{"x", double(v.x)},
                         {"y", double(v.y)},
                         {"width", double(v.width)},
                         {"height", double(v.height)},
                         {"min_depth", double(v.min_depth)},
                         {"max_depth", double(v.max_depth)}};
  }
  if (scene.scissor) {
    const Rect2D& r = *scene.scissor;
    j["scissor"] = Json{{"x", r.x}, {"y", r.y}, {"width", r.width}, {"height", r.height}};
  }
  j["space"] = "clip";
  if (!scene.methods.empty()) {
    Json m = Json::object();
    for (const MethodChoice& c : scene.methods) m[c.stage] = c.name;
    j["methods"] = m;
  }
  if (needs_non_finite(scene)) j["allow_non_finite"] = true;
  Json draws = Json::array();
  for (const Draw& d : scene.draws) {
    Json dj = Json::object();
    if (!d.name.empty()) dj["name"] = d.name;
    if (d.topology != Topology::TriangleList) dj["topology"] = to_string(d.topology);
    Json positions = Json::array();
    for (const glm::vec4& p : d.positions_clip)
      positions.push_back(Json::array({number(p.x), number(p.y), number(p.z), number(p.w)}));
    dj["positions"] = positions;
    if (!d.indices.empty()) dj["indices"] = d.indices;
    add_state(d.state, dj);
    draws.push_back(dj);
  }
  j["draws"] = draws;
  // One draw per line keeps a reduced scene readable and a large one diffable.
  std::string text = "{\n";
  bool first = true;
  for (auto& [key, value] : j.items()) {
    text += first ? "  " : ",\n  ";
    first = false;
    text += Json(key).dump() + ": ";
    if (key == "draws") {
      text += "[\n";
      for (size_t i = 0; i < value.size(); ++i)
        text += "    " + value[i].dump() + (i + 1 < value.size() ? ",\n" : "\n");
      text += "  ]";
    } else {
      text += value.dump();
    }
  }
  return text + "\n}\n";
}

void write_scene_file(const std::string& path, const Scene& scene) {
  write_text_file_atomic(path, scene_to_json_text(scene));
}

}  // namespace rastercmp::soak
