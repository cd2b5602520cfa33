// rastercmp import MODEL --out SCENE.json [--name NAME] [--camera ...] [--orbit AZ,EL[,DIST]]
//                 [--size WxH] [--depth-format F] [--samples N]
// Writes a model file (glTF, OBJ, PLY, STL, COLLADA, FBX, ...: what the Open Asset Import Library
// reads) as an ordinary scene file: world positions and indices per mesh, a camera framing the model
// (model/mesh_import.hpp, docs/scene-format.md "Models"). Exit 0, or 2 for a model it cannot read
// or bad options, and then nothing is written.
#include <cmath>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "model/errors.hpp"
#include "model/image_io.hpp"
#include "model/mesh_import.hpp"
#include "model/scene_io.hpp"

namespace rastercmp::app {
namespace {

struct ImportArgs {
  std::string model_path;
  std::string out_file;
  std::string name;
  std::string camera;
  std::vector<double> orbit;
  std::string size;
  std::string depth_format = "d32_sfloat";
  uint32_t samples = 1;
};

double number_in(const std::string& text, const std::string& option) {
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(value))
    throw UsageError(fmt::format("{}: expected a number, found \"{}\"", option, text));
  return value;
}

glm::vec3 vec3_in(const std::string& text, const std::string& option) {
  static const std::regex three(R"(([^,]+),([^,]+),([^,]+))");
  std::smatch m;
  if (!std::regex_match(text, m, three)) throw UsageError(fmt::format("{}: expected X,Y,Z, found \"{}\"", option, text));
  return {float(number_in(m[1], option)), float(number_in(m[2], option)), float(number_in(m[3], option))};
}

// "eye=X,Y,Z,target=X,Y,Z,up=X,Y,Z,fov=F,near=N,far=F", any subset, in any order.
CameraChoice parse_camera(const std::string& text) {
  CameraChoice camera;
  static const std::regex key(R"((?:^|,)(eye|target|up|fov|near|far)=)");
  std::vector<std::pair<std::string, size_t>> keys;  // name, where its value starts
  std::vector<size_t> starts;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), key); it != std::sregex_iterator(); ++it) {
    keys.emplace_back((*it)[1].str(), size_t(it->position() + it->length()));
    starts.push_back(size_t(it->position()));
  }
  if (keys.empty() || starts.front() != 0)
    throw UsageError("--camera: expected eye=X,Y,Z,target=X,Y,Z,up=X,Y,Z,fov=DEGREES,near=N,far=F (any of them), found \"" +
                     text + "\"");
  for (size_t i = 0; i < keys.size(); ++i) {
    const size_t end = i + 1 < keys.size() ? starts[i + 1] : text.size();
    const std::string value = text.substr(keys[i].second, end - keys[i].second);
    const std::string option = "--camera " + keys[i].first;
    const std::string& name = keys[i].first;
    if (name == "eye") camera.eye = vec3_in(value, option);
    if (name == "target") camera.target = vec3_in(value, option);
    if (name == "up") camera.up = vec3_in(value, option);
    if (name == "fov") camera.fov_y_degrees = number_in(value, option);
    if (name == "near") camera.near_plane = number_in(value, option);
    if (name == "far") camera.far_plane = number_in(value, option);
  }
  // The scene loader checks the camera as it checks any scene's (docs/scene-format.md "Camera").
  return camera;
}

int run_import(const ImportArgs& args) {
  ImportOptions options;
  if (!args.size.empty()) {
    static const std::regex size(R"(([0-9]{1,5})x([0-9]{1,5}))");
    std::smatch m;
    if (!std::regex_match(args.size, m, size))
      throw UsageError(fmt::format("--size: expected WIDTHxHEIGHT such as 512x384, found \"{}\"", args.size));
    options.width = uint32_t(std::stoul(m[1]));
    options.height = uint32_t(std::stoul(m[2]));
    if (options.width < 1 || options.width > 16384 || options.height < 1 || options.height > 16384)
      throw UsageError(fmt::format("--size: expected a width and height of 1..16384 (maxFramebufferWidth), found \"{}\"",
                                   args.size));
  }
  options.depth_format = args.depth_format == "d16_unorm"      ? DepthFormat::D16Unorm
                         : args.depth_format == "x8_d24_unorm" ? DepthFormat::X8D24Unorm
                         : args.depth_format == "none"         ? DepthFormat::None
                                                               : DepthFormat::D32Sfloat;
  options.samples = args.samples;
  if (!args.camera.empty()) options.camera = parse_camera(args.camera);
  if (!args.orbit.empty()) {
    if (options.camera.eye) throw UsageError("--orbit: places the eye, which --camera eye= gives too; give one of them");
    if (args.orbit.size() > 3 || args.orbit.size() < 2)
      throw UsageError("--orbit: expected AZIMUTH,ELEVATION[,DISTANCE] in degrees and world units");
    options.orbit.azimuth_degrees = args.orbit[0];
    options.orbit.elevation_degrees = args.orbit[1];
    if (args.orbit.size() == 3) options.orbit.distance = args.orbit[2];
  }
  const std::string folder = output_file_folder(args.out_file);  // a folder in its place: exit 2
  options.name = args.name;
  const std::string text = import_model_json(args.model_path, options);
  if (text.size() > kMaxSceneFileBytes)
    throw InputError(args.model_path, "",
                     fmt::format("expected a model whose scene file fits the loader's {} MiB; it would be {} MiB",
                                 kMaxSceneFileBytes >> 20, (text.size() + (1 << 20) - 1) >> 20));
  const Scene scene = parse_scene(text, args.model_path);  // an ordinary scene, or nothing is written
  ensure_output_dir(folder);
  write_text_file_atomic(args.out_file, text);
  fmt::print("{} → {}: {} ({}x{}), {}\n", args.model_path, args.out_file, scene.name, scene.width, scene.height,
             scene.description);
  return kExitOk;
}

}  // namespace

void add_import_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ImportArgs>();
  CLI::App* cmd = app.add_subcommand("import", "write a model file (glTF, OBJ, PLY, STL, COLLADA, FBX, ...) as a scene");
  cmd->add_option("model", args->model_path, "model file")->required();
  cmd->add_option("--out", args->out_file, "scene file to write (JSON)")->required();
  cmd->add_option("--name", args->name, "the scene's case name (default model.STEM.EXT)");
  cmd->add_option("--camera", args->camera,
                                 "eye=X,Y,Z,target=X,Y,Z,up=X,Y,Z,fov=DEGREES,near=N,far=F (any of them; the rest "
                                 "frames the model)");
  cmd->add_option("--orbit", args->orbit, "AZIMUTH,ELEVATION[,DISTANCE]: where the framing camera looks from")
      ->delimiter(',');
  cmd->add_option("--size", args->size, "framebuffer WIDTHxHEIGHT (default 512x512)");
  cmd->add_option("--depth-format", args->depth_format, "depth attachment")
      ->check(CLI::IsMember({"d16_unorm", "x8_d24_unorm", "d32_sfloat", "none"}));
  cmd->add_option("--samples", args->samples, "samples per pixel")->check(CLI::IsMember({1, 4}));
  cmd->callback([args, &exit_code] { exit_code = run_import(*args); });
}

}  // namespace rastercmp::app
