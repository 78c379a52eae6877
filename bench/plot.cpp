#include "bench/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

namespace dcurve::bench {
namespace {

constexpr double kPanelW = 520, kPanelH = 380, kLeft = 64, kRight = 150, kTop = 34, kBottom = 46;
constexpr double kLosslessStrip = 26;  // px left of the log axis where max error 0 is drawn
const char* const kColors[] = {"#d62728", "#1f77b4", "#17becf", "#9467bd", "#2ca02c", "#7f7f7f", "#bcbd22",
                               "#8c564b", "#e377c2", "#ff7f0e"};

struct Point {
  double error, bpvf;
  bool meets;
};

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

// Decade-aligned log range covering [lo, hi].
void decades(double lo, double hi, double* a, double* b) {
  *a = std::floor(std::log10(lo));
  *b = std::ceil(std::log10(hi));
  if (*b <= *a) *b = *a + 1;
}

void draw_panel(std::ostringstream& svg, double ox, double oy, const std::string& input,
                const std::vector<std::string>& methods, const std::map<std::string, std::vector<Point>>& points) {
  double emin = 1e300, emax = 0, bmin = 1e300, bmax = 0;
  for (const auto& [name, pts] : points)
    for (const auto& p : pts) {
      if (p.error > 0) { emin = std::min(emin, p.error); emax = std::max(emax, p.error); }
      if (p.bpvf > 0) { bmin = std::min(bmin, p.bpvf); bmax = std::max(bmax, p.bpvf); }
    }
  if (emax == 0) { emin = 1e-4; emax = 1e-2; }
  if (bmax == 0) { bmin = 1; bmax = 10; }
  double ex0, ex1, by0, by1;
  decades(emin, emax, &ex0, &ex1);
  decades(bmin, bmax, &by0, &by1);
  const double pw = kPanelW - kLeft - kRight, ph = kPanelH - kTop - kBottom;
  const double ax = ox + kLeft + kLosslessStrip, aw = pw - kLosslessStrip;  // the log axis
  auto X = [&](double e) {
    return e > 0 ? ax + (std::log10(e) - ex0) / (ex1 - ex0) * aw : ox + kLeft + kLosslessStrip / 2;
  };
  auto Y = [&](double b) { return oy + kTop + ph - (std::log10(b) - by0) / (by1 - by0) * ph; };

  svg << "<text x='" << num(ox + kLeft) << "' y='" << num(oy + 20) << "' font-weight='bold'>" << escape(input)
      << "</text>\n";
  svg << "<rect x='" << num(ox + kLeft) << "' y='" << num(oy + kTop) << "' width='" << num(pw) << "' height='"
      << num(ph) << "' fill='none' stroke='#444'/>\n";
  svg << "<line x1='" << num(ax) << "' y1='" << num(oy + kTop) << "' x2='" << num(ax) << "' y2='"
      << num(oy + kTop + ph) << "' stroke='#444' stroke-dasharray='3,3'/><text x='"
      << num(ox + kLeft + kLosslessStrip / 2) << "' y='" << num(oy + kTop + ph + 16)
      << "' text-anchor='middle' font-size='11'>0</text>\n";
  for (double d = ex0; d <= ex1 + 1e-9; d += 1) {
    const double x = X(std::pow(10.0, d));
    svg << "<line x1='" << num(x) << "' y1='" << num(oy + kTop) << "' x2='" << num(x) << "' y2='"
        << num(oy + kTop + ph) << "' stroke='#ddd'/><text x='" << num(x) << "' y='" << num(oy + kTop + ph + 16)
        << "' text-anchor='middle' font-size='11'>1e" << int(d) << "</text>\n";
  }
  for (double d = by0; d <= by1 + 1e-9; d += 1) {
    const double y = Y(std::pow(10.0, d));
    svg << "<line x1='" << num(ox + kLeft) << "' y1='" << num(y) << "' x2='" << num(ox + kLeft + pw) << "' y2='"
        << num(y) << "' stroke='#ddd'/><text x='" << num(ox + kLeft - 6) << "' y='" << num(y + 4)
        << "' text-anchor='end' font-size='11'>" << std::pow(10.0, d) << "</text>\n";
  }
  svg << "<text x='" << num(ox + kLeft + pw / 2) << "' y='" << num(oy + kPanelH - 8)
      << "' text-anchor='middle' font-size='12'>max error (fraction of L); left strip: lossless</text>\n";
  svg << "<text transform='translate(" << num(ox + 16) << "," << num(oy + kTop + ph / 2)
      << ") rotate(-90)' text-anchor='middle' font-size='12'>bits per vertex per frame</text>\n";

  for (size_t i = 0; i < methods.size(); ++i) {
    const auto it = points.find(methods[i]);
    if (it == points.end()) continue;
    std::vector<Point> pts = it->second;
    std::sort(pts.begin(), pts.end(), [](const Point& a, const Point& b) { return a.error < b.error; });
    const char* color = kColors[i % (sizeof kColors / sizeof *kColors)];
    std::string path;
    for (const auto& p : pts)
      if (p.bpvf > 0) path += (path.empty() ? "M" : " L") + num(X(p.error)) + "," + num(Y(p.bpvf));
    if (pts.size() > 1) svg << "<path d='" << path << "' fill='none' stroke='" << color << "' stroke-width='1.5'/>\n";
    for (const auto& p : pts)
      if (p.bpvf > 0)
        svg << "<circle cx='" << num(X(p.error)) << "' cy='" << num(Y(p.bpvf)) << "' r='4' stroke='" << color
            << "' stroke-width='1.5' fill='" << (p.meets ? color : "white") << "'/>\n";
    const double ly = oy + kTop + 8 + 18 * double(i);
    svg << "<circle cx='" << num(ox + kLeft + pw + 16) << "' cy='" << num(ly) << "' r='4' fill='" << color
        << "'/><text x='" << num(ox + kLeft + pw + 26) << "' y='" << num(ly + 4) << "' font-size='12'>"
        << escape(methods[i]) << "</text>\n";
  }
}

}  // namespace

std::string rate_distortion_svg(const std::vector<InputResult>& results) {
  std::vector<std::string> inputs, methods;
  std::map<std::string, std::map<std::string, std::vector<Point>>> by_input;
  for (const auto& in : results) {
    if (!by_input.count(in.input)) inputs.push_back(in.input);
    for (const auto& m : in.methods) {
      if (std::find(methods.begin(), methods.end(), m.method) == methods.end()) methods.push_back(m.method);
      by_input[in.input][m.method].push_back({m.max_error, m.bpvf, m.meets_tolerance});
    }
  }
  const int columns = inputs.size() > 1 ? 2 : 1;
  const int rows = int((inputs.size() + columns - 1) / columns);
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << num(columns * kPanelW) << "' height='"
      << num(std::max(rows, 1) * kPanelH) << "' font-family='sans-serif'>\n<rect width='100%' height='100%' "
      << "fill='white'/>\n";
  for (size_t i = 0; i < inputs.size(); ++i)
    draw_panel(svg, double(i % columns) * kPanelW, double(i / columns) * kPanelH, inputs[i], methods,
               by_input[inputs[i]]);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace dcurve::bench
