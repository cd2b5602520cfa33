// Models as scenes (model/mesh_import.hpp, docs/scene-format.md "Models"): `rastercmp import`
// writes an ordinary scene (world positions with the node transforms applied, one draw per mesh
// instance, lines and points kept, a camera framing the model), refuses a malformed model of each
// format with exit 2 naming the file and writing nothing, and `compare` and `conformance` take
// model files where they take scenes. The real models come from Debian's assimp-testmodels, which
// set-up installs (scripts/setup.sh).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/test_cli_support.hpp"

namespace rastercmp::cli_test {
namespace {

// glTF 2.0: a triangle in node 0 (translation 10, 0, 0), a line in node 1 (scale 2), a point in
// node 2, child of node 0. Positions (0,0,0) (1,0,0) (0,1,0) | (0,0,0) (0,0,1) | (0.5,0.5,0.5).
const std::string kNodesGltf = R"json({"asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0, "translation": [10, 0, 0], "children": [2]}, {"mesh": 1, "scale": [2, 2, 2]}, {"mesh": 2}],
  "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "mode": 4}]}, {"name": "seg", "primitives": [{"attributes": {"POSITION": 1}, "mode": 1}]}, {"name": "dot", "primitives": [{"attributes": {"POSITION": 2}, "mode": 0}]}],
  "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAIA/AAAAPwAAAD8AAAA/"}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}, {"buffer": 0, "byteOffset": 60, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}, {"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 1]}, {"bufferView": 2, "componentType": 5126, "count": 1, "type": "VEC3", "min": [0.5, 0.5, 0.5], "max": [0.5, 0.5, 0.5]}]})json";

const fs::path kTestModels = "/usr/share/assimp/models";

TEST(CliImport, NodeTransformsLinesAndPointsReachTheScene) {
  const TempDir tmp;
  write_file(tmp / "nodes.gltf", kNodesGltf);
  const std::vector<std::string> args = {"import", (tmp / "nodes.gltf").string(), "--out", (tmp / "nodes.json").string()};
  const RunResult r = run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << describe(args, r);
  const nlohmann::json scene = nlohmann::json::parse(read_file(tmp / "nodes.json"));
  EXPECT_EQ(scene.at("name"), "model.nodes.gltf");
  ASSERT_EQ(scene.at("draws").size(), 3u) << scene.dump(1);
  std::map<std::string, nlohmann::json> draws;
  for (const nlohmann::json& d : scene.at("draws")) draws[d.at("name")] = d;
  EXPECT_FALSE(draws.at("tri").contains("topology"));  // the loader's default, triangle_list
  EXPECT_EQ(draws.at("tri").at("positions"), nlohmann::json::parse("[[10, 0, 0], [11, 0, 0], [10, 1, 0]]"));
  EXPECT_EQ(draws.at("tri").at("indices"), nlohmann::json::parse("[0, 1, 2]"));
  EXPECT_EQ(draws.at("seg").at("topology"), "line_list");
  EXPECT_EQ(draws.at("seg").at("positions"), nlohmann::json::parse("[[0, 0, 0], [0, 0, 2]]"));
  EXPECT_EQ(draws.at("dot").at("topology"), "point_list");
  EXPECT_EQ(draws.at("dot").at("positions"), nlohmann::json::parse("[[10.5, 0.5, 0.5]]"));
  // The framing camera looks at the bounding box's centre; defaults are left out of the file.
  EXPECT_EQ(scene.at("camera").at("target"), nlohmann::json::parse("[5.5, 0.5, 1]"));
  EXPECT_FALSE(scene.contains("depth_format"));
  EXPECT_FALSE(scene.contains("samples"));
}

TEST(CliImport, OptionsReachTheSceneAndBadOnesWriteNothing) {
  const TempDir tmp;
  write_file(tmp / "nodes.gltf", kNodesGltf);
  const std::string model = (tmp / "nodes.gltf").string(), out = (tmp / "s.json").string();
  RunResult r = run_cli({"import", model, "--out", out, "--size", "320x200", "--depth-format", "d16_unorm", "--samples",
                         "4", "--camera", "eye=0,0,30,target=5,0,0,fov=30,near=1,far=100"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json scene = nlohmann::json::parse(read_file(out));
  EXPECT_EQ(scene.at("width"), 320);
  EXPECT_EQ(scene.at("height"), 200);
  EXPECT_EQ(scene.at("depth_format"), "d16_unorm");
  EXPECT_EQ(scene.at("samples"), 4);
  EXPECT_EQ(scene.at("camera"), nlohmann::json::parse(R"({"eye": [0, 0, 30], "target": [5, 0, 0], "up": [0, 1, 0],
                                                          "fov_y": 30, "near": 1, "far": 100})"));
  fs::remove(out);
  r = run_cli({"import", model, "--out", out, "--orbit", "90,0,40", "--camera", "near=1,far=100", "--name", "m.x"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json orbit = nlohmann::json::parse(read_file(out));
  EXPECT_EQ(orbit.at("name"), "m.x");
  EXPECT_EQ(orbit.at("camera").at("eye"), nlohmann::json::parse("[45.5, 0.5, 1]"));  // target + 40 along +x
  EXPECT_EQ(orbit.at("camera").at("near"), 1);
  EXPECT_EQ(orbit.at("camera").at("far"), 100);
  fs::remove(out);
  for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{
           {"--size", "0x10"},
           {"--size", "512"},
           {"--camera", "eye=0,3"},
           {"--camera", "position=1,2,3"},
           {"--camera", "eye=0,0,0,target=0,0,0"},  // the scene loader's own check
           {"--orbit", "10"},
           {"--orbit", "10,20", "--camera", "eye=1,2,3"},  // two eyes
           {"--name", "Not A Case Name"},
           {"--samples", "2"},
           {"--depth-format", "d24"},
       }) {
    std::vector<std::string> args = {"import", model, "--out", out};
    args.insert(args.end(), bad.begin(), bad.end());
    const RunResult b = run_cli(args);
    EXPECT_EQ(b.exit_code, 2) << describe(args, b);
    EXPECT_FALSE(fs::exists(out)) << describe(args, b);
  }
}

// A malformed file of each format: exit 2, one error line naming the file and the importer's
// reason, nothing on stdout, no output file. A file whose format nothing reads says so too.
TEST(CliImport, AMalformedModelOfEachFormatIsExit2WithTheReason) {
  const TempDir tmp;
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"cut.obj", "v 0 0\n"},
      {"cut.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n"},
      {"empty.ply", "ply\nformat ascii 1.0\nend_header\n"},
      {"cut.dae", "<?xml version=\"1.0\"?><COLLADA><library_geometries><geometry>"},
      {"cut.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 7}}]}]}"},
      {"cut.glb", std::string("glTF\x02\0\0\0", 8)},
      {"cut.fbx", "Kaydara FBX Binary  \0garbage"},
      {"random.3ds", std::string(64, '\x7f')},
  };
  for (const auto& [name, text] : bad) {
    write_file(tmp / name, text);
    const fs::path out = tmp / (name + ".json");
    const std::vector<std::string> args = {"import", (tmp / name).string(), "--out", out.string()};
    const RunResult r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << describe(args, r);
    EXPECT_EQ(r.signal, 0) << describe(args, r);
    EXPECT_NE(r.err.find((tmp / name).string()), std::string::npos) << describe(args, r);
    EXPECT_NE(r.err.find("expected a model"), std::string::npos) << describe(args, r);
    EXPECT_TRUE(r.out.empty()) << describe(args, r);
    EXPECT_FALSE(fs::exists(out)) << describe(args, r);
  }
  // A model the importer reads with vertices near FLT_MAX: no camera in float frames it, and the
  // message names the bounding box. (Written here: which of assimp-testmodels' files read so
  // depends on the release's assimp; Debian 12's read the PLY pond so, Debian 13's do not.)
  write_file(tmp / "huge.obj", "v 3e38 0 0\nv -3e38 0 0\nv 0 3e38 0\nf 1 2 3\n");
  const std::vector<std::string> args = {"import", (tmp / "huge.obj").string(), "--out", (tmp / "huge.json").string()};
  const RunResult r = run_cli(args);
  EXPECT_EQ(r.exit_code, 2) << describe(args, r);
  EXPECT_NE(r.err.find("bounding box spans"), std::string::npos) << describe(args, r);
  EXPECT_FALSE(fs::exists(tmp / "huge.json"));
}

// The real models of Debian's assimp-testmodels, given to compare and conformance as they are:
// imported with the defaults and bit-exact against lavapipe.
TEST(CliImport, RealModelsCompareBitExactWhereScenesWould) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  ASSERT_TRUE(fs::is_directory(kTestModels)) << kTestModels << " is missing: scripts/setup.sh installs assimp-testmodels";
  const std::vector<std::string> models = {
      "Collada/duck.dae", "Collada/teapots.DAE", "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
      "PLY/Wuson.ply",    "OBJ/WusonOBJ.obj",    "STL/Spider_ascii.stl",
  };
  const TempDir tmp;
  for (const std::string& model : models) {
    const std::vector<std::string> args = {"compare", (kTestModels / model).string()};
    const RunResult r = run_cli(args);
    EXPECT_EQ(r.exit_code, 0) << describe(args, r);
    EXPECT_NE(r.out.find("Pass (bit-exact)"), std::string::npos) << describe(args, r);
  }
  // A suite folder of models and a scene: every file is a case.
  fs::create_directories(tmp / "suite");
  fs::copy_file(kTestModels / "Collada/duck.dae", tmp / "suite" / "duck.dae");
  fs::copy_file(kTestModels / "STL/Spider_ascii.stl", tmp / "suite" / "spider.stl");
  write_file(tmp / "suite" / "one.json", R"({"draws": [{"positions": [[-0.5, -0.5, 0.5], [0.5, -0.5, 0.5], [0, 0.5, 0.5]]}]})");
  const std::vector<std::string> args = {"conformance", "--suite", (tmp / "suite").string(), "--out", (tmp / "out").string()};
  const RunResult r = run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << describe(args, r);
  const nlohmann::json summary = nlohmann::json::parse(read_file(tmp / "out" / "summary.json"));
  EXPECT_EQ(summary.at("cases").size(), 3u);
  EXPECT_EQ(summary.at("statuses").at("Pass"), 3);
  // Captured and judged later: a model's capture folder keeps its extension, so duck.dae and a
  // duck.obj beside it could not share one.
  const std::vector<std::string> capture = {"capture", "--suite", (tmp / "suite").string(), "--out",
                                            (tmp / "caps").string()};
  const RunResult c = run_cli(capture);
  ASSERT_EQ(c.exit_code, 0) << describe(capture, c);
  EXPECT_TRUE(fs::exists(tmp / "caps" / "duck.dae" / "render.json"));
  EXPECT_TRUE(fs::exists(tmp / "caps" / "one" / "render.json"));
  const std::vector<std::string> judge = {"conformance", "--suite", (tmp / "suite").string(), "--captures",
                                          (tmp / "caps").string(), "--out", (tmp / "judged").string()};
  const RunResult j = run_cli(judge, kNoVulkanDriver);
  EXPECT_EQ(j.exit_code, 0) << describe(judge, j);
}

// sweep zfight on a real model (--quick): the D16 standard onset calibrates the surfaces' gap, and
// every other series' measured onset lies where the depth-step formula puts it: D24 and D32
// standard 2^8 later than D16, reversed integer Z where standard is, D32 reversed with none.
TEST(CliImport, ZfightSweepOnAModelMeetsItsPrediction) {
  ASSERT_TRUE(fs::is_directory(kTestModels)) << kTestModels << " is missing: scripts/setup.sh installs assimp-testmodels";
  const TempDir tmp;
  const std::vector<std::string> args = {"sweep", "zfight", "--model", (kTestModels / "Collada/duck.dae").string(),
                                         "--quick", "--out", (tmp / "zfight").string()};
  const RunResult r = run_cli(args);
  ASSERT_EQ(r.exit_code, 0) << describe(args, r);
  const nlohmann::json report = nlohmann::json::parse(read_file(tmp / "zfight" / "zfight.json"));
  ASSERT_FALSE(report.at("calibrated_gap").is_null()) << report.dump(1);
  ASSERT_EQ(report.at("series").size(), 6u);
  for (const nlohmann::json& series : report.at("series")) {
    EXPECT_EQ(series.at("agrees"), true) << series.dump();
    const bool float_reversed = series.at("format") == "d32_sfloat" && series.at("mapping") == "reversed";
    EXPECT_EQ(series.at("measured_onset_at_most").is_null(), float_reversed) << series.dump();
  }
  EXPECT_TRUE(fs::exists(tmp / "zfight" / "zfight_far_near.svg"));
  EXPECT_TRUE(fs::exists(tmp / "zfight" / "index.html"));
}

}  // namespace
}  // namespace rastercmp::cli_test
