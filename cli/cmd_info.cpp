#include <nlohmann/json.hpp>

#include <cstdio>

#include "cli/commands.h"
#include "codec/container.h"
#include "encoder/io/files.h"

namespace dcurve::cli {

Action add_info(CLI::App& app) {
  struct Opts {
    std::string input;
    bool json = false;
  };
  auto o = std::make_shared<Opts>();
  app.add_option("input", o->input, ".dcrv file")->required();
  app.add_flag("--json", o->json, "Print one JSON object on stdout");
  return [o]() {
    std::vector<uint8_t> bytes;
    std::string err;
    if (!read_file(o->input, &bytes, &err)) {
      std::fprintf(stderr, "dcurve info: %s\n", err.c_str());
      return 1;
    }
    Model m;
    std::vector<SectionInfo> sections;
    if (!read_container(bytes.data(), bytes.size(), &m, &err, &sections)) {
      std::fprintf(stderr, "dcurve info: %s: %s\n", o->input.c_str(), err.c_str());
      return 1;
    }
    size_t basis_use[3] = {0, 0, 0};
    for (const Segment& s : m.segments)
      for (const CurveMotion& cm : s.motion) basis_use[size_t(cm.basis)]++;
    nlohmann::json js = nlohmann::json::array();
    for (const auto& s : sections)
      js.push_back({{"tag", s.tag}, {"required", s.required}, {"compressed", s.compressed},
                    {"stored_bytes", s.stored_bytes}, {"raw_bytes", s.raw_bytes}});
    nlohmann::json j = {{"file", o->input},
                        {"bytes", bytes.size()},
                        {"vertices", m.meta.vertex_count},
                        {"frames", m.meta.frame_count},
                        {"faces", m.faces.size() / 3},
                        {"frame_rate", m.meta.frame_rate},
                        {"tolerance", m.meta.tolerance},
                        {"rest_diagonal", m.meta.diag},
                        {"curves", m.curves.curve_count()},
                        {"segments", m.segments.size()},
                        {"basis_use", {{"zero", basis_use[0]}, {"pde8", basis_use[1]}, {"pde32", basis_use[2]}}},
                        {"grid_step", m.residual.step},
                        {"sections", js}};
    if (o->json) {
      std::printf("%s\n", j.dump().c_str());
      return 0;
    }
    std::printf("%s: %zu bytes\n  %u vertices, %u frames at %.3g fps, %zu faces\n  tolerance %.3g of L = %.6g\n"
                "  %u curves, %zu segments (motion models: %zu zero, %zu pde8, %zu pde32)\n  residual grid step %.6g\n",
                o->input.c_str(), bytes.size(), m.meta.vertex_count, m.meta.frame_count, m.meta.frame_rate,
                m.faces.size() / 3, m.meta.tolerance, m.meta.diag, m.curves.curve_count(), m.segments.size(),
                basis_use[0], basis_use[1], basis_use[2], m.residual.step);
    std::printf("  sections:\n");
    for (const auto& s : sections)
      std::printf("    %s %s%s %10llu bytes stored, %10llu raw\n", s.tag.c_str(), s.required ? "required" : "optional",
                  s.compressed ? ", zstd" : "", (unsigned long long)s.stored_bytes, (unsigned long long)s.raw_bytes);
    return 0;
  };
}

}  // namespace dcurve::cli
