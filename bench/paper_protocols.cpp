#include "bench/paper_protocols.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "bench/paper_splines.h"
#include "codec/common/error.h"
#include "encoder/fit/curve_frames.h"
#include "encoder/fit/fit.h"

namespace dcurve {
namespace {

using Clock = std::chrono::steady_clock;

// Six fitted samples 0.2 apart: above pi / (2 * 0.2) e^{-alpha t} is nearly an indicator of
// frame 0 and sin / cos alias between the samples (issue 39 measured odd-frame errors 4-25x
// worse with the former cap of 30).
const double kMaxTime2024 = std::acos(-1.0) / (2 * 0.2);
// The former cap: the range on which the leave-one-out choice is shown beside the cap.
constexpr double kMaxTimeWide = 30.0;

// How the time parameter is searched (FitOptions::max_time_param, time_param_by_leave_out).
struct TimeSearch {
  double max = kMaxTime2024;
  bool leave_out = false;
};

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double distance(const double* a, const double* b) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) d2 += (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(d2);
}

// The distance between a curve's two furthest points (2024 paper's D).
double furthest_pair(const double* xyz, size_t points) {
  double best = 0;
  for (size_t i = 0; i < points; ++i)
    for (size_t j = i + 1; j < points; ++j) best = std::max(best, distance(xyz + i * 3, xyz + j * 3));
  return best;
}

struct FrameError {
  double ea = 0, em = 0;  // mean over curves of the mean ratio; max over curves of the max ratio
  size_t curves = 0;
};

// Adds one curve's errors at one frame to the frame's 2024 figures.
void add_2024(const double* truth, const double* fitted, size_t points, FrameError* fe) {
  double d = furthest_pair(truth, points);
  if (!(d > 0)) return;  // a single point or a collapsed curve has no scale
  double sum = 0, worst = 0;
  for (size_t p = 0; p < points; ++p) {
    double e = distance(truth + p * 3, fitted + p * 3) / d;
    sum += e;
    worst = std::max(worst, e);
  }
  fe->ea += sum / double(points);
  fe->em = std::max(fe->em, worst);
  fe->curves++;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// Fits the even frames with one PDE variant and measures every frame 0..10.
// params (may be null): the chosen time and space parameters of every curve and axis.
bool pde_errors_2024(const std::vector<CurveFrames>& truth, const std::vector<CurveFrames>& fit_input,
                     const std::vector<double>& tau_all, Basis basis, bool rigid, std::vector<FrameError>* errors,
                     double* fit_ms, std::string* error, std::vector<std::pair<double, double>>* params = nullptr,
                     TimeSearch search = TimeSearch()) {
  FitOptions options;
  options.basis = basis;
  options.remove_rigid = rigid;
  options.max_time_param = search.max;
  options.time_param_by_leave_out = search.leave_out;
  std::vector<CurveFit> fits;
  Clock::time_point start = Clock::now();
  if (!fit_curves(fit_input, options, 0, &fits, error)) return false;
  *fit_ms = ms_since(start);
  if (params)
    for (const CurveFit& f : fits)
      for (const AxisFit& a : f.axis) params->emplace_back(a.motion.time_param, a.motion.space_param);
  errors->assign(tau_all.size(), FrameError());
  std::vector<double> predicted;
  for (size_t c = 0; c < truth.size(); ++c) {
    const CurveFrames& t = truth[c];
    const size_t P = t.points();
    predicted.resize(P * 3);
    for (size_t n = 0; n < tau_all.size(); ++n) {
      evaluate_curve_fit(fits[c], t.u, {}, tau_all[n], predicted.data());
      add_2024(t.xyz.data() + n * P * 3, predicted.data(), P, &(*errors)[n]);
    }
  }
  return true;
}

bool run_2024(const Animation& anim, const Curves& curves, nlohmann::json* result, std::string* table,
              std::string* error, bool alpha_searches) {
  const uint32_t kFrames = 11;
  if (anim.frames.size() < kFrames) {
    *error = "paper2024 needs at least 11 frames, the animation has " + std::to_string(anim.frames.size());
    return false;
  }
  std::vector<uint32_t> all, even;
  std::vector<double> tau_all, tau_even;
  for (uint32_t n = 0; n < kFrames; ++n) {
    all.push_back(n);
    tau_all.push_back(n / 10.0);
    if (n % 2 == 0) {
      even.push_back(n);
      tau_even.push_back(n / 10.0);
    }
  }
  const uint32_t C = curves.curve_count();
  std::vector<CurveFrames> truth(C), fit_input(C);
  for (uint32_t c = 0; c < C; ++c) {
    truth[c] = gather_curve_frames(anim, curves, c, all, tau_all);
    fit_input[c] = gather_curve_frames(anim, curves, c, even, tau_even);
  }
  std::vector<FrameError> pde(kFrames), spline(kFrames);
  double pde_ms = 0;
  std::vector<std::pair<double, double>> params;
  if (!pde_errors_2024(truth, fit_input, tau_all, Basis::Pde32, true, &pde, &pde_ms, error, &params)) return false;
  std::vector<double> alphas, rs;
  for (auto [alpha, r] : params) {
    alphas.push_back(alpha);
    rs.push_back(r);
  }
  std::sort(alphas.begin(), alphas.end());
  std::sort(rs.begin(), rs.end());
  std::vector<double> splined, left, right;
  for (uint32_t c = 0; c < C; ++c) {
    const CurveFrames& t = truth[c];
    const size_t P = t.points();
    for (uint32_t n = 0; n < kFrames; ++n) {
      const double* truth_n = t.xyz.data() + size_t(n) * P * 3;
      if (n % 2 == 0) {
        fit_bspline(t.u, truth_n, 50, &splined);
      } else {  // linear interpolation between the neighbouring fitted frames
        fit_bspline(t.u, truth_n - P * 3, 50, &left);
        fit_bspline(t.u, truth_n + P * 3, 50, &right);
        splined.resize(P * 3);
        for (size_t k = 0; k < P * 3; ++k) splined[k] = 0.5 * (left[k] + right[k]);
      }
      add_2024(truth_n, splined.data(), P, &spline[n]);
    }
  }

  auto summarize = [&](const std::vector<FrameError>& fe, bool odd_only) {
    double sum = 0, worst = 0;
    int count = 0;
    for (uint32_t n = 0; n < kFrames; ++n) {
      if (odd_only && n % 2 == 0) continue;
      double ea = fe[n].curves ? fe[n].ea / double(fe[n].curves) : 0.0;
      sum += ea;
      worst = std::max(worst, fe[n].em);
      ++count;
    }
    return std::make_pair(sum / count, worst);
  };
  auto [pde_ea, pde_em] = summarize(pde, false);
  auto [bs_ea, bs_em] = summarize(spline, false);
  auto [pde_ea_odd, pde_em_odd] = summarize(pde, true);
  auto [bs_ea_odd, bs_em_odd] = summarize(spline, true);

  nlohmann::json j;
  j["protocol"] = "paper2024";
  j["curves"] = C;
  j["frames_fitted"] = even;
  j["frames_predicted"] = {1, 3, 5, 7, 9};
  j["pde"] = {{"mean_EA", pde_ea}, {"max_EM", pde_em}, {"mean_EA_predicted", pde_ea_odd},
              {"max_EM_predicted", pde_em_odd}, {"basis", "pde32"}, {"rigid_removal", true},
              {"design_variables", size_t(C) * 32 * 3}, {"fit_ms", pde_ms},
              {"alpha", {{"min", alphas.front()}, {"median", alphas[alphas.size() / 2]}, {"max", alphas.back()}}},
              {"r", {{"min", rs.front()}, {"median", rs[rs.size() / 2]}, {"max", rs.back()}}},
              {"alpha_cap", kMaxTime2024}};
  j["bspline"] = {{"mean_EA", bs_ea}, {"max_EM", bs_em}, {"mean_EA_predicted", bs_ea_odd},
                  {"max_EM_predicted", bs_em_odd}, {"control_points", 50}};
  // A PDE error of exactly zero leaves the ratio undefined: JSON null, table "inf".
  auto ratio = [](double num, double den) { return den > 0 ? nlohmann::json(num / den) : nlohmann::json(); };
  j["ratio_bspline_over_pde"] = {{"mean_EA", ratio(bs_ea, pde_ea)}, {"max_EM", ratio(bs_em, pde_em)}};
  // The same protocol with the other PDE choices, to show what rigid removal and the basis size do.
  nlohmann::json variants = nlohmann::json::array();
  std::string vt;
  for (auto [basis, rigid] : {std::pair<Basis, bool>{Basis::Pde32, false}, {Basis::Pde8, true}, {Basis::Pde8, false}}) {
    std::vector<FrameError> fe;
    double ms = 0;
    if (!pde_errors_2024(truth, fit_input, tau_all, basis, rigid, &fe, &ms, error)) return false;
    auto [ea, em] = summarize(fe, false);
    const char* name = basis == Basis::Pde32 ? "pde32" : "pde8";
    variants.push_back({{"basis", name}, {"rigid_removal", rigid}, {"mean_EA", ea}, {"max_EM", em}, {"fit_ms", ms}});
    vt += std::string(" variant ") + name + (rigid ? " + rigid   " : " absolute  ") + ": mean E_An " + fmt("%.6f", ea) +
          ", max E_Mn " + fmt("%.6f", em) + "\n";
  }
  j["pde_variants"] = variants;
  // pde32 + rigid with other time-parameter searches: their alpha and odd-frame errors.
  nlohmann::json searches = nlohmann::json::array();
  std::vector<TimeSearch> other_searches;
  if (alpha_searches) other_searches = {{kMaxTimeWide, false}, {kMaxTimeWide, true}, {kMaxTime2024, true}};
  for (TimeSearch ts : other_searches) {
    std::vector<FrameError> fe;
    std::vector<std::pair<double, double>> ps;
    double ms = 0;
    if (!pde_errors_2024(truth, fit_input, tau_all, Basis::Pde32, true, &fe, &ms, error, &ps, ts)) return false;
    std::vector<double> as;
    for (auto [alpha, r] : ps) as.push_back(alpha);
    std::sort(as.begin(), as.end());
    auto [ea, em] = summarize(fe, true);
    searches.push_back({{"max_alpha", ts.max}, {"leave_out", ts.leave_out}, {"alpha_median", as[as.size() / 2]},
                        {"mean_EA_predicted", ea}, {"max_EM_predicted", em}, {"fit_ms", ms}});
    vt += std::string(" pde32 + rigid, alpha by ") + (ts.leave_out ? "leave-one-out" : "least squares") + " <= " +
          fmt("%.3f", ts.max) + ": alpha median " + fmt("%.3f", as[as.size() / 2]) + " (" + fmt("%.3f", as.front()) +
          " - " + fmt("%.3f", as.back()) + "), predicted frames mean E_An " + fmt("%.6f", ea) + ", max E_Mn " +
          fmt("%.6f", em) + "\n";
  }
  j["pde_other_searches"] = searches;
  j["paper_rope"] = {{"pde", {{"mean_EA", 0.006986}, {"max_EM", 0.019478}}},
                     {"bspline", {{"mean_EA", 0.046644}, {"max_EM", 0.270942}}}};
  nlohmann::json rows = nlohmann::json::array();
  std::string t = "paper2024: fit frames 0,2,..,10, predict 1,3,..,9 (" + std::to_string(C) + " curves)\n";
  t += " frame  fitted   PDE E_An    PDE E_Mn    Bspl E_An   Bspl E_Mn\n";
  for (uint32_t n = 0; n < kFrames; ++n) {
    double pe = pde[n].curves ? pde[n].ea / double(pde[n].curves) : 0.0;
    double be = spline[n].curves ? spline[n].ea / double(spline[n].curves) : 0.0;
    rows.push_back({{"frame", n}, {"pde_EA", pe}, {"pde_EM", pde[n].em}, {"bspline_EA", be}, {"bspline_EM", spline[n].em}});
    t += fmt("%6.0f", n) + (n % 2 ? "   no  " : "   yes ") + fmt("%11.6f", pe) + fmt(" %11.6f", pde[n].em) +
         fmt(" %11.6f", be) + fmt(" %11.6f", spline[n].em) + "\n";
  }
  j["per_frame"] = rows;
  t += " all frames: PDE mean E_An " + fmt("%.6f", pde_ea) + ", max E_Mn " + fmt("%.6f", pde_em) +
       " | B-spline mean E_An " + fmt("%.6f", bs_ea) + ", max E_Mn " + fmt("%.6f", bs_em) + "\n";
  t += " ratios B-spline / PDE: mean E_An " + fmt("%.2f", bs_ea / pde_ea) + ", max E_Mn " + fmt("%.2f", bs_em / pde_em) +
       "   (paper's rope: 6.68, 13.91)\n";
  t += " predicted frames only: PDE " + fmt("%.6f", pde_ea_odd) + " / " + fmt("%.6f", pde_em_odd) + ", B-spline " +
       fmt("%.6f", bs_ea_odd) + " / " + fmt("%.6f", bs_em_odd) + "; PDE fit " + fmt("%.1f", pde_ms) + " ms\n";
  t += " pde32 + rigid parameters per curve and axis: alpha median " + fmt("%.3f", alphas[alphas.size() / 2]) + " (" +
       fmt("%.3f", alphas.front()) + " - " + fmt("%.3f", alphas.back()) + ", cap " + fmt("%.3f", kMaxTime2024) +
       "), r median " + fmt("%.3f", rs[rs.size() / 2]) + " (" + fmt("%.3f", rs.front()) + " - " + fmt("%.3f", rs.back()) +
       ")\n";
  t += vt;
  *result = j;
  if (table) *table = t;
  return true;
}

// 2022 eq. (23) for one frame of one curve: mean and max of |error| / |original point|.
struct Ratio2022 {
  double sum = 0, worst = 0;
  size_t count = 0;
  void add(const double* truth, const double* fitted, size_t points) {
    double s = 0, w = 0;
    size_t n = 0;
    for (size_t p = 0; p < points; ++p) {
      double norm = std::sqrt(truth[p * 3] * truth[p * 3] + truth[p * 3 + 1] * truth[p * 3 + 1] +
                              truth[p * 3 + 2] * truth[p * 3 + 2]);
      if (!(norm > 0)) continue;  // the ratio is undefined at the origin
      double e = distance(truth + p * 3, fitted + p * 3) / norm;
      s += e;
      w = std::max(w, e);
      ++n;
    }
    if (n == 0) return;
    sum += s / double(n);
    worst = std::max(worst, w);
    ++count;
  }
  double mean() const { return count ? sum / double(count) : 0.0; }
};

// One method's eq. (23) errors at each keyframe of a pair and its fit time, over a set of
// curves (all, open or closed).
struct Method2022 {
  Ratio2022 key[2];
  double ms = 0;
  size_t curves = 0, points = 0;
  double ea12() const { return 0.5 * (key[0].mean() + key[1].mean()); }
  double em12() const { return std::max(key[0].worst, key[1].worst); }
};

enum { kPde2022, kBspline2022, kBezier2022, kMethods2022 };
const char* const kMethodNames2022[kMethods2022] = {"pde", "bspline", "bezier"};

// Fits one curve's two keyframes with each method and adds the errors and times to m.
bool fit_pair_2022(const CurveFrames& in, Method2022 m[kMethods2022], std::string* error) {
  const size_t P = in.points();
  FitOptions options;  // Pde8, every case searched
  CurveFit fit;
  Clock::time_point start = Clock::now();
  if (!fit_curve(in, options, &fit, error)) return false;
  m[kPde2022].ms += ms_since(start);
  std::vector<double> fitted[kMethods2022][2];
  start = Clock::now();
  for (size_t j = 0; j < 2; ++j) fit_bspline(in.u, in.xyz.data() + j * P * 3, 4, &fitted[kBspline2022][j]);
  m[kBspline2022].ms += ms_since(start);
  start = Clock::now();
  for (size_t j = 0; j < 2; ++j) fit_bezier(in.u, in.xyz.data() + j * P * 3, &fitted[kBezier2022][j]);
  m[kBezier2022].ms += ms_since(start);
  for (size_t j = 0; j < 2; ++j) {
    fitted[kPde2022][j].resize(P * 3);
    evaluate_curve_fit(fit, in.u, {}, in.tau[j], fitted[kPde2022][j].data());
  }
  for (int k = 0; k < kMethods2022; ++k) {
    for (size_t j = 0; j < 2; ++j) m[k].key[j].add(in.xyz.data() + j * P * 3, fitted[k][j].data(), P);
    m[k].curves++;
    m[k].points += 2 * P;
  }
  return true;
}

// The paper's rows (Tables 2 and 3: E_A1, E_A2, E_A12, E_m1, E_m2, E_m12 in the table's
// unit, CPU ms) and PM (points on both keyframes) for its open (OC) and closed (CC) curve,
// method order as kMethodNames2022.
struct PaperRow2022 {
  double pm, ea1, ea2, ea12, em1, em2, em12, ms;
};
const PaperRow2022 kPaperTable2[2][kMethods2022] = {
    {{140, 4.641821, 3.811424, 4.226623, 71.60692, 7.954821, 71.60692, 5.7532},
     {140, 4.631861, 3.813969, 4.222915, 79.84222, 7.796782, 79.84222, 3.3210},
     {140, 4.631861, 3.813969, 4.222915, 79.84222, 7.796782, 79.84222, 2.8257}},
    {{142, 4.624602, 3.810121, 4.217362, 71.00726, 7.620819, 71.00726, 5.8322},
     {142, 4.615302, 3.811597, 4.213450, 71.01385, 7.470214, 71.01385, 3.5928},
     {142, 4.615302, 3.811597, 4.213450, 71.01385, 7.470214, 71.01385, 2.9644}}};
const PaperRow2022 kPaperTable3[2][kMethods2022] = {
    {{132, 2.638812, 3.142145, 2.890479, 8.422275, 19.07610, 19.07610, 5.4184},
     {132, 2.172167, 2.181193, 2.176680, 80.48240, 80.82564, 80.48240, 3.0592},
     {132, 2.172167, 2.181193, 2.176680, 80.48240, 8.082564, 80.48240, 2.6934}},
    {{134, 2.632932, 3.169087, 2.901010, 8.077028, 18.39898, 18.39898, 5.4873},
     {134, 2.186633, 2.195735, 2.191184, 80.73569, 81.08065, 81.08065, 3.1072},
     {134, 2.186633, 2.195735, 2.191184, 80.73569, 81.08065, 81.08065, 2.8346}}};

nlohmann::json method_json(const Method2022& m) {
  return {{"mean_EA", m.ea12()},          {"max_EM", m.em12()},
          {"EA", {m.key[0].mean(), m.key[1].mean()}}, {"EM", {m.key[0].worst, m.key[1].worst}},
          {"fit_ms", m.ms},               {"fit_ms_per_curve", m.curves ? m.ms / double(m.curves) : 0.0},
          {"curves", m.curves},           {"design_variables_per_curve", 8}};
}

std::string row_text(const char* method, const char* kind, double pm, const double v[7], double unit) {
  std::string t = std::string(" ") + method + kind + fmt("%7.1f", pm) + "    8";
  for (int k = 0; k < 6; ++k) t += fmt(" %9.4f", v[k] * unit);
  return t + fmt(" %8.4f", v[6]) + "\n";
}

// One of Tables 2-3: keyframes a and b, rows per method and curve kind (open, closed), our
// figures (PM: mean points of a curve on both keyframes; errors and ms per curve) beside
// the paper's.
bool table_2022(const Animation& anim, const Curves& curves, uint32_t a, uint32_t b, const PaperRow2022 paper[2][3],
                double unit, const char* unit_name, nlohmann::json* out, std::string* text, std::string* error) {
  Method2022 by_kind[2][kMethods2022], all[kMethods2022];
  for (uint32_t c = 0; c < curves.curve_count(); ++c) {
    const CurveFrames in = gather_curve_frames(anim, curves, c, {a, b}, {0.0, 1.0});
    Method2022 one[kMethods2022];
    if (!fit_pair_2022(in, one, error)) return fail(error, "curve " + std::to_string(c) + ": " + *error);
    for (Method2022* dst : {by_kind[curves.closed[c] ? 1 : 0], all})
      for (int k = 0; k < kMethods2022; ++k) {
        for (int j = 0; j < 2; ++j) {
          dst[k].key[j].sum += one[k].key[j].sum;
          dst[k].key[j].count += one[k].key[j].count;
          dst[k].key[j].worst = std::max(dst[k].key[j].worst, one[k].key[j].worst);
        }
        dst[k].ms += one[k].ms;
        dst[k].curves += one[k].curves;
        dst[k].points += one[k].points;
      }
  }
  nlohmann::json j = {{"frames", {a, b}}, {"error_unit", unit_name}};
  for (int k = 0; k < kMethods2022; ++k) j[kMethodNames2022[k]] = method_json(all[k]);
  *text += " keyframes " + std::to_string(a) + " and " + std::to_string(b) + ", errors x " + unit_name +
           " (eq. 23), PM = points of one curve on both keyframes, CPU ms per curve\n";
  *text += " method    kind    PM  PBB      E_A1      E_A2     E_A12      E_m1      E_m2     E_m12   CPU ms\n";
  for (int kind = 0; kind < 2; ++kind) {
    const char* kind_name = kind ? " CC " : " OC ";
    for (int k = 0; k < kMethods2022; ++k) {
      const Method2022& m = by_kind[kind][k];
      j[kind ? "closed" : "open"][kMethodNames2022[k]] = method_json(m);
      if (m.curves == 0) continue;
      const double per = 1.0 / double(m.curves);
      const double ours[7] = {m.key[0].mean(), m.key[1].mean(), m.ea12(), m.key[0].worst, m.key[1].worst, m.em12(), m.ms * per};
      const char* name = k == kPde2022 ? "PDE     " : k == kBspline2022 ? "B-spline" : "Bezier  ";
      *text += row_text(name, kind_name, double(m.points) * per, ours, 1.0 / unit);
      const PaperRow2022& p = paper[kind][k];
      const double theirs[7] = {p.ea1, p.ea2, p.ea12, p.em1, p.em2, p.em12, p.ms};
      *text += row_text(" paper  ", kind_name, p.pm, theirs, 1.0);
    }
    *text += "   (" + std::to_string(by_kind[kind][0].curves) + (kind ? " closed" : " open") + " curves)\n";
  }
  *out = j;
  return true;
}

bool run_2022(const Animation& anim, const Curves& curves, nlohmann::json* result, std::string* table,
              std::string* error) {
  const uint32_t F = uint32_t(anim.frames.size());
  if (F < 2) return fail(error, "paper2022 needs at least 2 frames");
  // Table 2: keyframes far apart (the paper's 20 and 100; first and last when fewer frames);
  // Table 3: adjacent keyframes (the paper's 37 and 38; the middle two when fewer).
  const uint32_t a = F > 100 ? 20 : 0, b = F > 100 ? 100 : F - 1;
  const uint32_t c = F > 38 ? 37 : (F - 1) / 2;
  nlohmann::json far, near;
  std::string t = "paper2022: " + std::to_string(curves.curve_count()) + " curves\nTable 2:";
  if (!table_2022(anim, curves, a, b, kPaperTable2, 1e-3, "1e-3", &far, &t, error)) return false;
  t += "Table 3:";
  if (!table_2022(anim, curves, c, c + 1, kPaperTable3, 1e-4, "1e-4", &near, &t, error)) return false;
  t += " (paper: one open curve of 70 and one closed curve of 71 points per keyframe, from its horse)\n";
  nlohmann::json j = far;
  j["protocol"] = "paper2022";
  j["curves"] = curves.curve_count();
  j["table2"] = far;
  j["table3"] = near;
  *result = j;
  if (table) *table = t;
  return true;
}

}  // namespace

bool run_paper_protocol(const std::string& protocol, const Animation& anim, const Curves& curves, nlohmann::json* result,
                        std::string* table, std::string* error, bool alpha_searches) {
  std::string local;
  if (!error) error = &local;
  if (!validate_animation(anim, error)) return false;
  if (!validate_curves_for(anim, curves, error)) return false;
  if (curves.curve_count() == 0) {
    *error = "curves: no curves";
    return false;
  }
  if (protocol == "paper2024") return run_2024(anim, curves, result, table, error, alpha_searches);
  if (protocol == "paper2022") return run_2022(anim, curves, result, table, error);
  *error = "unknown protocol '" + protocol + "' (expected paper2024 or paper2022)";
  return false;
}

bool grid_row_curves(const Animation& anim, uint32_t columns, Curves* curves, std::string* error) {
  if (columns < 2 || anim.vertex_count % columns != 0 || anim.frames.empty()) {
    if (error) *error = "grid rows: vertex count " + std::to_string(anim.vertex_count) + " is not a multiple of " +
                        std::to_string(columns);
    return false;
  }
  *curves = Curves();
  const std::vector<float>& rest = anim.frames[0];
  for (uint32_t row = 0; row < anim.vertex_count / columns; ++row) {
    curves->offsets.push_back(uint32_t(curves->vertices.size()));
    std::vector<double> s(columns, 0.0);
    for (uint32_t k = 0; k < columns; ++k) {
      uint32_t v = row * columns + k;
      curves->vertices.push_back(v);
      if (k > 0) {
        double d2 = 0;
        for (int a = 0; a < 3; ++a) {
          double d = double(rest[size_t(v) * 3 + size_t(a)]) - double(rest[size_t(v - 1) * 3 + size_t(a)]);
          d2 += d * d;
        }
        s[k] = s[k - 1] + std::sqrt(d2);
      }
    }
    for (uint32_t k = 0; k < columns; ++k) curves->u.push_back(s.back() > 0 ? float(s[k] / s.back()) : float(k) / float(columns - 1));
    curves->u.back() = 1.0f;
    curves->closed.push_back(0);
  }
  curves->offsets.push_back(uint32_t(curves->vertices.size()));
  return true;
}

}  // namespace dcurve
