#include "bench/report.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace dcurve::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const MethodResult* find_method(const InputResult& in, const std::string& name) {
  for (const auto& m : in.methods)
    if (m.method == name) return &m;
  return nullptr;
}

std::string fmt(const char* f, double v) {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

nlohmann::json number_or_null(double v) { return std::isnan(v) ? nlohmann::json() : nlohmann::json(v); }

}  // namespace

double ratio_to_draco_per_frame(const InputResult& in, const MethodResult& m) {
  const MethodResult* d = find_method(in, "draco_per_frame");
  if (!d || !d->meets_tolerance || d->bytes == 0) return kNaN;
  return double(m.bytes) / double(d->bytes);
}

double ratio_to_best_other(const InputResult& in, const MethodResult& m, std::string* best) {
  const MethodResult* ref = nullptr;
  for (const auto& o : in.methods)
    if (o.method != m.method && o.method != "dcurve" && o.meets_tolerance && o.bytes > 0 &&
        (!ref || o.bytes < ref->bytes))
      ref = &o;
  if (best) *best = ref ? ref->method : "";
  return ref ? double(m.bytes) / double(ref->bytes) : kNaN;
}

std::string format_table(const std::vector<InputResult>& results) {
  std::ostringstream out;
  for (const auto& in : results) {
    char head[256];
    std::snprintf(head, sizeof head, "%s: %u vertices x %u frames, tolerance %g (max error, fraction of L)\n",
                  in.input.c_str(), in.vertices, in.frames, in.tolerance);
    out << head;
    char row[512];
    std::snprintf(row, sizeof row, "  %-16s %12s %10s %9s %8s %8s %7s %9s %9s %7s %8s %10s  %s\n", "method",
                  "bytes", "motion.B", "conn.B", "/draco", "/best", "bpvf", "max_err", "rmse", "KG%", "enc s", "dec Mv/s", "settings");
    out << row;
    for (const auto& m : in.methods) {
      std::string best;
      const double to_best = ratio_to_best_other(in, m, &best);
      std::snprintf(row, sizeof row, "  %-16s %12llu %10llu %9llu %8s %8s %7s %9s %9s %7s %8s %10s  %s%s\n",
                    m.method.c_str(), (unsigned long long)m.bytes,
                    (unsigned long long)(m.bytes - m.connectivity_bytes), (unsigned long long)m.connectivity_bytes,
                    fmt("%.3f", ratio_to_draco_per_frame(in, m)).c_str(), fmt("%.3f", to_best).c_str(),
                    fmt("%.3f", m.bpvf).c_str(), fmt("%.3g", m.max_error).c_str(), fmt("%.3g", m.rmse).c_str(),
                    fmt("%.3f", m.kg_error_pct).c_str(), fmt("%.2f", m.encode_seconds).c_str(),
                    fmt("%.1f", m.decode_vertices_per_second / 1e6).c_str(),
                    m.meets_tolerance ? "" : "[MISSES TOLERANCE] ", m.settings.c_str());
      out << row;
    }
    std::string best;
    if (const MethodResult* d = find_method(in, "dcurve")) {
      const double r = ratio_to_best_other(in, *d, &best);
      if (!std::isnan(r)) out << "  dcurve / best baseline (" << best << ") = " << fmt("%.3f", r) << "\n";
    }
    out << "\n";
  }
  out << "bytes = motion.B + conn.B (connectivity): non-Draco baselines pay one Draco edgebreaker encode of\n"
         "frame 0's faces; Draco files carry it in every file (conn.B estimates that share);\n"
         "dcurve counts its own connectivity section. /draco, /best: bytes over draco_per_frame's and\n"
         "over the smallest other baseline's that meets the tolerance. Errors measured on decoded bytes.\n";
  return out.str();
}

nlohmann::json results_json(const std::vector<InputResult>& results) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& in : results) {
    nlohmann::json methods = nlohmann::json::array();
    for (const auto& m : in.methods)
      methods.push_back({{"method", m.method},
                         {"bytes", m.bytes},
                         {"connectivity_bytes", m.connectivity_bytes},
                         {"motion_bytes", m.bytes - m.connectivity_bytes},
                         {"ratio_to_draco_per_frame", number_or_null(ratio_to_draco_per_frame(in, m))},
                         {"ratio_to_best_other", number_or_null(ratio_to_best_other(in, m))},
                         {"bpvf", m.bpvf},
                         {"max_error", m.max_error},
                         {"rmse", m.rmse},
                         {"kg_error_pct", m.kg_error_pct},
                         {"encode_seconds", m.encode_seconds},
                         {"decode_vertices_per_second", m.decode_vertices_per_second},
                         {"meets_tolerance", m.meets_tolerance},
                         {"settings", m.settings}});
    list.push_back({{"input", in.input},
                    {"tolerance", in.tolerance},
                    {"vertices", in.vertices},
                    {"frames", in.frames},
                    {"methods", methods}});
  }
  return {{"results", list}};
}

std::string results_csv(const std::vector<InputResult>& results) {
  std::ostringstream out;
  out << "input,tolerance,vertices,frames,method,bytes,connectivity_bytes,ratio_to_draco_per_frame,"
         "ratio_to_best_other,bpvf,max_error,rmse,kg_error_pct,encode_seconds,decode_vertices_per_second,"
         "meets_tolerance,settings\n";
  for (const auto& in : results)
    for (const auto& m : in.methods) {
      // Free text is quoted, with its own double quotes turned into single ones.
      std::string input = in.input, settings = m.settings;
      for (std::string* text : {&input, &settings})
        for (char& c : *text)
          if (c == '"') c = '\'';
      out << '"' << input << "\"," << in.tolerance << ',' << in.vertices << ',' << in.frames << ',' << m.method << ','
          << m.bytes << ',' << m.connectivity_bytes << ',' << fmt("%.6g", ratio_to_draco_per_frame(in, m)) << ','
          << fmt("%.6g", ratio_to_best_other(in, m)) << ',' << fmt("%.6g", m.bpvf) << ','
          << fmt("%.6g", m.max_error) << ',' << fmt("%.6g", m.rmse) << ',' << fmt("%.6g", m.kg_error_pct) << ','
          << fmt("%.6g", m.encode_seconds) << ',' << fmt("%.6g", m.decode_vertices_per_second) << ','
          << (m.meets_tolerance ? 1 : 0) << ",\"" << settings << "\"\n";
    }
  return out.str();
}

}  // namespace dcurve::bench
