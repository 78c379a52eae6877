// Per-frame rigid motion of one curve (2024 paper, sec. 4, done properly): each frame is
// aligned to the reference frame by the least-squares rotation with det = +1 (Kabsch) about
// the centroids, the aligned ("local") shapes are fitted, and the rigid motion is put back.
//
// Restoring at any tau: keys sit at the fitted frames' tau. Between two keys the rotation is
// the quaternion slerp (shortest arc, signs made consistent key to key) and the centroid is
// linearly interpolated; before the first / after the last key the end key holds.
//   world = R(tau) * (local - ref_centroid) + centroid(tau)
// so the reference frame's key is the identity and local == world there.
// Keying the translation (exact at the fitted frames, linear between them) measured better on
// corpus-ext's paper2024 runs than leaving it in the fitted data (horse-gallop mean E_An 0.069
// against 0.219): four time functions follow fast curve motion worse than the keys.
#pragma once
#include <cstddef>
#include <vector>

namespace dcurve {

struct RigidKey {
  double tau = 0;                   // segment-local time of the key, [0, 1]
  double q[4] = {1, 0, 0, 0};       // unit quaternion (w, x, y, z): local -> world rotation
  double centroid[3] = {0, 0, 0};   // world centroid of the frame's points, model units
};

struct RigidTrack {
  double ref_centroid[3] = {0, 0, 0};  // centroid of the reference (first) frame
  std::vector<RigidKey> keys;          // increasing tau; empty = no rigid motion
};

// Finds the rigid motion of each frame relative to frame 0 and writes the aligned local
// positions. xyz: frames * points * 3 (frame-major), model units; tau per frame.
void remove_rigid_motion(const std::vector<double>& xyz, const std::vector<double>& tau, std::size_t points,
                         RigidTrack* track, std::vector<double>* local);

// Rotation matrix (row-major 3x3) and centroid of the track at tau, as described above.
void rigid_at(const RigidTrack& track, double tau, double rotation[9], double centroid[3]);

// world = R (local - ref_centroid) + centroid for `points` points, in place. No-op without keys.
void apply_rigid(const RigidTrack& track, double tau, std::size_t points, double* xyz);

}  // namespace dcurve
