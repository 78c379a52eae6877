// Frame poses of a posed low-rank model (LRNK, format 2.5): a body that turns or travels
// needs many principal components in world coordinates, since every component then also
// turns with it; carried back into one pose, the same frames need fewer.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dcurve {

struct FramePoses {
  // As LowRankModel::poses stores them (kLowRankPoseValues per frame, codec/common/low_rank.h):
  // frame f = pose_centre + t_f + m_f (posed - pose_centre), m_f in units of 2^-16.
  std::vector<int32_t> poses;
  int32_t centre[3] = {0, 0, 0};  // grid units: frame 0's centroid, rounded
  // Every frame carried into frame 0's pose through the inverse of its stored (rounded) pose,
  // rounded to the grid: what the posed model's components are taken from. Frame 0 is
  // itself (its pose is the identity), so a frame-0 anchor still predicts it exactly.
  std::vector<int32_t> aligned;
  double max_angle = 0;  // largest rotation of a frame against frame 0, radians
};

// The rigid motion (rotation and translation, least squares over all vertices: Kabsch, det
// +1) that carries frame 0's grid values q onto each frame's (F frames of n = V * 3 values,
// frame-major). False when a pose or an aligned value would leave the format's ranges (then
// no posed model is tried). Deterministic.
bool estimate_frame_poses(const std::vector<int32_t>& q, uint32_t F, size_t n, FramePoses* out);

}  // namespace dcurve
