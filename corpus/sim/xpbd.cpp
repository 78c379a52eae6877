#include "corpus/sim/xpbd.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace dcurve {
namespace {

// Tet ids sorted along a Morton (Z-order) curve of their centroids: Gauss-Seidel then sweeps
// through space, so the particles it touches are still in cache from the previous tets.
std::vector<size_t> spatial_order(const TetMesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const auto& p : mesh.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double extent = std::max((hi - lo).maxCoeff(), 1e-300);
  std::vector<std::pair<uint64_t, size_t>> keyed(mesh.tets.size());
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) c += mesh.points[mesh.tets[t][k]];
    uint64_t key = 0;
    for (int k = 0; k < 3; ++k) {
      const uint64_t q = uint64_t(std::clamp((c[k] / 4 - lo[k]) / extent, 0.0, 1.0) * 2097151.0);  // 21 bits
      for (int bit = 0; bit < 21; ++bit) key |= ((q >> bit) & 1u) << (3 * bit + k);
    }
    keyed[t] = {key, t};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<size_t> order(keyed.size());
  for (size_t t = 0; t < keyed.size(); ++t) order[t] = keyed[t].second;
  return order;
}

}  // namespace

bool XpbdSolver::init(const TetMesh& mesh, const Material& material, const XpbdWorld& world, std::string* error) {
  material_ = material;
  world_ = world;
  const double g = world.gravity.norm();
  up_ = g > 0 ? Eigen::Vector3d(-world.gravity / g) : Eigen::Vector3d(0, 1, 0);
  const double e = material.youngs_modulus, nu = material.poisson_ratio;
  mu_ = e / (2 * (1 + nu));
  lame_ = e * nu / ((1 + nu) * (1 - 2 * nu));
  // Rest stability of the stable Neo-Hookean energy (Macklin & Mueller 2021, eq. 13).
  gamma_ = lame_ > 0 ? 1 + mu_ / lame_ : 1;
  rest_ = x_ = prev_ = mesh.points;
  v_.assign(x_.size(), Eigen::Vector3d::Zero());
  std::vector<double> mass(x_.size(), 0.0);
  tets_.clear();
  tets_.reserve(mesh.tets.size());
  for (size_t t : spatial_order(mesh)) {
    Tet tet;
    for (int k = 0; k < 4; ++k) tet.id[k] = mesh.tets[t][k];
    Eigen::Matrix3d dm;
    for (int k = 0; k < 3; ++k) dm.col(k) = x_[tet.id[k + 1]] - x_[tet.id[0]];
    tet.volume = dm.determinant() / 6.0;
    const double scale = dm.colwise().norm().maxCoeff();
    if (!(tet.volume > 1e-9 * scale * scale * scale)) {
      *error = "tet " + std::to_string(t) + " is flat or inverted";
      return false;
    }
    tet.dm_inv = dm.inverse();
    for (int k = 0; k < 4; ++k) mass[tet.id[k]] += material.density * tet.volume / 4;
    tets_.push_back(tet);
  }
  w_.resize(x_.size());
  for (size_t i = 0; i < x_.size(); ++i) {
    if (!(mass[i] > 0)) {
      *error = "particle " + std::to_string(i) + " belongs to no tet";
      return false;
    }
    w_[i] = 1.0 / mass[i];
  }
  edges_.clear();
  if (material.edge_compliance >= 0) {
    std::vector<std::pair<int, int>> pairs;
    for (const Tet& t : tets_)
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b) pairs.emplace_back(std::min(t.id[a], t.id[b]), std::max(t.id[a], t.id[b]));
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    for (auto [a, b] : pairs) edges_.push_back({a, b, (x_[a] - x_[b]).norm()});
  }
  lambda_dev_.assign(tets_.size(), 0.0);
  lambda_hyd_.assign(tets_.size(), 0.0);
  lambda_vol_.assign(tets_.size(), 0.0);
  lambda_edge_.assign(edges_.size(), 0.0);
  pushed_.assign(x_.size(), 0.0);
  return true;
}

void XpbdSolver::make_kinematic(uint32_t i) {
  w_[i] = 0;
  v_[i].setZero();
}

void XpbdSolver::apply(const int id[4], double c, const Eigen::Vector3d g[4], double alpha_tilde, double* lambda) {
  double wsum = 0;
  for (int k = 0; k < 4; ++k) wsum += w_[id[k]] * g[k].squaredNorm();
  const double denom = wsum + alpha_tilde;
  if (!(denom > 1e-300)) return;  // every corner kinematic and the constraint rigid
  const double dlambda = (-c - alpha_tilde * *lambda) / denom;
  if (!std::isfinite(dlambda)) return;
  *lambda += dlambda;
  for (int k = 0; k < 4; ++k) x_[id[k]] += (w_[id[k]] * dlambda) * g[k];
}

void XpbdSolver::solve_tet(size_t t, double h2) {
  const Tet& tet = tets_[t];
  Eigen::Vector3d g[4];
  auto deformation = [&]() {
    Eigen::Matrix3d ds;
    for (int k = 0; k < 3; ++k) ds.col(k) = x_[tet.id[k + 1]] - x_[tet.id[0]];
    return Eigen::Matrix3d(ds * tet.dm_inv);
  };
  // Chain rule from dC/dF to the corners: dC/dx_k = column k-1 of dC/dF * Dm^-T, x_0 takes minus the sum.
  auto corners = [&](const Eigen::Matrix3d& dcdf) {
    const Eigen::Matrix3d grad = dcdf * tet.dm_inv.transpose();
    for (int k = 0; k < 3; ++k) g[k + 1] = grad.col(k);
    g[0] = -(g[1] + g[2] + g[3]);
  };
  auto cofactor = [](const Eigen::Matrix3d& f) {
    Eigen::Matrix3d c;
    c.col(0) = f.col(1).cross(f.col(2));
    c.col(1) = f.col(2).cross(f.col(0));
    c.col(2) = f.col(0).cross(f.col(1));
    return c;
  };
  if (mu_ > 0 && lame_ > 0) {
    // Deviatoric C_D = |F|_F (compliance 1 / (mu V)) and hydrostatic C_H = det F - gamma
    // (compliance 1 / (lambda V)) solved together as one 2x2 block: their gradients are
    // parallel at rest, and solved one after the other they fight (the rest pose drifts).
    const Eigen::Matrix3d f = deformation();
    const double norm = f.norm();
    if (norm > 1e-12) {
      Eigen::Vector3d gd[4];
      corners(f / norm);
      std::copy(g, g + 4, gd);
      corners(cofactor(f));
      const double ad = 1.0 / (mu_ * tet.volume * h2), ah = 1.0 / (lame_ * tet.volume * h2);
      double a11 = ad, a12 = 0, a22 = ah;
      for (int k = 0; k < 4; ++k) {
        const double w = w_[tet.id[k]];
        a11 += w * gd[k].squaredNorm();
        a12 += w * gd[k].dot(g[k]);
        a22 += w * g[k].squaredNorm();
      }
      const double b1 = -norm - ad * lambda_dev_[t], b2 = -(f.determinant() - gamma_) - ah * lambda_hyd_[t];
      const double det = a11 * a22 - a12 * a12;
      if (det > 1e-300 * a11 * a22) {
        const double dd = (b1 * a22 - b2 * a12) / det, dh = (a11 * b2 - a12 * b1) / det;
        if (std::isfinite(dd) && std::isfinite(dh)) {
          lambda_dev_[t] += dd;
          lambda_hyd_[t] += dh;
          for (int k = 0; k < 4; ++k) x_[tet.id[k]] += w_[tet.id[k]] * (dd * gd[k] + dh * g[k]);
        }
      }
    }
  }
  if (material_.volume_compliance >= 0) {
    // Volume: C = det F - 1 with compliance (1 / bulk modulus) / V, so the energy is
    // K V (J - 1)^2 / 2 whatever the tet size.
    const Eigen::Matrix3d f = deformation();
    corners(cofactor(f));
    apply(tet.id, f.determinant() - 1.0, g, material_.volume_compliance / (tet.volume * h2), &lambda_vol_[t]);
  }
}

void XpbdSolver::solve_edge(size_t e, double h2) {
  const Edge& edge = edges_[e];
  const Eigen::Vector3d d = x_[edge.b] - x_[edge.a];
  const double len = d.norm();
  if (len < 1e-15) return;
  const int id[4] = {edge.a, edge.b, edge.a, edge.b};
  // Corners 2 and 3 repeat a and b with zero gradient, so apply() serves edges too.
  const Eigen::Vector3d n = d / len;
  const Eigen::Vector3d g[4] = {-n, n, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  apply(id, len - edge.rest, g, material_.edge_compliance / h2, &lambda_edge_[e]);
}

void XpbdSolver::push_out_of_ground() {
  for (size_t i = 0; i < x_.size(); ++i) {
    const double depth = world_.ground_height - up_.dot(x_[i]);
    if (depth <= 0 || w_[i] == 0) continue;
    x_[i] += depth * up_;
    pushed_[i] += depth;
  }
}

void XpbdSolver::apply_ground_friction() {
  for (size_t i = 0; i < x_.size(); ++i) {
    if (pushed_[i] <= 0) continue;
    // Coulomb friction in position form: the tangential slide this substep is cut by at
    // most friction * (normal correction).
    Eigen::Vector3d slide = x_[i] - prev_[i];
    slide -= up_.dot(slide) * up_;
    const double len = slide.norm(), cap = world_.ground_friction * pushed_[i];
    x_[i] -= len <= cap ? slide : Eigen::Vector3d(slide * (cap / len));
  }
}

void XpbdSolver::substep(double h, int iterations) {
  const size_t n = x_.size();
  for (size_t i = 0; i < n; ++i) {
    if (w_[i] == 0) continue;  // kinematic: set_position already placed it
    prev_[i] = x_[i];
    v_[i] += h * world_.gravity;
    x_[i] += h * v_[i];
  }
  std::fill(lambda_dev_.begin(), lambda_dev_.end(), 0.0);
  std::fill(lambda_hyd_.begin(), lambda_hyd_.end(), 0.0);
  std::fill(lambda_vol_.begin(), lambda_vol_.end(), 0.0);
  std::fill(lambda_edge_.begin(), lambda_edge_.end(), 0.0);
  std::fill(pushed_.begin(), pushed_.end(), 0.0);
  const double h2 = h * h;
  for (int it = 0; it < iterations; ++it) {
    for (size_t t = 0; t < tets_.size(); ++t) solve_tet(t, h2);
    for (size_t e = 0; e < edges_.size(); ++e) solve_edge(e, h2);
    // Contact inside the loop, so the constraints see it and little penetration is left
    // for the last projection to turn into velocity.
    if (world_.ground) push_out_of_ground();
  }
  if (world_.ground) apply_ground_friction();
  const double keep = std::exp(-material_.damping * h);
  for (size_t i = 0; i < n; ++i) {
    if (w_[i] == 0) continue;
    v_[i] = (x_[i] - prev_[i]) * (keep / h);
  }
}

double XpbdSolver::kinetic_energy() const {
  double e = 0;
  for (size_t i = 0; i < x_.size(); ++i)
    if (w_[i] > 0) e += 0.5 * v_[i].squaredNorm() / w_[i];
  return e;
}

}  // namespace dcurve
