#include "corpus/sim/scene.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <set>
#include <vector>

#include "corpus/scenes.h"
#include "encoder/io/files.h"

namespace dcurve {

bool Region::contains(const Eigen::Vector3d& x) const {
  if (kind == Kind::Plane) return (x - point).dot(normal) >= 0;
  return (x.array() >= min.array()).all() && (x.array() <= max.array()).all();
}

namespace {

// Reads JSON values with range checks; every message names the key path.
struct Reader {
  std::string* error;

  bool fail(const std::string& msg) {
    *error = msg;
    return false;
  }
  bool only_keys(const nlohmann::json& obj, const std::string& where, std::set<std::string> keys) {
    if (!obj.is_object()) return fail(where + " must be an object");
    for (auto it = obj.begin(); it != obj.end(); ++it)
      if (!keys.count(it.key())) return fail("unknown key \"" + it.key() + "\" in " + where);
    return true;
  }
  bool num(const nlohmann::json& obj, const char* key, const std::string& where, double lo, double hi, double* out) {
    auto it = obj.find(key);
    if (it == obj.end()) return true;  // keep the default
    if (!it->is_number()) return fail(where + "." + key + " must be a number");
    double v = it->get<double>();
    if (!(v >= lo && v <= hi))
      return fail(where + "." + key + " = " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
                  std::to_string(hi) + "]");
    *out = v;
    return true;
  }
  bool integer(const nlohmann::json& obj, const char* key, const std::string& where, int lo, int hi, int* out) {
    double v = *out;
    if (!num(obj, key, where, lo, hi, &v)) return false;
    if (v != std::floor(v)) return fail(where + "." + key + " must be an integer");
    *out = int(v);
    return true;
  }
  bool vec(const nlohmann::json& obj, const char* key, const std::string& where, Eigen::Vector3d* out) {
    auto it = obj.find(key);
    if (it == obj.end()) return true;
    if (!it->is_array() || it->size() != 3) return fail(where + "." + key + " must be [x, y, z]");
    for (int k = 0; k < 3; ++k) {
      const auto& e = (*it)[k];
      if (!e.is_number() || !std::isfinite(e.get<double>()))
        return fail(where + "." + key + " must hold 3 finite numbers");
      (*out)[k] = e.get<double>();
    }
    return true;
  }
  bool unit(const nlohmann::json& obj, const char* key, const std::string& where, Eigen::Vector3d* out) {
    if (!vec(obj, key, where, out)) return false;
    if (out->norm() < 1e-12) return fail(where + "." + key + " must not be zero");
    out->normalize();
    return true;
  }

  bool region(const nlohmann::json& j, const std::string& where, Region* r) {
    if (!only_keys(j, where, {"box", "plane"})) return false;
    if (j.contains("box") == j.contains("plane")) return fail(where + " needs exactly one of \"box\" or \"plane\"");
    if (j.contains("box")) {
      const auto& b = j["box"];
      r->kind = Region::Kind::Box;
      if (!only_keys(b, where + ".box", {"min", "max"})) return false;
      if (!b.contains("min") || !b.contains("max")) return fail(where + ".box needs \"min\" and \"max\"");
      return vec(b, "min", where + ".box", &r->min) && vec(b, "max", where + ".box", &r->max);
    }
    const auto& p = j["plane"];
    r->kind = Region::Kind::Plane;
    if (!only_keys(p, where + ".plane", {"point", "normal"})) return false;
    if (!p.contains("normal")) return fail(where + ".plane needs \"normal\"");
    return vec(p, "point", where + ".plane", &r->point) && unit(p, "normal", where + ".plane", &r->normal);
  }

  bool handle(const nlohmann::json& j, const std::string& where, bool pin, Handle* h) {
    if (pin) return region(j, where, &h->region);
    if (!only_keys(j, where, {"region", "velocity", "axis", "angular_velocity", "pivot", "start", "end"}))
      return false;
    if (!j.contains("region")) return fail(where + " needs \"region\"");
    h->has_pivot = j.contains("pivot");
    return region(j["region"], where + ".region", &h->region) && vec(j, "velocity", where, &h->velocity) &&
           unit(j, "axis", where, &h->axis) && num(j, "angular_velocity", where, -1e4, 1e4, &h->angular_velocity) &&
           vec(j, "pivot", where, &h->pivot) && num(j, "start", where, 0, 1e9, &h->start) &&
           num(j, "end", where, h->start, 1e30, &h->end);
  }

  bool material(const nlohmann::json& j, Material* m) {
    const std::string w = "material";
    return only_keys(j, w, {"density", "youngs_modulus", "poisson_ratio", "edge_compliance", "volume_compliance",
                            "damping"}) &&
           num(j, "density", w, 1e-6, 1e9, &m->density) && num(j, "youngs_modulus", w, 0, 1e13, &m->youngs_modulus) &&
           num(j, "poisson_ratio", w, 0.01, 0.499, &m->poisson_ratio) &&
           num(j, "edge_compliance", w, -1, 1e6, &m->edge_compliance) &&
           num(j, "volume_compliance", w, -1, 1e6, &m->volume_compliance) && num(j, "damping", w, 0, 1e4, &m->damping);
  }
};

}  // namespace

bool scene_from_json(const nlohmann::json& j, const std::string& base_dir, Scene* scene, std::string* error) {
  Reader r{error};
  Scene s;
  if (!r.only_keys(j, "scene", {"name", "mesh", "tetgen", "material", "gravity", "ground", "pins", "handles",
                                "frames", "fps", "substeps", "iterations"}))
    return false;
  if (j.contains("name")) {
    if (!j["name"].is_string()) return r.fail("scene.name must be a string");
    s.name = j["name"].get<std::string>();
  }
  if (!j.contains("mesh") || !j["mesh"].is_object()) return r.fail("scene needs a \"mesh\" object");
  nlohmann::json mesh = j["mesh"];
  if (!r.vec(mesh, "translate", "mesh", &s.mesh_translate) || !r.num(mesh, "scale", "mesh", 1e-9, 1e9, &s.mesh_scale))
    return false;
  mesh.erase("translate");
  mesh.erase("scale");
  if (mesh.contains("file")) {
    if (!r.only_keys(mesh, "mesh", {"file"})) return false;
    if (!mesh["file"].is_string()) return r.fail("mesh.file must be a string");
    std::filesystem::path p = mesh["file"].get<std::string>();
    s.mesh_file = (p.is_relative() && !base_dir.empty() ? std::filesystem::path(base_dir) / p : p).string();
  } else if (mesh.contains("generator")) {
    s.generator = mesh;
  } else {
    return r.fail("mesh needs \"file\" or \"generator\"");
  }
  if (j.contains("tetgen")) {
    const auto& t = j["tetgen"];
    if (!r.only_keys(t, "tetgen", {"quality", "max_volume"}) || !r.num(t, "quality", "tetgen", 0, 100, &s.tet_quality) ||
        !r.num(t, "max_volume", "tetgen", 0, 1e18, &s.tet_max_volume))
      return false;
    if (s.tet_quality != 0 && s.tet_quality < 1.1) return r.fail("tetgen.quality must be 0 (off) or >= 1.1");
  }
  if (j.contains("material") && !r.material(j["material"], &s.material)) return false;
  if (!r.vec(j, "gravity", "scene", &s.gravity)) return false;
  if (j.contains("ground")) {
    const auto& g = j["ground"];
    s.ground = true;
    if (!r.only_keys(g, "ground", {"height", "friction"}) || !r.num(g, "height", "ground", -1e9, 1e9, &s.ground_height) ||
        !r.num(g, "friction", "ground", 0, 10, &s.ground_friction))
      return false;
  }
  for (const char* key : {"pins", "handles"}) {
    if (!j.contains(key)) continue;
    if (!j[key].is_array()) return r.fail(std::string("scene.") + key + " must be an array");
    for (size_t i = 0; i < j[key].size(); ++i) {
      Handle h;
      if (!r.handle(j[key][i], std::string(key) + "[" + std::to_string(i) + "]", key[0] == 'p', &h)) return false;
      s.handles.push_back(h);
    }
  }
  if (!r.integer(j, "frames", "scene", 1, 1000000, &s.frames) || !r.num(j, "fps", "scene", 1e-3, 1e6, &s.fps) ||
      !r.integer(j, "substeps", "scene", 1, 100000, &s.substeps) ||
      !r.integer(j, "iterations", "scene", 1, 10000, &s.iterations))
    return false;
  *scene = std::move(s);
  return true;
}

bool load_scene_file(const std::string& path, Scene* scene, std::string* error) {
  // read_file refuses a FIFO or device without waiting on it; a scene is a few KB.
  std::vector<uint8_t> bytes;
  if (!read_file(path, &bytes, error, uint64_t(64) << 20)) return false;
  nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end(), nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) {
    *error = path + ": not valid JSON";
    return false;
  }
  std::string why;
  if (!scene_from_json(j, std::filesystem::path(path).parent_path().string(), scene, &why)) {
    *error = path + ": " + why;
    return false;
  }
  if (scene->name.empty()) scene->name = path;  // messages then name the file
  return true;
}

std::vector<std::string> builtin_scene_names() { return corpus::builtin_scene_names(); }

bool builtin_scene(const std::string& name, Scene* scene, std::string* error) {
  nlohmann::json j;
  if (!corpus::builtin_scene_json(name, &j)) {
    std::string all;
    for (const auto& n : builtin_scene_names()) all += (all.empty() ? "" : ", ") + n;
    *error = "unknown built-in scene \"" + name + "\" (" + all + ")";
    return false;
  }
  std::string why;
  if (!scene_from_json(j, "", scene, &why)) {
    *error = "built-in scene " + name + ": " + why;
    return false;
  }
  scene->name = name;
  return true;
}

}  // namespace dcurve
