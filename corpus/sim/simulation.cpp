#include "corpus/sim/simulation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "corpus/surfaces.h"
#include "encoder/io/frames.h"

namespace dcurve {

bool load_scene_surface(const Scene& scene, std::vector<double>* xyz, std::vector<uint32_t>* faces, std::string* error) {
  if (!scene.mesh_file.empty()) {
    std::vector<float> xyzf;
    if (!read_mesh(scene.mesh_file, &xyzf, faces, error)) return false;
    xyz->assign(xyzf.begin(), xyzf.end());
  } else {
    corpus::SurfaceMesh m;
    if (!corpus::generate_surface(scene.generator, &m, error)) return false;
    *xyz = std::move(m.xyz);
    *faces = std::move(m.faces);
  }
  for (size_t i = 0; i < xyz->size(); ++i) (*xyz)[i] = (*xyz)[i] * scene.mesh_scale + scene.mesh_translate[i % 3];
  return true;
}

bool SceneSimulation::init(const Scene& scene, std::string* error) {
  scene_ = scene;
  frame_ = 0;
  const std::string source = scene.mesh_file.empty() ? "scene " + scene.name + " mesh" : scene.mesh_file;
  std::vector<double> xyz;
  std::string why;
  if (!load_scene_surface(scene, &xyz, &faces_, &why) ||
      !tetrahedralize_surface(xyz, faces_, TetOptions{scene.tet_quality, scene.tet_max_volume}, &tets_, &why)) {
    *error = why.rfind(source, 0) == 0 ? why : source + ": " + why;
    return false;
  }
  XpbdWorld world{scene.gravity, scene.ground, scene.ground_height, scene.ground_friction};
  if (!solver_.init(tets_, scene.material, world, &why)) {
    *error = source + ": " + why;
    return false;
  }
  // Each particle follows the first handle whose region holds it in the rest pose.
  driven_.clear();
  pivots_.assign(scene.handles.size(), Eigen::Vector3d::Zero());
  std::vector<size_t> count(scene.handles.size(), 0);
  const auto& rest = solver_.rest_positions();
  for (uint32_t i = 0; i < rest.size(); ++i)
    for (size_t h = 0; h < scene.handles.size(); ++h)
      if (scene.handles[h].region.contains(rest[i])) {
        driven_.push_back({i, h});
        solver_.make_kinematic(i);
        pivots_[h] += rest[i];
        ++count[h];
        break;
      }
  for (size_t h = 0; h < scene.handles.size(); ++h) {
    if (count[h] == 0) {
      *error = "scene " + scene.name + ": handle/pin " + std::to_string(h) + " holds no particle of the mesh";
      return false;
    }
    pivots_[h] = scene.handles[h].has_pivot ? scene.handles[h].pivot : Eigen::Vector3d(pivots_[h] / double(count[h]));
  }
  return true;
}

bool SceneSimulation::advance_frame(std::string* error) {
  const int substeps = scene_.substeps;
  const double h = 1.0 / (scene_.fps * substeps);
  for (int s = 0; s < substeps; ++s) {
    // Time from a step count, not a running sum, so every frame lands on the same bits.
    const double t = double(int64_t(frame_) * substeps + s + 1) * h;
    for (const Driven& d : driven_) {
      const Handle& hd = scene_.handles[d.handle];
      const double active = std::clamp(t, hd.start, hd.end) - hd.start;
      // Pins and handles that have not started stay exactly at rest (no rounding drift).
      if (active == 0 || (hd.velocity.isZero() && hd.angular_velocity == 0)) continue;
      const Eigen::AngleAxisd turn(hd.angular_velocity * active, hd.axis);
      const Eigen::Vector3d& x0 = solver_.rest_positions()[d.particle];
      solver_.set_position(d.particle, pivots_[d.handle] + turn * (x0 - pivots_[d.handle]) + hd.velocity * active);
    }
    solver_.substep(h, scene_.iterations);
  }
  ++frame_;
  for (const auto& x : solver_.positions())
    if (!x.allFinite()) {
      *error = "scene " + scene_.name + ": simulation became unstable at frame " + std::to_string(frame_) +
               " (try more substeps or a softer material)";
      return false;
    }
  return true;
}

void SceneSimulation::surface_positions(std::vector<float>* xyz) const {
  const auto& x = solver_.positions();
  xyz->resize(size_t(tets_.surface_vertex_count) * 3);
  for (uint32_t i = 0; i < tets_.surface_vertex_count; ++i)
    for (int k = 0; k < 3; ++k) (*xyz)[3 * size_t(i) + k] = float(x[i][k]);
}

bool simulate_scene(const Scene& scene, Animation* out, const std::function<void(double)>& progress,
                    std::string* error) {
  SceneSimulation sim;
  if (!sim.init(scene, error)) return false;
  Animation anim;
  anim.vertex_count = sim.surface_vertex_count();
  anim.faces = sim.surface_faces();
  anim.frame_rate = scene.fps;
  anim.frames.resize(size_t(scene.frames));
  sim.surface_positions(&anim.frames[0]);
  for (int f = 1; f < scene.frames; ++f) {
    if (!sim.advance_frame(error)) return false;
    sim.surface_positions(&anim.frames[size_t(f)]);
    if (progress) progress(double(f) / (scene.frames - 1));
  }
  if (progress) progress(1.0);
  *out = std::move(anim);
  return true;
}

}  // namespace dcurve
