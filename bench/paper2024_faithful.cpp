#include "bench/paper2024_faithful.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "bench/paper_splines.h"
#include "codec/common/basis.h"
#include "codec/common/error.h"

namespace dcurve {
namespace {

constexpr uint32_t kFrames = 11;   // frames 0..10, tau = n / 10
constexpr int kControlPoints = 50;
constexpr int kTimeTerms = 4, kSpaceTerms = 8, kTerms = kTimeTerms * kSpaceTerms;
// Six fitted samples 0.2 apart: above pi / (2 * 0.2) the time functions alias between them.
const double kMaxAlpha = std::acos(-1.0) / (2 * 0.2);
// The former cap, where issue 39 found the least-squares choice aliasing: the range the
// leave-one-out choice is shown on.
constexpr double kMaxAlphaWide = 30.0;

int longest_axis(const std::vector<float>& xyz) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], double(xyz[i]));
    hi[i % 3] = std::max(hi[i % 3], double(xyz[i]));
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
  return axis;
}

// One curve at frames 0..10, aligned to frame 0 (eqs. 19-23), with u per frame (eq. 24).
struct AlignedCurve {
  size_t points = 0;
  Eigen::MatrixXd xyz[kFrames];  // points x 3
  std::vector<double> u[kFrames];
};

AlignedCurve align_curve(const Animation& anim, const Curves& curves, uint32_t c, int axis) {
  AlignedCurve ac;
  const uint32_t begin = curves.offsets[c], end = curves.offsets[c + 1];
  ac.points = end - begin;
  Eigen::MatrixXd raw[kFrames];
  for (uint32_t n = 0; n < kFrames; ++n) {
    raw[n].resize(Eigen::Index(ac.points), 3);
    for (uint32_t k = begin; k < end; ++k)
      for (int a = 0; a < 3; ++a) raw[n](k - begin, a) = anim.frames[n][size_t(curves.vertices[k]) * 3 + size_t(a)];
  }
  for (uint32_t n = 0; n < kFrames; ++n) {
    // eq. 19: the first point moved onto frame 0's; eqs. 20-23: the 3 x 3 map (not constrained
    // to a rotation) that brings the shifted curve closest to frame 0's.
    Eigen::MatrixXd shifted = raw[n];
    shifted.rowwise() -= raw[n].row(0) - raw[0].row(0);
    const Eigen::Matrix3d map = shifted.colPivHouseholderQr().solve(raw[0]);
    ac.xyz[n] = n == 0 ? raw[0] : Eigen::MatrixXd(shifted * map);
    // eq. 24: u from the coordinate along the line, normalized per frame.
    const double lo = ac.xyz[n].col(axis).minCoeff(), hi = ac.xyz[n].col(axis).maxCoeff();
    for (size_t k = 0; k < ac.points; ++k)
      ac.u[n].push_back(hi > lo ? std::clamp((ac.xyz[n](Eigen::Index(k), axis) - lo) / (hi - lo), 0.0, 1.0) : 0.0);
  }
  return ac;
}

// The 32 products T_i(tau_n) U_j(u_nk) of eq. 17, a row per point of each frame listed.
Eigen::MatrixXd pde_design(const AlignedCurve& ac, const std::vector<uint32_t>& frames, double alpha, double r) {
  Eigen::MatrixXd a(Eigen::Index(frames.size() * ac.points), kTerms);
  Eigen::Index row = 0;
  for (uint32_t n : frames) {
    double t[kTimeTerms];
    basis_time(Basis::Pde32, 0, alpha, n / 10.0, t);
    for (size_t k = 0; k < ac.points; ++k, ++row) {
      double s[kSpaceTerms];
      basis_space(Basis::Pde32, 0, r, ac.u[n][k], s);
      for (int i = 0; i < kTimeTerms; ++i)
        for (int j = 0; j < kSpaceTerms; ++j) a(row, i * kSpaceTerms + j) = t[i] * s[j];
    }
  }
  return a;
}

Eigen::MatrixXd stacked(const AlignedCurve& ac, const std::vector<uint32_t>& frames) {
  Eigen::MatrixXd y(Eigen::Index(frames.size() * ac.points), 3);
  for (size_t f = 0; f < frames.size(); ++f) y.middleRows(Eigen::Index(f * ac.points), Eigen::Index(ac.points)) = ac.xyz[frames[f]];
  return y;
}

struct PdeFit {
  double alpha = 0, r = 0, sse = 1e300;
  Eigen::MatrixXd coeffs;  // 32 x 3
};

// How (alpha, r) is chosen: the grid reaches max_alpha; with leave_out each alpha keeps its
// best-fitting r and the alpha whose fit best predicts each fitted frame from the others
// wins, else the pair with the smallest squared error at the fitted frames.
struct PdeSearch {
  double max_alpha = kMaxAlpha;
  bool leave_out = false;
};

// eq. 25 at one (alpha, r) on the listed frames.
PdeFit solve_pde(const AlignedCurve& ac, const std::vector<uint32_t>& frames, double alpha, double r) {
  const Eigen::MatrixXd y = stacked(ac, frames);
  const Eigen::MatrixXd a = pde_design(ac, frames, alpha, r);
  // Column scaling: near p = 0 the functions span many magnitudes.
  Eigen::VectorXd scale = a.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < scale.size(); ++j) scale(j) = scale(j) > 0 ? 1.0 / scale(j) : 1.0;
  const Eigen::MatrixXd scaled = a * scale.asDiagonal();
  PdeFit fit{alpha, r, 0, scale.asDiagonal() * scaled.colPivHouseholderQr().solve(y)};
  fit.sse = (a * fit.coeffs - y).squaredNorm();
  return fit;
}

// Squared error at each fitted frame of the fit of the other fitted frames (the end frames
// too, as encoder/fit/param_search.h's leave_out_error2).
double leave_out_sse(const AlignedCurve& ac, const std::vector<uint32_t>& fitted, double alpha, double r) {
  double sum = 0;
  for (size_t k = 0; k < fitted.size(); ++k) {
    std::vector<uint32_t> others = fitted;
    others.erase(others.begin() + std::ptrdiff_t(k));
    const PdeFit fit = solve_pde(ac, others, alpha, r);
    sum += (pde_design(ac, {fitted[k]}, alpha, r) * fit.coeffs - ac.xyz[fitted[k]]).squaredNorm();
  }
  return sum;
}

PdeFit fit_pde(const AlignedCurve& ac, const std::vector<uint32_t>& fitted, const PdeSearch& search) {
  std::vector<double> alphas = {0.0}, rs = {0.0};
  for (int k = 0; k < 8; ++k) alphas.push_back(0.25 * std::pow(search.max_alpha / 0.25, k / 7.0));
  for (int k = 0; k < 12; ++k) rs.push_back(0.25 * std::pow(40.0 / 0.25, k / 11.0));
  PdeFit best;
  double best_score = 1e300;
  for (double alpha : alphas) {
    PdeFit at_alpha;
    for (double r : rs) {
      PdeFit fit = solve_pde(ac, fitted, alpha, r);
      if (fit.sse < at_alpha.sse) at_alpha = std::move(fit);
    }
    const double score = search.leave_out ? leave_out_sse(ac, fitted, alpha, at_alpha.r) : at_alpha.sse;
    if (score < best_score) {
      best_score = score;
      best = std::move(at_alpha);
    }
  }
  return best;
}

// Errors of one frame, over the curves: eq. 26 (mean point distance / D) averaged, eq. 27
// (max point distance / D) maximized.
struct FrameErrors {
  double ea_sum = 0, em = 0;
  size_t curves = 0;
  void add(const Eigen::MatrixXd& truth, const Eigen::MatrixXd& predicted, double d) {
    const Eigen::VectorXd dist = (truth - predicted).rowwise().norm();
    ea_sum += dist.mean() / d;
    em = std::max(em, dist.maxCoeff() / d);
    ++curves;
  }
  double ea() const { return curves ? ea_sum / double(curves) : 0.0; }
};

struct Summary {
  double mean_ea = 0, max_em = 0;
};

Summary summarize(const std::vector<FrameErrors>& fe, int parity) {  // parity: -1 all, 0 even, 1 odd
  Summary s;
  int count = 0;
  for (uint32_t n = 0; n < kFrames; ++n) {
    if (parity >= 0 && int(n % 2) != parity) continue;
    s.mean_ea += fe[n].ea();
    s.max_em = std::max(s.max_em, fe[n].em);
    ++count;
  }
  s.mean_ea /= count;
  return s;
}

double furthest_pair(const Eigen::MatrixXd& xyz) {
  double best = 0;
  for (Eigen::Index i = 0; i < xyz.rows(); ++i)
    for (Eigen::Index j = i + 1; j < xyz.rows(); ++j) best = std::max(best, (xyz.row(i) - xyz.row(j)).norm());
  return best;
}

Eigen::MatrixXd as_matrix(const std::vector<double>& xyz) {
  Eigen::MatrixXd m(Eigen::Index(xyz.size() / 3), 3);
  for (size_t p = 0; p < xyz.size() / 3; ++p)
    for (int a = 0; a < 3; ++a) m(Eigen::Index(p), a) = xyz[p * 3 + size_t(a)];
  return m;
}

std::vector<double> as_vector(const Eigen::MatrixXd& m) {
  std::vector<double> v(size_t(m.rows()) * 3);
  for (Eigen::Index p = 0; p < m.rows(); ++p)
    for (int a = 0; a < 3; ++a) v[size_t(p) * 3 + size_t(a)] = m(p, a);
  return v;
}

// The B-spline baseline at frame n: its own fit on even frames, the average of the two
// neighbours' control points on odd ones, evaluated at frame n's u.
Eigen::MatrixXd spline_at(const AlignedCurve& ac, const std::vector<std::vector<double>>& controls, uint32_t n) {
  std::vector<double> c = controls[n % 2 ? n - 1 : n];
  if (n % 2)
    for (size_t k = 0; k < c.size(); ++k) c[k] = 0.5 * (c[k] + controls[n + 1][k]);
  std::vector<double> xyz;
  evaluate_bspline(c, ac.u[n], &xyz);
  return as_matrix(xyz);
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

nlohmann::json summary_json(const std::vector<FrameErrors>& fe) {
  nlohmann::json j;
  for (auto [name, parity] : {std::pair<const char*, int>{"all", -1}, {"fitted", 0}, {"odd", 1}}) {
    const Summary s = summarize(fe, parity);
    j[name] = {{"mean_EA", s.mean_ea}, {"max_EM", s.max_em}};
  }
  return j;
}

std::string table_text(const std::vector<FrameErrors>& pde, const std::vector<FrameErrors>& spline) {
  std::string t = " frame  fitted   PDE E_An    PDE E_Mn    Bspl E_An   Bspl E_Mn\n";
  for (uint32_t n = 0; n < kFrames; ++n)
    t += fmt("%6.0f", n) + (n % 2 ? "   no  " : "   yes ") + fmt("%11.6f", pde[n].ea()) + fmt(" %11.6f", pde[n].em) +
         fmt(" %11.6f", spline[n].ea()) + fmt(" %11.6f", spline[n].em) + "\n";
  for (auto [name, parity] : {std::pair<const char*, int>{"frames 0-10 ", -1}, {"odd frames  ", 1}, {"fitted frames", 0}}) {
    const Summary p = summarize(pde, parity), b = summarize(spline, parity);
    t += std::string(" ") + name + ": PDE mean E_An " + fmt("%.6f", p.mean_ea) + ", max E_Mn " + fmt("%.6f", p.max_em) +
         " | B-spline " + fmt("%.6f", b.mean_ea) + ", " + fmt("%.6f", b.max_em) + " | ratio B-spline/PDE " +
         fmt("%.2f", b.mean_ea / std::max(p.mean_ea, 1e-300)) + ", " + fmt("%.2f", b.max_em / std::max(p.max_em, 1e-300)) +
         "\n";
  }
  return t;
}

}  // namespace

bool surface_lines(const Animation& anim, Curves* lines, std::string* error) {
  const std::vector<float>& rest = anim.frames[0];
  const int axis = longest_axis(rest);
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t i = 0; i < rest.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], double(rest[i]));
    hi[i % 3] = std::max(hi[i % 3], double(rest[i]));
  }
  const double L = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                             (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const double cell = std::max(L * 1e-6, 1e-30);
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  std::map<std::pair<long long, long long>, std::vector<uint32_t>> groups;
  for (uint32_t v = 0; v < anim.vertex_count; ++v)
    groups[{std::llround(rest[size_t(v) * 3 + size_t(a1)] / cell), std::llround(rest[size_t(v) * 3 + size_t(a2)] / cell)}]
        .push_back(v);
  *lines = Curves();
  for (auto& [key, ids] : groups) {
    if (ids.size() < kFrames) continue;
    std::sort(ids.begin(), ids.end(), [&](uint32_t a, uint32_t b) {
      return rest[size_t(a) * 3 + size_t(axis)] < rest[size_t(b) * 3 + size_t(axis)];
    });
    lines->offsets.push_back(uint32_t(lines->vertices.size()));
    lines->closed.push_back(0);
    const double first = rest[size_t(ids.front()) * 3 + size_t(axis)], last = rest[size_t(ids.back()) * 3 + size_t(axis)];
    for (uint32_t v : ids) {
      lines->vertices.push_back(v);
      lines->u.push_back(last > first ? float((rest[size_t(v) * 3 + size_t(axis)] - first) / (last - first)) : 0.f);
    }
  }
  if (lines->vertices.empty()) return fail(error, "no line of 11 or more vertices along the longest axis");
  lines->offsets.push_back(uint32_t(lines->vertices.size()));
  return true;
}

namespace {

// The PDE fits of every curve under one parameter search, and their errors per frame.
struct PdeRun {
  PdeSearch search;
  std::vector<FrameErrors> frames = std::vector<FrameErrors>(kFrames);
  std::vector<double> alphas, rs;
};

PdeRun run_pde(const std::vector<AlignedCurve>& curves, const std::vector<uint32_t>& fitted, const PdeSearch& search,
               double d) {
  PdeRun run;
  run.search = search;
  for (const AlignedCurve& ac : curves) {
    const PdeFit fit = fit_pde(ac, fitted, search);
    run.alphas.push_back(fit.alpha);
    run.rs.push_back(fit.r);
    for (uint32_t n = 0; n < kFrames; ++n) run.frames[n].add(ac.xyz[n], pde_design(ac, {n}, fit.alpha, fit.r) * fit.coeffs, d);
  }
  return run;
}

nlohmann::json range_json(const std::vector<double>& v) {
  return {{"min", *std::min_element(v.begin(), v.end())}, {"median", median(v)}, {"max", *std::max_element(v.begin(), v.end())}};
}

std::string search_name(const PdeSearch& s) {
  return std::string(s.leave_out ? "alpha by leave-one-out" : "alpha by least squares") + ", alpha <= " +
         fmt("%.3f", s.max_alpha);
}

// One line per alternative search: its alpha and its odd-frame errors.
std::string search_line(const PdeRun& run) {
  const Summary odd = summarize(run.frames, 1), all = summarize(run.frames, -1);
  return " " + search_name(run.search) + ": alpha median " + fmt("%.3f", median(run.alphas)) + " (" +
         fmt("%.3f", *std::min_element(run.alphas.begin(), run.alphas.end())) + " - " +
         fmt("%.3f", *std::max_element(run.alphas.begin(), run.alphas.end())) + "), odd frames mean E_An " +
         fmt("%.6f", odd.mean_ea) + ", max E_Mn " + fmt("%.6f", odd.max_em) + "; frames 0-10 " +
         fmt("%.6f", all.mean_ea) + " / " + fmt("%.6f", all.max_em) + "\n";
}

}  // namespace

bool run_paper2024_faithful(const Animation& anim, const Curves& curves, nlohmann::json* result, std::string* table,
                            std::string* error, bool alpha_searches) {
  if (anim.frames.size() < kFrames) return fail(error, "paper2024 needs at least 11 frames");
  const uint32_t C = curves.curve_count();
  const int axis = longest_axis(anim.frames[0]);
  const std::vector<uint32_t> fitted = {0, 2, 4, 6, 8, 10};
  std::vector<AlignedCurve> aligned;
  for (uint32_t c = 0; c < C; ++c) {
    AlignedCurve ac = align_curve(anim, curves, c, axis);
    if (ac.points >= 2) aligned.push_back(std::move(ac));
  }
  if (aligned.empty()) return fail(error, "no curve of 2 or more points");
  const double d = furthest_pair(aligned[0].xyz[0]);  // the paper's D: its first curve's
  if (!(d > 0)) return fail(error, "the first curve has no extent");
  std::vector<FrameErrors> spline(kFrames);
  size_t points = 0;
  for (const AlignedCurve& ac : aligned) {
    points += ac.points;
    std::vector<std::vector<double>> controls(kFrames);
    for (uint32_t n : fitted) fit_bspline_controls(ac.u[n], as_vector(ac.xyz[n]).data(), kControlPoints, &controls[n]);
    for (uint32_t n = 0; n < kFrames; ++n) spline[n].add(ac.xyz[n], spline_at(ac, controls, n), d);
  }
  // The main table: alpha capped; beside it the former search (least squares up to 30, the
  // cap issue 39 found aliasing) and the leave-one-out choice over the same range.
  const PdeRun capped = run_pde(aligned, fitted, PdeSearch{}, d);
  std::vector<PdeRun> others;
  if (alpha_searches) {
    for (bool leave_out : {false, true}) others.push_back(run_pde(aligned, fitted, PdeSearch{kMaxAlphaWide, leave_out}, d));
    others.push_back(run_pde(aligned, fitted, PdeSearch{kMaxAlpha, true}, d));
  }
  const std::vector<FrameErrors>& pde = capped.frames;
  nlohmann::json j;
  j["protocol"] = "paper2024_faithful";
  j["curves"] = C;
  j["mean_points_per_curve"] = double(points) / double(aligned.size());
  j["D"] = d;
  j["alpha_cap"] = kMaxAlpha;
  j["alpha"] = range_json(capped.alphas);
  j["r"] = range_json(capped.rs);
  j["pde"] = summary_json(pde);
  j["bspline"] = summary_json(spline);
  nlohmann::json searches = nlohmann::json::array();
  std::string search_text;
  for (const PdeRun& run : others) {
    searches.push_back({{"max_alpha", run.search.max_alpha}, {"leave_out", run.search.leave_out},
                        {"alpha", range_json(run.alphas)}, {"pde", summary_json(run.frames)}});
    search_text += search_line(run);
  }
  j["pde_other_searches"] = searches;
  nlohmann::json rows = nlohmann::json::array();
  for (uint32_t n = 0; n < kFrames; ++n)
    rows.push_back({{"frame", n}, {"pde_EA", pde[n].ea()}, {"pde_EM", pde[n].em}, {"bspline_EA", spline[n].ea()},
                    {"bspline_EM", spline[n].em}});
  j["per_frame"] = rows;
  j["paper_rope"] = {{"pde", {{"mean_EA", 0.006986}, {"max_EM", 0.019478}}},
                     {"bspline", {{"mean_EA", 0.046644}, {"max_EM", 0.270942}}}};
  *result = j;
  if (table)
    *table = "paper2024, as the paper describes it: " + std::to_string(aligned.size()) + " full-length curves of " +
             fmt("%.0f", double(points) / double(aligned.size())) +
             " points, every frame aligned to frame 0 by a 3x3 map, u per frame (eq. 24), D = " + fmt("%.4g", d) +
             "\n" + search_line(capped) + table_text(pde, spline) +
             " (paper's Table 1, cube-rope: PDE 0.006986 / 0.019478, B-spline 0.046644 / 0.270942)\n" +
             (others.empty() ? "" : " the same PDE fit with other alpha searches:\n" + search_text);
  return true;
}

}  // namespace dcurve
