// Posed low-rank models (LRNK frame poses, format 2.5): the pose formula both sides compute,
// poses estimated from frames, files that carry them, and damaged poses rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "codec/common/low_rank.h"
#include "codec/common/validate.h"
#include "codec/compress/low_rank_writer.h"
#include "codec/decompress/container_reader.h"
#include "container_bytes.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "encoder/rate/frame_poses.h"
#include "test_util.h"

namespace dcurve {
namespace {

constexpr int32_t kOne = int32_t(1) << kLowRankPoseShift;

// A W x H strip whose shape jumps between combinations of three smooth modes from frame to
// frame (random weights: temporal prediction cannot follow, a low-rank model can) while the
// whole strip tumbles (turns about y by up to `turn` radians and about x by half that) and
// drifts: three components in its own pose, many more in world coordinates.
Animation turning_strip(uint32_t W, uint32_t H, uint32_t F, double turn) {
  Animation anim;
  anim.vertex_count = W * H;
  anim.faces = test::grid_faces(W, H);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> weight(-1, 1);
  for (uint32_t f = 0; f < F; ++f) {
    const double t = double(f) / (F - 1), a = turn * t, c = std::cos(a), s = std::sin(a);
    const double w0 = weight(rng), w1 = weight(rng), w2 = weight(rng);
    std::vector<float> xyz;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const double u = double(x) / (W - 1), w = 0.3 * y / (H - 1);
        const double bend = 0.3 * (w0 * std::sin(M_PI * u) + w1 * u * u + w2 * std::cos(2 * M_PI * u) * w);
        // Turned about y by a, then about x by a / 2: a tumble, not a spin about one axis.
        const double px = u - 0.5, py = w - 0.15, pz = bend;
        const double x1 = c * px + s * pz, z1 = -s * px + c * pz;
        const double cb = std::cos(a / 2), sb = std::sin(a / 2);
        xyz.insert(xyz.end(), {float(x1 + 0.2 * t), float(cb * py - sb * z1), float(sb * py + cb * z1)});
      }
    anim.frames.push_back(std::move(xyz));
  }
  return anim;
}

std::vector<uint8_t> encode(const Animation& anim, bool poses, EncodeReport* rep) {
  EncodeOptions o;
  o.tolerance = 1e-3;
  o.grid_refinement = 2;  // the grid search is grid_test's
  o.low_rank_poses = poses;
  return test::encoded(anim, o, rep);
}

Model read(const std::vector<uint8_t>& bytes) {
  Model m;
  std::string err;
  EXPECT_TRUE(read_container(bytes.data(), bytes.size(), &m, &err)) << err;
  return m;
}

// Frame 0 unposed, frame 1 turned a quarter about z, moved and with a half-unit entry: the
// values of format_spec/dcrv.md section 10's formula worked by hand.
TEST(LowRankPose, PoseMapsThePosedPredictionAsTheSpecSays) {
  LowRankModel lr;
  lr.components = 1;
  lr.coeffs = {0, 0};  // two frames: the prediction is the mean alone
  lr.pose_centre[0] = 10;
  lr.pose_centre[1] = 20;
  lr.pose_centre[2] = 30;
  lr.poses = {kOne, 0, 0, 0, kOne, 0, 0, 0, kOne, 0, 0, 0,
              0, -kOne, 0, kOne, 0, 0, 0, 0, kOne / 2, 5, -3, 2};
  // mean (vertex 0 then vertex 1), then one basis vector of zeros.
  const std::vector<int32_t> mean_and_basis = {11, 20, 30, 10, 22, 33, 0, 0, 0, 0, 0, 0};
  std::vector<int32_t> out(6);
  low_rank_frame(lr, 0, mean_and_basis.data(), 6, out.data());
  EXPECT_EQ(out, std::vector<int32_t>({11, 20, 30, 10, 22, 33}));
  low_rank_frame(lr, 1, mean_and_basis.data(), 6, out.data());
  // Vertex 0: d = (1, 0, 0) -> (0, 1, 0); z: 30 + 2 + round(0 / 2). Vertex 1: d = (0, 2, 3) ->
  // (-2, 0, 1.5 rounded half up = 2).
  EXPECT_EQ(out, std::vector<int32_t>({15, 18, 32, 13, 17, 34}));
  // A posed-space value far from the centre enters clamped: no overflow, a bounded answer.
  const std::vector<int32_t> far = {int32_t(1) << 30, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  lr.pose_centre[0] = -(int32_t(1) << 30);
  low_rank_frame(lr, 0, far.data(), 6, out.data());
  EXPECT_EQ(out[0], -(int32_t(1) << 30) + int32_t(kMaxLowRankPoseReach));
}

// A rigidly turning cloud on the grid: frame 0's pose is the identity exactly (so a frame-0
// anchor still predicts it exactly), the angle is found, and every frame carried back lands
// within a few grid units of frame 0.
TEST(LowRankPose, EstimatedPosesCarryFramesBackToFrameZero) {
  const uint32_t V = 200, F = 5;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1000, 1000);
  std::vector<double> rest(size_t(V) * 3);
  for (double& x : rest) x = u(rng);
  std::vector<int32_t> q;
  for (uint32_t f = 0; f < F; ++f) {
    const double a = 0.3 * f, c = std::cos(a), s = std::sin(a);
    for (uint32_t v = 0; v < V; ++v) {
      const double x = rest[3 * v], y = rest[3 * v + 1], z = rest[3 * v + 2];
      q.push_back(int32_t(std::lround(c * x - s * y + 40.0 * f)));
      q.push_back(int32_t(std::lround(s * x + c * y)));
      q.push_back(int32_t(std::lround(z - 7.0 * f)));
    }
  }
  FramePoses poses;
  ASSERT_TRUE(estimate_frame_poses(q, F, size_t(V) * 3, &poses));
  EXPECT_NEAR(poses.max_angle, 1.2, 1e-3);
  const std::vector<int32_t> identity = {kOne, 0, 0, 0, kOne, 0, 0, 0, kOne, 0, 0, 0};
  EXPECT_EQ(std::vector<int32_t>(poses.poses.begin(), poses.poses.begin() + kLowRankPoseValues), identity);
  for (uint32_t f = 0; f < F; ++f)
    for (size_t i = 0; i < size_t(V) * 3; ++i)
      ASSERT_NEAR(poses.aligned[size_t(f) * V * 3 + i], q[i], f == 0 ? 0 : 3) << "frame " << f << " value " << i;
}

// A strip that turns while it bends: the encoder keeps a posed model, the file is smaller
// than the best without poses, and every frame decodes within the tolerance.
TEST(LowRankPose, TurningBodyGetsAPosedModelWithinTolerance) {
  const Animation anim = turning_strip(32, 8, 48, 3.0);
  EncodeReport posed_rep, plain_rep;
  const std::vector<uint8_t> posed = encode(anim, true, &posed_rep);
  const std::vector<uint8_t> plain = encode(anim, false, &plain_rep);
  EXPECT_FALSE(read(posed).low_rank.poses.empty());
  EXPECT_TRUE(read(plain).low_rank.poses.empty());
  EXPECT_LT(posed.size(), plain.size());
  EXPECT_LE(test::decoded_max_error(posed, anim), 1e-3);
  EXPECT_LE(posed_rep.error.max_error, 1e-3);
}

// Poses out of range, the reserved flag bit, and every truncation of a posed section are
// rejected; a damaged byte either fails or decodes the frames the undamaged file decodes.
TEST(LowRankPose, DamagedPosesAreRejected) {
  const Animation anim = turning_strip(32, 8, 48, 3.0);
  EncodeReport rep;
  const std::vector<uint8_t> bytes = encode(anim, true, &rep);
  Model m = read(bytes);
  ASSERT_FALSE(m.low_rank.poses.empty());
  std::string err;
  EXPECT_TRUE(validate_model(m, &err)) << err;
  Model bad = m;
  bad.low_rank.poses[3] = int32_t(kMaxLowRankPoseMatrix + 1);
  EXPECT_FALSE(validate_model(bad, &err));
  bad = m;
  bad.low_rank.poses.pop_back();
  EXPECT_FALSE(validate_model(bad, &err));
  bad = m;
  bad.low_rank.pose_centre[1] = int32_t(kMaxLowRankPoseOffset + 1);
  EXPECT_FALSE(validate_model(bad, &err));

  const std::vector<uint8_t> raw = low_rank_bytes(m);
  ASSERT_GE(raw.size(), 40u);
  auto with_payload = [&](const std::vector<uint8_t>& payload) {
    testing::RawFile f = testing::split_file(bytes);
    for (testing::RawSection& s : f.sections)
      if (s.tag == "LRNK") s = testing::plain_section("LRNK", true, payload);
    return testing::assemble(f);
  };
  // The file as written again with its LRNK stored plainly decodes; the reserved bit fails.
  std::vector<uint8_t> file = with_payload(raw);
  ASSERT_TRUE(read_container(file.data(), file.size(), &m, &err)) << err;
  std::vector<uint8_t> p = raw;
  p[2] |= 0x20;
  file = with_payload(p);
  EXPECT_FALSE(read_container(file.data(), file.size(), &m, &err));
  // A pose stream cut short (the last bytes of the section are the pose stream's).
  for (size_t cut = 1; cut <= 8; ++cut) {
    file = with_payload({raw.begin(), raw.end() - std::ptrdiff_t(cut)});
    EXPECT_FALSE(read_container(file.data(), file.size(), &m, &err)) << cut;
  }
  auto original = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(original) << err;
  for (size_t i = raw.size() - 40; i < raw.size(); ++i) {
    p = raw;
    p[i] ^= 0x5a;
    ASSERT_TRUE(test::refused_or_decodes_as(with_payload(p), *original)) << "byte " << i;
  }
}

}  // namespace
}  // namespace dcurve
