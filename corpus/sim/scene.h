// A simulation scene: which surface to fill with tets, the material, what holds or moves it,
// and how long and finely to simulate. Read from a JSON scene file or a built-in scene
// (corpus/scenes.h); the README's "Scene files" section lists every key.
// Units: metres, kilograms, seconds, pascals; +y is up unless gravity says otherwise.
#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

#include "encoder/animation.h"

namespace dcurve {

// A set of particles chosen in the rest pose: inside an axis-aligned box, or on the side
// of a plane that its normal points to ((x - point) . normal >= 0).
struct Region {
  enum class Kind { Box, Plane } kind = Kind::Box;
  Eigen::Vector3d min{0, 0, 0}, max{0, 0, 0};       // box corners, metres
  Eigen::Vector3d point{0, 0, 0}, normal{0, 1, 0};  // plane, metres / unit vector
  bool contains(const Eigen::Vector3d& x) const;
};

// Particles of `region` follow a prescribed rigid motion: between `start` and `end`
// (seconds) they translate with `velocity` (m/s) and rotate about `axis` through `pivot`
// at `angular_velocity` (rad/s); before `start` they rest, after `end` they hold.
// A handle with no motion is a pin.
struct Handle {
  Region region;
  Eigen::Vector3d velocity{0, 0, 0};
  Eigen::Vector3d axis{0, 1, 0};
  double angular_velocity = 0;
  bool has_pivot = false;            // false: the centroid of the region's particles
  Eigen::Vector3d pivot{0, 0, 0};
  double start = 0, end = 1e30;
};

// Stable Neo-Hookean (Macklin & Mueller 2021) from Young's modulus and Poisson's ratio,
// plus optional classic XPBD edge-length and tet-volume constraints.
struct Material {
  double density = 1000;           // kg/m^3, > 0
  double youngs_modulus = 1e6;     // Pa, >= 0 (0 turns the Neo-Hookean constraints off)
  double poisson_ratio = 0.3;      // in [0.01, 0.499]
  double edge_compliance = -1;     // m/N per edge; < 0 = no edge constraints, 0 = rigid edges
  double volume_compliance = -1;   // 1/Pa (inverse bulk modulus); < 0 = none, 0 = incompressible
  double damping = 0.5;            // 1/s: velocities decay as exp(-damping t)
};

struct Scene {
  std::string name;                // for messages; a scene file without "name" uses its path
  std::string mesh_file;           // OBJ/PLY/OFF surface; empty when `generator` is used
  nlohmann::json generator;        // corpus/surfaces.h spec when mesh_file is empty
  double mesh_scale = 1;           // applied to the surface before `mesh_translate`
  Eigen::Vector3d mesh_translate{0, 0, 0};
  double tet_quality = 2.0;        // TetGen -q max radius-edge ratio, >= 1.1 (0 = no refinement)
  double tet_max_volume = 0;       // TetGen -a max tet volume, m^3 (0 = unlimited)
  Material material;
  Eigen::Vector3d gravity{0, -9.81, 0};  // m/s^2
  bool ground = false;             // a plane perpendicular to gravity ...
  double ground_height = 0;        // ... at this height along -gravity, metres
  double ground_friction = 0.5;    // Coulomb friction coefficient in [0, 10]
  std::vector<Handle> handles;     // pins and kinematic handles
  int frames = 60;                 // output frames including frame 0 (the rest pose), >= 1
  double fps = 30;                 // frames per second, > 0
  int substeps = 40;               // XPBD substeps per frame, >= 1
  int iterations = 1;              // constraint iterations per substep, >= 1
};

// Parses a scene from JSON; relative mesh paths resolve against `base_dir`.
bool scene_from_json(const nlohmann::json& j, const std::string& base_dir, Scene* scene, std::string* error);

// Reads a JSON scene file; errors name the file.
bool load_scene_file(const std::string& path, Scene* scene, std::string* error);

// Built-in scenes from corpus/scenes.h; "rope-small" first.
std::vector<std::string> builtin_scene_names();
bool builtin_scene(const std::string& name, Scene* scene, std::string* error);

// Runs tetrahedralization + XPBD; fills `out` with the input surface mesh (same vertices in
// the same order, same faces) in every frame. `progress` (may be empty) gets the fraction
// done in [0, 1]. Same scene -> same bytes. False with a message on bad input.
bool simulate_scene(const Scene& scene, Animation* out, const std::function<void(double)>& progress,
                    std::string* error);

}  // namespace dcurve
