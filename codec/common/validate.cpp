#include "codec/common/validate.h"

#include "codec/common/basis.h"
#include "codec/common/container_format.h"
#include "codec/common/error.h"
#include "codec/common/low_rank.h"
#include "codec/common/render_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace dcurve {
namespace {
bool finite_positive(double v) { return std::isfinite(v) && v > 0; }

bool validate_attribute(const RenderAttribute& a, size_t render_count, std::string* error) {
  if (uint8_t(a.semantic) >= kAttributeSemanticCount || !attribute_components_allowed(a.semantic, a.components) ||
      a.bits < 1 || a.bits > kMaxAttributeBits)
    return fail(error, "render attribute has an unknown semantic, component count or precision");
  if (a.q.size() != render_count * a.components) return fail(error, "render attribute does not cover every render vertex");
  for (uint32_t c = 0; c < a.components; ++c)
    if (!std::isfinite(a.lo[c]) || !std::isfinite(a.hi[c]) || a.lo[c] > a.hi[c])
      return fail(error, "render attribute range is not finite and ordered");
  for (uint32_t q : a.q)
    if (q >> a.bits) return fail(error, "render attribute value outside its precision");
  return true;
}

// Render vertices (REND): vertices in first-use order, corners that show their own vertex, one
// attribute per semantic in ascending order.
bool validate_render(const Model& m, std::string* error) {
  const RenderMesh& r = m.render;
  if (r.empty()) {
    if (!r.corners.empty() || !r.attributes.empty()) return fail(error, "render attributes without render vertices");
    return true;
  }
  std::vector<uint32_t> ordinals;
  if (m.faces.empty() || !render_source_in_first_use_order(r.source, m.meta.vertex_count) ||
      !render_corner_ordinals(m.faces, r, m.meta.vertex_count, &ordinals))
    return fail(error, "render vertices do not show every vertex in first-use order, or a corner shows another vertex");
  for (size_t i = 0; i < r.attributes.size(); ++i) {
    if (i > 0 && uint8_t(r.attributes[i].semantic) <= uint8_t(r.attributes[i - 1].semantic))
      return fail(error, "render attributes are not in ascending semantic order");
    if (!validate_attribute(r.attributes[i], r.source.size(), error)) return false;
  }
  if (r.groups.empty()) return r.face_group.empty() ? true : fail(error, "face groups without groups");
  if (r.face_group.size() != m.faces.size() / 3) return fail(error, "face groups do not cover every triangle");
  for (uint32_t g : r.face_group)
    if (g >= r.groups.size()) return fail(error, "a triangle's face group does not exist");
  for (const FaceGroup& g : r.groups)
    if (g.material < -1) return fail(error, "a face group's material index is negative");
  return true;
}

bool validate_placement(const Placement& p, std::string* error) {
  if (!std::isfinite(p.start_time)) return fail(error, "start time is not finite");
  for (double x : p.matrix)
    if (!std::isfinite(x)) return fail(error, "placement matrix is not finite");
  return true;
}
}  // namespace

bool validate_model(const Model& m, std::string* error) {
  const uint32_t V = m.meta.vertex_count, F = m.meta.frame_count;
  if (V == 0) return fail(error, "vertex count is zero");
  if (F == 0) return fail(error, "frame count is zero");
  if (!finite_positive(m.meta.diag)) return fail(error, "rest-pose diagonal is not a positive number");
  if (!finite_positive(m.meta.tolerance)) return fail(error, "tolerance is not a positive number");
  if (!std::isfinite(m.meta.frame_rate) || m.meta.frame_rate < 0) return fail(error, "frame rate is invalid");
  if (uint8_t(m.meta.inbetween) >= kInbetweenCount) return fail(error, "unknown in-between rule");
  const bool has_residual = m.residual.step != 0.0 || !m.residual.payload.empty();
  if (has_residual) {
    uint64_t values = uint64_t(V) * F * 3;
    uint64_t budget = std::max<uint64_t>(kMaxValuesFloor, kMaxValuesPerPayloadByte * m.residual.coded_bytes());
    if (values > budget) return fail(error, "vertex and frame counts are implausible for the residual size");
  } else if (m.segments.empty()) {
    return fail(error, "file has neither a residual layer nor time segments: nothing to evaluate");
  }

  if (m.faces.size() % 3 != 0) return fail(error, "face list is not made of triangles");
  for (uint32_t idx : m.faces)
    if (idx >= V) return fail(error, "face index out of range");

  const Curves& c = m.curves;
  if (c.offsets.empty() || c.offsets.front() != 0 || c.offsets.back() != V || c.vertices.size() != V ||
      c.u.size() != V || c.closed.size() != c.curve_count())
    return fail(error, "curves do not cover every vertex exactly once");
  std::vector<uint8_t> seen(V, 0);
  for (uint32_t v : c.vertices) {
    if (v >= V || seen[v]) return fail(error, "curves do not cover every vertex exactly once");
    seen[v] = 1;
  }
  for (uint32_t k = 0; k < c.curve_count(); ++k) {
    if (c.offsets[k + 1] <= c.offsets[k]) return fail(error, "empty curve");
    for (uint32_t i = c.offsets[k]; i < c.offsets[k + 1]; ++i) {
      if (!(c.u[i] >= 0.f && c.u[i] <= 1.f)) return fail(error, "curve parameter u outside [0,1]");
      if (i > c.offsets[k] && c.u[i] < c.u[i - 1]) return fail(error, "curve parameter u decreases along a curve");
    }
  }

  uint32_t expect_first = 0;
  for (const Segment& s : m.segments) {
    if (s.first_frame != expect_first || s.last_frame < s.first_frame || s.last_frame >= F)
      return fail(error, "time segments do not tile the frame range");
    expect_first = s.last_frame;
    if (s.mode == FitMode::Displacement && !has_residual)
      return fail(error, "displacement segment needs the residual layer for its rest pose");
    if (s.motion.size() != size_t(c.curve_count()) * 3) return fail(error, "segment motion count mismatch");
    for (const CurveMotion& cm : s.motion) {
      if (cm.basis == Basis::Zero) continue;
      if (cm.coeffs.size() != size_t(basis_term_count(cm.basis))) return fail(error, "coefficient count mismatch");
      if ((cm.basis == Basis::Pde8 && cm.basis_case > 3) || (cm.basis == Basis::Pde32 && cm.basis_case != 0))
        return fail(error, "basis case out of range");
      if (!(std::isfinite(cm.time_param) && cm.time_param >= 0 && cm.time_param <= kBasisMaxParam &&
            std::isfinite(cm.space_param) && cm.space_param >= 0 && cm.space_param <= kBasisMaxParam))
        return fail(error, "basis parameter out of range");
      if (cm.coeff_exponent < kCoeffExponentMin || cm.coeff_exponent > kCoeffExponentMax)
        return fail(error, "coefficient exponent out of range");
      for (float v : cm.coeffs) {
        const double k = std::ldexp(double(v), -cm.coeff_exponent);
        if (!(std::isfinite(v) && k == std::round(k) && std::fabs(k) < std::ldexp(1.0, kCoeffIntegerBits)))
          return fail(error, "coefficient is not an integer multiple of 2^exponent below 2^24 of them");
      }
    }
  }
  if (!m.segments.empty() && m.segments.back().last_frame != (F > 1 ? F - 1 : 0))
    return fail(error, "time segments do not reach the last frame");

  const LowRankModel& lr = m.low_rank;
  if (lr.components > 0) {
    if (!has_residual) return fail(error, "low-rank model without a residual layer");
    for (const Segment& s : m.segments)
      for (const CurveMotion& cm : s.motion)
        if (cm.basis != Basis::Zero) return fail(error, "file has both a low-rank model and PDE motions");
    if (lr.components > kMaxLowRankComponents || lr.shift > kMaxLowRankShift || lr.mean_shift > lr.shift ||
        lr.coeffs.size() != size_t(F) * lr.components)
      return fail(error, "low-rank model fields out of range");
    for (int32_t c : lr.coeffs)
      if (c < -kMaxLowRankCoeff || c > kMaxLowRankCoeff) return fail(error, "low-rank coefficient out of range");
    if (!lr.coeff_shifts.empty()) {
      if (lr.coeff_shifts.size() != lr.components) return fail(error, "low-rank coefficient shift count mismatch");
      for (size_t i = 0; i < lr.coeffs.size(); ++i) {
        const uint32_t s = lr.coeff_shifts[i % lr.components];
        if (s > lr.shift || lr.coeffs[i] % (int32_t(1) << s) != 0)
          return fail(error, "low-rank coefficient is not a multiple of its component's shift");
      }
    }
    if (!lr.poses.empty()) {
      if (lr.poses.size() != size_t(F) * kLowRankPoseValues) return fail(error, "low-rank pose count mismatch");
      for (size_t i = 0; i < lr.poses.size(); ++i)
        if (!low_rank_pose_value_ok(i, lr.poses[i])) return fail(error, "low-rank pose value out of range");
      for (int32_t c : lr.pose_centre)
        if (!low_rank_pose_centre_ok(c)) return fail(error, "low-rank pose centre out of range");
    }
    const uint64_t values = (uint64_t(lr.components) + 1) * V * 3;
    if (values > std::max<uint64_t>(kMaxValuesFloor, kMaxValuesPerPayloadByte * lr.basis_payload.size()))
      return fail(error, "vertex count and rank are implausible for the low-rank basis size");
  }

  if (has_residual) {
    if (!finite_positive(m.residual.step)) return fail(error, "residual grid step is not a positive number");
    for (double o : m.residual.origin)
      if (!std::isfinite(o)) return fail(error, "residual grid origin is not finite");
    // Chunks decode when a frame needs them: every int32 grid value must map to a finite
    // binary32 position, so no chunk can make the output overflow.
    for (double o : m.residual.origin)
      if (std::fabs(o) + m.residual.step * 2147483648.0 > double(std::numeric_limits<float>::max()))
        return fail(error, "residual grid would place grid values outside the float range");
  }
  if (!m.materials.empty() && m.render.empty()) return fail(error, "materials without render vertices");
  return validate_render(m, error) && validate_placement(m.placement, error);
}

}  // namespace dcurve
