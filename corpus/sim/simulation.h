// A scene being simulated frame by frame: the surface loaded or generated, filled with tets,
// handles resolved to particles, and the XPBD solver. simulate_scene() drives it; benchmarks
// and tests use it to step and inspect frames one at a time.
#pragma once
#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

#include "corpus/sim/scene.h"
#include "corpus/sim/xpbd.h"

namespace dcurve {

// Loads or generates the scene's surface (scale and translate applied): 3 doubles per
// vertex, 3 ids per triangle. Errors name the mesh file.
bool load_scene_surface(const Scene& scene, std::vector<double>* xyz, std::vector<uint32_t>* faces, std::string* error);

class SceneSimulation {
 public:
  // Surface, tets, solver and handles; false with a message naming the mesh on bad input.
  bool init(const Scene& scene, std::string* error);

  // Simulates one frame (1/fps seconds, scene.substeps substeps). False when the state
  // stops being finite (an unstable setting), with a message.
  bool advance_frame(std::string* error);

  int frame() const { return frame_; }  // frames simulated so far; frame 0 is the rest pose
  // The input surface's vertices now, 3 floats each, in input order.
  void surface_positions(std::vector<float>* xyz) const;
  const std::vector<uint32_t>& surface_faces() const { return faces_; }
  uint32_t surface_vertex_count() const { return tets_.surface_vertex_count; }
  const TetMesh& tet_mesh() const { return tets_; }
  const XpbdSolver& solver() const { return solver_; }

 private:
  struct Driven {
    uint32_t particle;
    size_t handle;
  };
  Scene scene_;
  std::vector<uint32_t> faces_;
  TetMesh tets_;
  XpbdSolver solver_;
  std::vector<Driven> driven_;
  std::vector<Eigen::Vector3d> pivots_;  // one per handle
  int frame_ = 0;
};

}  // namespace dcurve
