#include "encoder/fit/rigid.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>

namespace dcurve {
namespace {

using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

Eigen::Map<const Points> frame_points(const std::vector<double>& xyz, size_t frame, size_t points) {
  return Eigen::Map<const Points>(xyz.data() + frame * points * 3, Eigen::Index(points), 3);
}

// Kabsch: the rotation R (det +1) minimizing sum |R (a - ca) - (b - cb)|^2.
Eigen::Matrix3d kabsch(const Points& a_centered, const Points& b_centered) {
  Eigen::Matrix3d h = a_centered.transpose() * b_centered;
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d v = svd.matrixV(), u = svd.matrixU();
  double d = (v * u.transpose()).determinant() < 0 ? -1.0 : 1.0;
  Eigen::Matrix3d fix = Eigen::Matrix3d::Identity();
  fix(2, 2) = d;
  return v * fix * u.transpose();
}

}  // namespace

void remove_rigid_motion(const std::vector<double>& xyz, const std::vector<double>& tau, size_t points,
                         RigidTrack* track, std::vector<double>* local) {
  const size_t frames = tau.size();
  track->keys.assign(frames, RigidKey());
  local->assign(xyz.size(), 0.0);
  if (frames == 0 || points == 0) return;
  Points ref = frame_points(xyz, 0, points);
  Eigen::RowVector3d ref_c = ref.colwise().mean();
  Points ref_centered = ref.rowwise() - ref_c;
  for (int a = 0; a < 3; ++a) track->ref_centroid[a] = ref_c(a);
  Eigen::Quaterniond previous(1, 0, 0, 0);
  for (size_t f = 0; f < frames; ++f) {
    Points cur = frame_points(xyz, f, points);
    Eigen::RowVector3d c = cur.colwise().mean();
    Points cur_centered = cur.rowwise() - c;
    Eigen::Matrix3d r = f == 0 ? Eigen::Matrix3d::Identity() : kabsch(ref_centered, cur_centered);
    Eigen::Quaterniond q(r);
    q.normalize();
    if (q.dot(previous) < 0) q.coeffs() = -q.coeffs();  // keep slerp on the short arc
    previous = q;
    RigidKey& key = track->keys[f];
    key.tau = tau[f];
    key.q[0] = q.w(); key.q[1] = q.x(); key.q[2] = q.y(); key.q[3] = q.z();
    for (int a = 0; a < 3; ++a) key.centroid[a] = c(a);
    // local = R^T (world - centroid) + ref_centroid
    Eigen::Map<Points> out(local->data() + f * points * 3, Eigen::Index(points), 3);
    out = (cur_centered * q.toRotationMatrix()).rowwise() + ref_c;
  }
}

void rigid_at(const RigidTrack& track, double tau, double rotation[9], double centroid[3]) {
  const auto& keys = track.keys;
  auto to_quat = [](const RigidKey& k) { return Eigen::Quaterniond(k.q[0], k.q[1], k.q[2], k.q[3]); };
  Eigen::Quaterniond q(1, 0, 0, 0);
  Eigen::Vector3d c(track.ref_centroid[0], track.ref_centroid[1], track.ref_centroid[2]);
  if (!keys.empty()) {
    size_t hi = size_t(std::upper_bound(keys.begin(), keys.end(), tau,
                                        [](double t, const RigidKey& k) { return t < k.tau; }) -
                       keys.begin());
    if (hi == 0 || hi == keys.size()) {
      const RigidKey& k = hi == 0 ? keys.front() : keys.back();
      q = to_quat(k);
      c = Eigen::Vector3d(k.centroid[0], k.centroid[1], k.centroid[2]);
    } else {
      const RigidKey& a = keys[hi - 1];
      const RigidKey& b = keys[hi];
      double w = b.tau > a.tau ? (tau - a.tau) / (b.tau - a.tau) : 0.0;
      q = to_quat(a).slerp(w, to_quat(b));
      for (int i = 0; i < 3; ++i) c(i) = (1 - w) * a.centroid[i] + w * b.centroid[i];
    }
  }
  Eigen::Matrix3d r = q.normalized().toRotationMatrix();
  for (int i = 0; i < 3; ++i) {
    centroid[i] = c(i);
    for (int j = 0; j < 3; ++j) rotation[i * 3 + j] = r(i, j);
  }
}

void apply_rigid(const RigidTrack& track, double tau, size_t points, double* xyz) {
  if (track.keys.empty()) return;
  double r[9], c[3];
  rigid_at(track, tau, r, c);
  for (size_t p = 0; p < points; ++p) {
    double d[3];
    for (int a = 0; a < 3; ++a) d[a] = xyz[p * 3 + a] - track.ref_centroid[a];
    for (int a = 0; a < 3; ++a) xyz[p * 3 + a] = r[a * 3] * d[0] + r[a * 3 + 1] * d[1] + r[a * 3 + 2] * d[2] + c[a];
  }
}

}  // namespace dcurve
