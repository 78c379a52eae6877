#include "encoder/rate/frame_poses.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

#include "codec/common/low_rank.h"

namespace dcurve {
namespace {

Eigen::Vector3d centroid(const int32_t* x, size_t V) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (size_t v = 0; v < V; ++v) c += Eigen::Vector3d(x[3 * v], x[3 * v + 1], x[3 * v + 2]);
  return c / double(std::max<size_t>(V, 1));
}

// The rotation R minimizing sum |R (a_v - ca) - (b_v - cb)|^2 (Kabsch, reflection removed).
Eigen::Matrix3d best_rotation(const int32_t* a, const Eigen::Vector3d& ca, const int32_t* b, const Eigen::Vector3d& cb,
                              size_t V) {
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (size_t v = 0; v < V; ++v)
    h += (Eigen::Vector3d(a[3 * v], a[3 * v + 1], a[3 * v + 2]) - ca) *
         (Eigen::Vector3d(b[3 * v], b[3 * v + 1], b[3 * v + 2]) - cb).transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixV() * d * svd.matrixU().transpose();
}

}  // namespace

bool estimate_frame_poses(const std::vector<int32_t>& q, uint32_t F, size_t n, FramePoses* out) {
  const size_t V = n / 3;
  if (F == 0 || V == 0 || q.size() != size_t(F) * n) return false;
  const double unit = std::ldexp(1.0, int(kLowRankPoseShift));
  const Eigen::Vector3d c0 = centroid(q.data(), V);
  Eigen::Vector3d centre;
  for (int a = 0; a < 3; ++a) {
    centre(a) = std::nearbyint(c0(a));
    if (!(std::fabs(centre(a)) <= double(kMaxLowRankPoseOffset))) return false;
    out->centre[a] = int32_t(centre(a));
  }
  out->poses.assign(size_t(F) * kLowRankPoseValues, 0);
  out->aligned.assign(q.size(), 0);
  out->max_angle = 0;
  for (uint32_t f = 0; f < F; ++f) {
    const int32_t* x = q.data() + size_t(f) * n;
    int32_t* pose = out->poses.data() + size_t(f) * kLowRankPoseValues;
    Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    if (f > 0) {  // frame 0's pose is the identity, exactly
      const Eigen::Vector3d cf = centroid(x, V);
      const Eigen::Matrix3d r = best_rotation(q.data(), c0, x, cf, V);
      out->max_angle = std::max(out->max_angle, std::acos(std::clamp((r.trace() - 1) / 2, -1.0, 1.0)));
      // x = R (p - c0) + cf = R (p - centre) + centre + t with t = cf - centre - R (c0 - centre).
      const Eigen::Vector3d tt = cf - centre - r * (c0 - centre);
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) m(a, b) = std::nearbyint(r(a, b) * unit) / unit;
        t(a) = std::nearbyint(tt(a));
        if (!(std::fabs(t(a)) <= double(kMaxLowRankPoseOffset))) return false;
      }
    }
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) pose[3 * a + b] = int32_t(std::lround(m(a, b) * unit));
      pose[9 + a] = int32_t(t(a));
    }
    // The stored pose, undone: a rotation's rounded matrix is still invertible.
    const Eigen::Matrix3d inverse = m.inverse();
    for (size_t v = 0; v < V; ++v) {
      const Eigen::Vector3d p =
          centre + inverse * (Eigen::Vector3d(x[3 * v], x[3 * v + 1], x[3 * v + 2]) - centre - t);
      for (int a = 0; a < 3; ++a) {
        const double r = std::nearbyint(p(a));
        if (!(std::fabs(r) <= double(INT32_MAX))) return false;
        out->aligned[size_t(f) * n + 3 * v + size_t(a)] = int32_t(r);
      }
    }
  }
  return true;
}

}  // namespace dcurve
