// Models in the formats people have (glTF, OBJ, PLY, STL, COLLADA, FBX and the rest the Open Asset
// Import Library reads) as ordinary scenes: `rastercmp import` writes the scene file, and every
// command that takes a scene file takes a model file too, imported with the defaults below
// (docs/scene-format.md, "Models").
//
// The scene is world space with a camera: each mesh of each node, with the node's transforms
// applied, is one draw with indices (triangulated; its lines and points are line_list and
// point_list draws); no normals, materials or textures. More than 255 mesh instances are joined,
// in order and by topology, into at most 255 draws.
#pragma once

#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "model/scene.hpp"

namespace rastercmp {

// Where the camera looks from, around the model's bounding sphere: azimuth about +y from +z and
// elevation above the xz plane, in degrees; distance in world units (default: the sphere fills
// the narrower field of view).
struct Orbit {
  double azimuth_degrees = 35;
  double elevation_degrees = 25;
  std::optional<double> distance;
};

// A camera given in part: what is left out is framed (up +y, fov_y 45 degrees, near and far
// holding the model's bounding sphere as seen from the eye).
struct CameraChoice {
  std::optional<glm::vec3> eye, target, up;
  std::optional<double> fov_y_degrees, near_plane, far_plane;
};

struct ImportOptions {
  std::string name;  // the case name; empty: model.STEM.EXT
  uint32_t width = 512, height = 512;
  DepthFormat depth_format = DepthFormat::D32Sfloat;
  uint32_t samples = 1;
  Orbit orbit;          // where the eye is when `camera.eye` is not given
  CameraChoice camera;  // target default: the centre of the bounding box
};

// Whether `path` names a model file: not .json, and an extension the importer reads.
bool is_model_file(const std::string& path);

// A model file a suite folder counts as a case: is_model_file, less the importer's two extensions
// that name generic data (.xml, .raw), which a folder holds for other reasons (a junit.xml).
bool is_suite_model_file(const std::string& path);

// The model as scene JSON text (what `rastercmp import` writes). Throws InputError naming the file
// and the importer's reason, or the limit the model exceeds.
std::string import_model_json(const std::string& path, const ImportOptions& options);

// A scene file, or a model file imported with the default options.
Scene load_scene_or_model(const std::string& path);

}  // namespace rastercmp
