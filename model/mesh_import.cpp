#include "model/mesh_import.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/core.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "model/errors.hpp"
#include "model/scene_io.hpp"

namespace rastercmp {
namespace {

constexpr double kPi = 3.14159265358979323846;

enum class MeshTopology { Triangles, Lines, Points };

const char* topology_name(MeshTopology t) {
  switch (t) {
    case MeshTopology::Triangles: return "triangle_list";
    case MeshTopology::Lines: return "line_list";
    case MeshTopology::Points: return "point_list";
  }
  return "triangle_list";
}

// One mesh of one node, with the node's transforms (its own and its parents') applied.
struct MeshInstance {
  const aiMesh* mesh = nullptr;
  aiMatrix4x4 to_world;
  std::string name;
};

void collect_instances(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
                       std::vector<MeshInstance>& out) {
  const aiMatrix4x4 to_world = parent * node.mTransformation;
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh* mesh = scene.mMeshes[node.mMeshes[i]];
    if (mesh->mNumVertices == 0) continue;
    std::string name = mesh->mName.length > 0 ? mesh->mName.C_Str() : node.mName.C_Str();
    out.push_back({mesh, to_world, std::move(name)});
  }
  for (unsigned i = 0; i < node.mNumChildren; ++i) collect_instances(scene, *node.mChildren[i], to_world, out);
}

// aiProcess_SortByPType leaves one primitive type per mesh; the triangulation makes polygons
// triangles. A mesh of vertices without faces (a PLY point cloud) is its points.
MeshTopology topology_of(const aiMesh& mesh) {
  if (mesh.mNumFaces == 0) return MeshTopology::Points;
  if (mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) return MeshTopology::Triangles;
  if (mesh.mPrimitiveTypes & aiPrimitiveType_LINE) return MeshTopology::Lines;
  return MeshTopology::Points;
}

unsigned vertices_per_primitive(MeshTopology t) {
  return t == MeshTopology::Triangles ? 3 : t == MeshTopology::Lines ? 2 : 1;
}

// A draw of the written scene: instances joined (one, unless the model has more than 255).
struct ImportedDraw {
  MeshTopology topology = MeshTopology::Triangles;
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
  size_t dropped = 0;  // primitives left out: a vertex not finite
};

// Consecutive instances of one topology, in chunks of at most `per_draw`.
std::vector<std::vector<size_t>> group_instances(const std::vector<MeshInstance>& instances, size_t per_draw) {
  std::vector<std::vector<size_t>> groups;
  for (size_t i = 0; i < instances.size(); ++i) {
    const bool same = !groups.empty() && groups.back().size() < per_draw &&
                      topology_of(*instances[groups.back().back()].mesh) == topology_of(*instances[i].mesh);
    if (!same) groups.emplace_back();
    groups.back().push_back(i);
  }
  return groups;
}

std::vector<ImportedDraw> make_draws(const std::vector<MeshInstance>& instances, const std::string& file) {
  size_t per_draw = 1;
  std::vector<std::vector<size_t>> groups = group_instances(instances, per_draw);
  while (groups.size() > kMaxDraws) groups = group_instances(instances, ++per_draw);
  std::vector<ImportedDraw> draws;
  for (const std::vector<size_t>& group : groups) {
    ImportedDraw draw;
    draw.topology = topology_of(*instances[group.front()].mesh);
    draw.name = group.size() == 1 ? instances[group.front()].name
                                  : fmt::format("meshes {}..{}", group.front(), group.back());
    const unsigned corners = vertices_per_primitive(draw.topology);
    for (const size_t i : group) {
      const MeshInstance& instance = instances[i];
      // Vertices whose world position is not finite (a range scan's missing samples) are left out,
      // with every primitive that uses one; the rest are renumbered.
      constexpr uint32_t kDropped = std::numeric_limits<uint32_t>::max();
      std::vector<uint32_t> renumbered(instance.mesh->mNumVertices, kDropped);
      for (unsigned v = 0; v < instance.mesh->mNumVertices; ++v) {
        const aiVector3D p = instance.to_world * instance.mesh->mVertices[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
        renumbered[v] = uint32_t(draw.positions.size());
        draw.positions.emplace_back(p.x, p.y, p.z);
      }
      const auto emit = [&](const unsigned* corner_indices) {
        for (unsigned k = 0; k < corners; ++k)
          if (renumbered[corner_indices[k]] == kDropped) return ++draw.dropped, void();
        for (unsigned k = 0; k < corners; ++k) draw.indices.push_back(renumbered[corner_indices[k]]);
      };
      for (unsigned v = 0; v < instance.mesh->mNumVertices && instance.mesh->mNumFaces == 0; ++v) emit(&v);
      for (unsigned f = 0; f < instance.mesh->mNumFaces; ++f) {
        const aiFace& face = instance.mesh->mFaces[f];
        for (unsigned k = 0; k < face.mNumIndices; ++k)
          if (face.mIndices[k] >= instance.mesh->mNumVertices)
            throw InputError(file, "",
                             fmt::format("expected faces that use the mesh's vertices; face {} of mesh \"{}\" uses "
                                         "vertex {} of {}",
                                         f, instance.name, face.mIndices[k], instance.mesh->mNumVertices));
        if (face.mNumIndices == corners) emit(face.mIndices);  // else a degenerate face the sort left
      }
    }
    if (draw.positions.size() > std::numeric_limits<uint32_t>::max() ||
        draw.indices.size() / corners > kMaxPrimitivesPerDraw)
      throw InputError(file, "", fmt::format("expected at most {} primitives in a draw; the meshes of draw {} have {}",
                                             kMaxPrimitivesPerDraw, draws.size(), draw.indices.size() / corners));
    if (!draw.indices.empty()) draws.push_back(std::move(draw));
  }
  return draws;
}

// The camera: what `o.camera` gives, the rest framing the bounding sphere of `draws` (from `o.orbit`
// when no eye is given: the sphere fills the narrower field of view).
Camera framing_camera(const std::vector<ImportedDraw>& draws, const ImportOptions& o, const std::string& file) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const ImportedDraw& d : draws)
    for (const glm::vec3& p : d.positions) {
      lo = glm::min(lo, glm::dvec3(p));
      hi = glm::max(hi, glm::dvec3(p));
    }
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * glm::length(hi - lo), 1e-6 * std::max(1.0, glm::length(centre)));
  const double fov_y = o.camera.fov_y_degrees.value_or(45.0);
  const double aspect = double(o.width) / double(o.height);
  const double half_fov_y = 0.5 * fov_y * kPi / 180.0;
  const double half_fov_x = std::atan(std::tan(half_fov_y) * aspect);
  Camera camera;
  camera.target = o.camera.target.value_or(glm::vec3(centre));
  if (o.camera.eye) {
    camera.eye = *o.camera.eye;
  } else {
    const double fit = radius / std::sin(std::min(half_fov_y, half_fov_x));
    const double distance = o.orbit.distance.value_or(fit);
    const double az = o.orbit.azimuth_degrees * kPi / 180.0, el = o.orbit.elevation_degrees * kPi / 180.0;
    const glm::dvec3 direction(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
    camera.eye = glm::vec3(glm::dvec3(camera.target) + distance * direction);
  }
  camera.up = o.camera.up.value_or(glm::vec3(0, 1, 0));
  camera.fov_y_degrees = float(fov_y);
  // Near and far hold the sphere (when the eye is outside it), near no closer than 1/1000 of far.
  const double to_centre = glm::length(glm::dvec3(camera.eye) - centre);
  const double far_plane = o.camera.far_plane.value_or(to_centre + 1.05 * radius);
  camera.far_plane = float(far_plane);
  camera.near_plane = float(o.camera.near_plane.value_or(std::max(to_centre - 1.05 * radius, far_plane / 1000.0)));
  const auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite(camera.eye) || !finite(camera.target) || !std::isfinite(camera.far_plane))
    throw InputError(file, "",
                     fmt::format("expected a model a camera in float can frame; its bounding box spans ({:g}, {:g}, {:g}) "
                                 "to ({:g}, {:g}, {:g})",
                                 lo.x, lo.y, lo.z, hi.x, hi.y, hi.z));
  return camera;
}

std::string number(float v) { return fmt::format("{}", v); }

std::string vec3_text(const glm::vec3& v) { return fmt::format("[{}, {}, {}]", v.x, v.y, v.z); }

// A case name from the file name: "model.STEM.EXT", lower case, other characters as '_'.
std::string case_name(const std::string& path) {
  const auto part = [](std::string text) {
    std::string out;
    for (char c : text) {
      c = char(std::tolower(static_cast<unsigned char>(c)));
      out += ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9')) ? c : '_';
    }
    return out.empty() ? std::string("_") : out;
  };
  const std::filesystem::path p(path);
  const std::string ext = p.extension().string();
  return "model." + part(p.stem().string()) + "." + part(ext.empty() ? "none" : ext.substr(1));
}

std::string scene_text(const std::string& path, const std::vector<ImportedDraw>& draws, const Camera& camera,
                       const ImportOptions& o) {
  size_t triangles = 0, lines = 0, points = 0, vertices = 0, dropped = 0;
  for (const ImportedDraw& d : draws) {
    dropped += d.dropped;
    const size_t n = d.indices.size() / vertices_per_primitive(d.topology);
    (d.topology == MeshTopology::Triangles ? triangles : d.topology == MeshTopology::Lines ? lines : points) += n;
    vertices += d.positions.size();
  }
  const std::string file_name = std::filesystem::path(path).filename().string();
  std::string description = fmt::format("imported from {}: {} draw(s), {} triangles", file_name, draws.size(), triangles);
  if (lines > 0) description += fmt::format(", {} lines", lines);
  if (points > 0) description += fmt::format(", {} points", points);
  description += fmt::format(", {} vertices", vertices);
  if (dropped > 0) description += fmt::format("; {} primitive(s) with a non-finite vertex left out", dropped);
  std::string text = "{\n";
  text += "  \"name\": " + nlohmann::json(o.name.empty() ? case_name(path) : o.name).dump() + ",\n";
  text += "  \"description\": " + nlohmann::json(description).dump(-1, ' ', true) + ",\n";
  text += fmt::format("  \"width\": {}, \"height\": {},\n", o.width, o.height);
  if (o.depth_format != DepthFormat::D32Sfloat) text += fmt::format("  \"depth_format\": \"{}\",\n", to_string(o.depth_format));
  if (o.samples != 1) text += fmt::format("  \"samples\": {},\n", o.samples);
  text += "  \"camera\": {\"eye\": " + vec3_text(camera.eye) + ", \"target\": " + vec3_text(camera.target) +
          ", \"up\": " + vec3_text(camera.up) + ",\n             \"fov_y\": " + number(camera.fov_y_degrees) +
          ", \"near\": " + number(camera.near_plane) + ", \"far\": " + number(camera.far_plane) + "},\n";
  text += "  \"draws\": [";
  for (size_t d = 0; d < draws.size(); ++d) {
    const ImportedDraw& draw = draws[d];
    text += d == 0 ? "\n" : ",\n";
    text += "    {\"name\": " + nlohmann::json(draw.name).dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
    if (draw.topology != MeshTopology::Triangles) text += fmt::format(", \"topology\": \"{}\"", topology_name(draw.topology));
    text += ",\n     \"positions\": [";
    for (size_t i = 0; i < draw.positions.size(); ++i) text += (i == 0 ? "" : i % 4 == 0 ? ",\n                   " : ", ") + vec3_text(draw.positions[i]);
    text += "],\n     \"indices\": [";
    const size_t per_line = 3 * 8;
    for (size_t i = 0; i < draw.indices.size(); ++i)
      text += (i == 0 ? "" : i % per_line == 0 ? ",\n                 " : ", ") + std::to_string(draw.indices[i]);
    text += "]}";
  }
  text += "\n  ]\n}\n";
  return text;
}

}  // namespace

bool is_suite_model_file(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext != ".xml" && ext != ".raw" && is_model_file(path);
}

bool is_model_file(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext.empty() || ext == ".json") return false;
  const Assimp::Importer importer;
  return importer.IsExtensionSupported(ext);
}

std::string import_model_json(const std::string& path, const ImportOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path, "", "expected a model file (a regular file the importer reads)");
  Assimp::Importer importer;
  // Points and lines are kept (as draws of their own); normals, materials and textures are not read.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, 0);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_JoinIdenticalVertices);
  if (scene == nullptr) throw InputError(path, "", std::string("expected a model the importer reads: ") + importer.GetErrorString());
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE || scene->mRootNode == nullptr)
    throw InputError(path, "", "expected a model with meshes; the importer read an incomplete scene");
  std::vector<MeshInstance> instances;
  collect_instances(*scene, *scene->mRootNode, aiMatrix4x4(), instances);
  const std::vector<ImportedDraw> draws = make_draws(instances, path);
  if (draws.empty()) throw InputError(path, "", "expected a model with at least one mesh of points, lines or triangles");
  const Camera camera = framing_camera(draws, options, path);
  return scene_text(path, draws, camera, options);
}

Scene load_scene_or_model(const std::string& path) {
  if (!is_model_file(path)) return load_scene_file(path);
  return parse_scene(import_model_json(path, ImportOptions{}), path);
}

}  // namespace rastercmp
