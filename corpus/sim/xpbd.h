// XPBD (Macklin, Mueller, Chentanez 2016) on a tet mesh with substepping (Macklin et al.
// 2019, "Small steps"): stable Neo-Hookean tet constraints (Macklin & Mueller 2021), optional
// edge-length and tet-volume constraints, gravity, damping, a ground plane with Coulomb
// friction and kinematic particles. Compliance is per unit of energy, so the material does
// not change with the time step or the iteration count. Single-threaded Gauss-Seidel in a
// fixed order: the same input gives the same bits.
#pragma once
#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

#include "corpus/sim/scene.h"
#include "corpus/sim/tetrahedralize.h"

namespace dcurve {

struct XpbdWorld {
  Eigen::Vector3d gravity{0, -9.81, 0};  // m/s^2
  bool ground = false;
  double ground_height = 0;              // metres along the up direction (-gravity)
  double ground_friction = 0.5;          // Coulomb coefficient
};

class XpbdSolver {
 public:
  // Copies the rest pose, builds the constraints and lumps tet masses (density * volume / 4
  // per corner). False when a tet is inverted or flat or a particle gets no mass.
  bool init(const TetMesh& mesh, const Material& material, const XpbdWorld& world, std::string* error);

  // Makes particle `i` kinematic (infinite mass): it moves only through set_position.
  void make_kinematic(uint32_t i);
  // Moves a kinematic particle to where it must be at the end of the next substep.
  void set_position(uint32_t i, const Eigen::Vector3d& x) { x_[i] = x; }

  // Advances by one substep of h > 0 seconds with `iterations` >= 1 Gauss-Seidel sweeps.
  void substep(double h, int iterations);

  const std::vector<Eigen::Vector3d>& positions() const { return x_; }
  const std::vector<Eigen::Vector3d>& rest_positions() const { return rest_; }
  double kinetic_energy() const;  // joules, free particles only
  size_t tet_count() const { return tets_.size(); }
  size_t particle_count() const { return x_.size(); }

 private:
  struct Tet {
    int id[4];
    Eigen::Matrix3d dm_inv;  // inverse of the rest edge matrix [x1-x0, x2-x0, x3-x0]
    double volume;           // rest volume, m^3
  };
  struct Edge {
    int a, b;
    double rest;  // metres
  };
  // One XPBD update of a constraint C over the tet's 4 corners with gradients g.
  void apply(const int id[4], double c, const Eigen::Vector3d g[4], double alpha_tilde, double* lambda);
  void solve_tet(size_t t, double h2);
  void solve_edge(size_t e, double h2);
  void push_out_of_ground();
  void apply_ground_friction();

  Material material_;
  XpbdWorld world_;
  Eigen::Vector3d up_{0, 1, 0};
  double mu_ = 0, lame_ = 0, gamma_ = 1;
  std::vector<Eigen::Vector3d> x_, prev_, v_, rest_;
  std::vector<double> w_;       // inverse masses, 0 = kinematic
  std::vector<double> pushed_;  // ground correction this substep, metres
  std::vector<Tet> tets_;
  std::vector<Edge> edges_;
  std::vector<double> lambda_dev_, lambda_hyd_, lambda_vol_, lambda_edge_;
};

}  // namespace dcurve
