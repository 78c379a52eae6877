// Scene files and the built-in corpus (the `dcurve simulate` command line: cli_test).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "corpus/sim/scene.h"
#include "corpus/sim/simulation.h"

namespace dcurve {
namespace {

namespace fs = std::filesystem;

fs::path scratch_dir(const std::string& name) {
  fs::path dir = fs::path(DCURVE_BINARY_DIR) / "sim_scene_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

TEST(SimScene, BuiltinScenesParseAndRopeSizesFitTheirRoles) {
  const auto names = builtin_scene_names();
  ASSERT_GE(names.size(), 6u);
  EXPECT_EQ(names[0], "rope-small");
  for (const auto& name : names) {
    Scene s;
    std::string err;
    ASSERT_TRUE(builtin_scene(name, &s, &err)) << name << ": " << err;
    EXPECT_EQ(s.name, name);
    std::vector<double> xyz;
    std::vector<uint32_t> faces;
    ASSERT_TRUE(load_scene_surface(s, &xyz, &faces, &err)) << name << ": " << err;
    const size_t vertices = xyz.size() / 3;
    if (name == "rope-small") {
      EXPECT_GE(vertices, 1000u);
      EXPECT_LE(vertices, 3000u);
      EXPECT_GE(s.frames, 60);
    }
    if (name == "rope") {
      EXPECT_GE(vertices, 18000u);
      EXPECT_LE(vertices, 22000u);
    }
  }
  Scene s;
  std::string err;
  EXPECT_FALSE(builtin_scene("no-such-scene", &s, &err));
  EXPECT_NE(err.find("rope-small"), std::string::npos) << err;  // the message lists the names
}

TEST(SimScene, SceneFileKeysAndRelativeMeshPath) {
  const fs::path dir = scratch_dir("keys");
  write_text(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  write_text(dir / "scene.json", R"({
    "mesh": {"file": "tri.obj", "scale": 0.5, "translate": [0, 1, 0]},
    "tetgen": {"quality": 1.5, "max_volume": 0.01},
    "material": {"density": 500, "youngs_modulus": 2e5, "poisson_ratio": 0.4, "volume_compliance": 0, "damping": 2},
    "gravity": [0, 0, -9.81], "ground": {"height": -1, "friction": 0.3},
    "pins": [{"plane": {"point": [0, 1.4, 0], "normal": [0, 2, 0]}}],
    "handles": [{"region": {"box": {"min": [0.4, 0.9, -1], "max": [1, 1.1, 1]}}, "velocity": [0.1, 0, 0],
                 "axis": [0, 0, 2], "angular_velocity": 1, "start": 0.5, "end": 1}],
    "frames": 5, "fps": 24, "substeps": 7, "iterations": 3})");
  Scene s;
  std::string err;
  ASSERT_TRUE(load_scene_file((dir / "scene.json").string(), &s, &err)) << err;
  EXPECT_EQ(s.mesh_file, (dir / "tri.obj").string());
  EXPECT_EQ(s.name, (dir / "scene.json").string());
  EXPECT_EQ(s.mesh_scale, 0.5);
  EXPECT_EQ(s.material.density, 500);
  EXPECT_EQ(s.material.volume_compliance, 0);
  EXPECT_EQ(s.gravity.z(), -9.81);
  EXPECT_TRUE(s.ground);
  ASSERT_EQ(s.handles.size(), 2u);
  EXPECT_EQ(s.handles[0].region.kind, Region::Kind::Plane);
  EXPECT_DOUBLE_EQ(s.handles[1].axis.norm(), 1.0);
  EXPECT_EQ(s.frames, 5);
  EXPECT_EQ(s.substeps, 7);
  Animation anim;
  ASSERT_TRUE(simulate_scene(s, &anim, {}, &err)) << err;
  EXPECT_EQ(anim.vertex_count, 4u);
  EXPECT_EQ(anim.frames.size(), 5u);
  EXPECT_EQ(anim.frame_rate, 24);
  EXPECT_FLOAT_EQ(anim.frames[0][4], 1.0f);  // vertex 1 = (1, 0, 0) * 0.5 + (0, 1, 0)
}

TEST(SimScene, BadSceneFilesNameTheFileAndTheProblem) {
  const fs::path dir = scratch_dir("bad");
  const std::string base = R"("mesh": {"generator": "box", "size": [1, 1, 1], "divisions": [2, 2, 2]})";
  const std::pair<std::string, std::string> cases[] = {
      {"{" + base + ", \"frames\": 0}", "frames"},
      {"{" + base + ", \"substep\": 3}", "unknown key \"substep\""},
      {"{" + base + ", \"material\": {\"poisson_ratio\": 0.5}}", "poisson_ratio"},
      {"{" + base + ", \"pins\": [{\"box\": {\"min\": [5, 5, 5], \"max\": [6, 6, 6]}}]}", "holds no particle"},
      {R"({"mesh": {"generator": "box", "size": [1, 1], "divisions": [2, 2, 2]}})", "size"},
      {R"({"mesh": {"file": "missing.obj"}})", "missing.obj"},
      {"{\"mesh\": ", "not valid JSON"},
      {"{}", "mesh"},
  };
  for (const auto& [text, expect] : cases) {
    write_text(dir / "bad.json", text);
    Scene s;
    std::string err;
    Animation anim;
    const bool ok = load_scene_file((dir / "bad.json").string(), &s, &err) && simulate_scene(s, &anim, {}, &err);
    EXPECT_FALSE(ok) << text;
    EXPECT_NE(err.find(expect), std::string::npos) << text << " -> " << err;
    if (err.find("missing.obj") == std::string::npos && err.find("holds no particle") == std::string::npos) {
      EXPECT_NE(err.find("bad.json"), std::string::npos) << err;
    }
  }
  Scene s;
  std::string err;
  EXPECT_FALSE(load_scene_file((dir / "absent.json").string(), &s, &err));
  EXPECT_NE(err.find("absent.json"), std::string::npos);
}

}  // namespace
}  // namespace dcurve
