#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/face_order_text.h"
#include "codec/common/container_format.h"
#include "codec/common/inbetween.h"
#include "codec/common/render_mesh.h"
#include "codec/common/residual.h"
#include "codec/compress/low_rank_writer.h"
#include "codec/decompress/container_reader.h"
#include "decoder/dcurve.hpp"
#include "encoder/face_order.h"
#include "encoder/io/files.h"
#include "encoder/io/quoted_text.h"
#include "encoder/rate/plan_report.h"

namespace dcurve::cli {
namespace {

const char* mode_name(FitMode m) { return m == FitMode::Displacement ? "displacement" : "absolute"; }
// Raw bytes the frame poses add to the LRNK section (0 without poses).
uint64_t pose_bytes(const Model& m) {
  if (m.low_rank.poses.empty()) return 0;
  Model bare = m;
  bare.low_rank.poses.clear();
  return low_rank_bytes(m).size() - low_rank_bytes(bare).size();
}
const char* layout_name(int l) { return l == 0 ? "exact" : l == 1 ? "traversal" : l == 2 ? "compact" : "none"; }

// Counts of motions per basis (zero, pde8, pde32) and of Pde8 motions per case.
struct BasisUse {
  uint64_t by_basis[3] = {0, 0, 0};
  uint64_t pde8_cases[4] = {0, 0, 0, 0};
  void add(const CurveMotion& cm) {
    by_basis[size_t(cm.basis)]++;
    if (cm.basis == Basis::Pde8) pde8_cases[cm.basis_case & 3]++;
  }
  nlohmann::json json() const {
    return {{"zero", by_basis[0]}, {"pde8", by_basis[1]}, {"pde32", by_basis[2]},
            {"pde8_cases", {pde8_cases[0], pde8_cases[1], pde8_cases[2], pde8_cases[3]}}};
  }
};

// Which motion model the file carries, by name: "pde8", "pde32", "pde" (both kinds of
// curves), "low_rank", or "none" (the residual layer's predictors alone).
std::string model_name(const BasisUse& use, const Model& m) {
  const bool pde8 = use.by_basis[1] > 0, pde32 = use.by_basis[2] > 0;
  if (pde8 || pde32) return pde8 && pde32 ? "pde" : pde8 ? "pde8" : "pde32";
  return m.low_rank.components > 0 ? "low_rank" : "none";
}

// The model in words a user reads: what it is and what it takes.
std::string model_text(const std::string& name, const BasisUse& use, const Model& m, uint64_t low_rank_bytes) {
  if (name == "low_rank")
    return "low-rank basis of " + std::to_string(m.low_rank.components) + " components (" +
           std::to_string(low_rank_bytes) + " bytes), from which the frames are predicted";
  if (name == "none") return "none: each frame is predicted from decoded frames and mesh neighbours";
  return "PDE curves (" + std::to_string(use.by_basis[1]) + " pde8 and " + std::to_string(use.by_basis[2]) +
         " pde32 motions over " + std::to_string(m.segments.size()) + " time segments); in-betweens follow them";
}

// Bytes of the section `tag`, header included (0 when the file has none).
uint64_t section_bytes(const std::vector<SectionInfo>& sections, const std::string& tag) {
  uint64_t bytes = 0;
  for (const auto& s : sections)
    if (s.tag == tag) bytes += s.stored_bytes + s.header_bytes;
  return bytes;
}

// Everything `dcurve info` reports, as one JSON object; the text output prints from it.

// Render vertices, their attributes and the placement (REND, PLAC).
nlohmann::json describe_render(const Model& m) {
  nlohmann::json attributes = nlohmann::json::array();
  for (const RenderAttribute& a : m.render.attributes)
    attributes.push_back({{"name", attribute_gltf_name(a.semantic)}, {"components", a.components}, {"bits", a.bits}});
  nlohmann::json groups = nlohmann::json::array();
  for (const FaceGroup& g : m.render.groups) groups.push_back({{"material", g.material}, {"name", g.name}});
  const Placement& p = m.placement;
  return {{"groups", groups},
          {"material_bytes", m.materials.json.size()},
          {"images", m.materials.images.size()},
          {"render_vertices", m.render.empty() ? m.meta.vertex_count : uint32_t(m.render.source.size())},
          {"attributes", attributes},
          {"start_time", p.start_time},
          {"matrix", p.has_matrix ? nlohmann::json(std::vector<double>(p.matrix, p.matrix + 16)) : nlohmann::json()},
          {"mesh_name", p.mesh_name},
          {"node_name", p.node_name}};
}

nlohmann::json describe(const std::string& path, const std::vector<uint8_t>& bytes, const Model& m,
                        const std::vector<SectionInfo>& sections) {
  ContainerHeader h;
  peek_header(bytes.data(), bytes.size(), &h);
  nlohmann::json js = nlohmann::json::array();
  const uint64_t connectivity = connectivity_bytes(sections);
  int face_layout = -1;
  for (const auto& s : sections) {
    js.push_back({{"tag", s.tag}, {"offset", s.offset}, {"header_bytes", s.header_bytes}, {"required", s.required}, {"compressed", s.compressed},
                  {"stored_bytes", s.stored_bytes}, {"raw_bytes", s.raw_bytes}});
    if (s.tag == "FACE") face_layout = s.face_layout;
  }
  std::vector<uint32_t> lengths;
  uint64_t closed = 0;
  for (uint32_t c = 0; c < m.curves.curve_count(); ++c) {
    lengths.push_back(m.curves.offsets[c + 1] - m.curves.offsets[c]);
    closed += m.curves.closed[c];
  }
  std::sort(lengths.begin(), lengths.end());
  const uint64_t faces = m.faces.size() / 3;
  const double vf = double(m.meta.vertex_count) * m.meta.frame_count;
  BasisUse total;
  nlohmann::json segs = nlohmann::json::array();
  for (const Segment& s : m.segments) {
    BasisUse use;
    for (const CurveMotion& cm : s.motion) {
      use.add(cm);
      total.add(cm);
    }
    segs.push_back({{"first_frame", s.first_frame}, {"last_frame", s.last_frame}, {"mode", mode_name(s.mode)},
                    {"basis_use", use.json()}});
  }
  const bool has_residual = m.residual.step > 0;
  nlohmann::json predictors = predictor_use(m);
  const std::string model = model_name(total, m);
  const FaceOrderUse order = face_order_use(m.faces);

  return {{"file", path},
          {"bytes", bytes.size()},
          {"version", std::to_string(h.version_major) + "." + std::to_string(h.version_minor)},
          {"flags", h.flags},
          {"vertices", m.meta.vertex_count},
          {"frames", m.meta.frame_count},
          {"frame_rate", m.meta.frame_rate},
          {"units", m.meta.units},
          {"tolerance", m.meta.tolerance},
          {"rest_diagonal", m.meta.diag},
          {"inbetween", inbetween_name(m.meta.inbetween)},
          {"bpvf", 8.0 * double(bytes.size()) / vf},
          {"motion_bytes", bytes.size() - connectivity},
          {"connectivity_bytes", connectivity},
          {"faces", faces},
          {"face_layout", layout_name(face_layout)},
          {"face_order", faces ? face_order_name(order.coder_order) : "none"},
          {"coder_order_connectivity_bytes", order.coder_order_bytes},
          {"model", model},
          {"model_text", model_text(model, total, m, section_bytes(sections, "LRNK"))},
          {"face_bytes_per_triangle", faces ? double(connectivity) / double(faces) : 0.0},
          {"curves",
           {{"count", lengths.size()},
            {"closed", closed},
            {"min_length", lengths.empty() ? 0 : lengths.front()},
            {"median_length", lengths.empty() ? 0 : lengths[lengths.size() / 2]},
            {"max_length", lengths.empty() ? 0 : lengths.back()},
            {"mean_length", lengths.empty() ? 0.0 : double(m.meta.vertex_count) / double(lengths.size())}}},
          {"segments", segs},
          {"basis_use", total.json()},
          {"residual",
           {{"present", has_residual},
            {"grid_step", m.residual.step},
            {"origin", {m.residual.origin[0], m.residual.origin[1], m.residual.origin[2]}},
            {"payload_bytes", m.residual.payload.size()},
            {"chunk_frames", m.residual.chunk_frames},
            {"chunks", chunk_count(m.meta.frame_count, m.residual.chunk_frames)},
            {"predictors", predictors}}},
          {"low_rank",
           {{"components", m.low_rank.components},
            {"shift", m.low_rank.shift},
            {"mean_shift", m.low_rank.mean_shift},
            {"coefficient_shifts", m.low_rank.coeff_shifts},
            {"basis_payload_bytes", m.low_rank.basis_payload.size()},
            {"posed", !m.low_rank.poses.empty()},
            {"pose_bytes", pose_bytes(m)}}},
          {"render", describe_render(m)},
          {"sections", js}};
}

// `text` for a terminal: printable ASCII as is, every other byte as \xNN, so the units or a
// path stored in a file cannot send escape sequences.
std::string printable(const std::string& text) {
  std::string out;
  char buf[8];
  for (unsigned char c : text) {
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out.push_back(char(c));
    } else {
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  return out;
}

// The first few group names, each cut, and how many more: a file may hold 100,000 groups
// (--json lists them all).
std::string group_names_text(const nlohmann::json& groups) {
  constexpr size_t kShownNames = 5, kShownNameBytes = 64;
  std::string names;
  for (size_t i = 0; i < groups.size() && i < kShownNames; ++i)
    names += (i ? ", \"" : "\"") + quote_file_text(groups[i]["name"].get<std::string>(), kShownNameBytes) + "\"";
  if (groups.size() > kShownNames) names += " and " + std::to_string(groups.size() - kShownNames) + " more";
  return names;
}

// What every user asks first: size, counts, tolerance, which model and which face layout.
void print_render(const nlohmann::json& r, uint32_t vertices) {
  std::string attributes;
  for (const auto& a : r["attributes"])
    attributes += (attributes.empty() ? "" : ", ") + a["name"].get<std::string>() + " (" +
                  std::to_string(a["bits"].get<int>()) + " bits)";
  if (r["render_vertices"].get<uint32_t>() != vertices || !attributes.empty())
    std::printf("  render vertices: %u (seam copies share their vertex's position); attributes: %s\n",
                r["render_vertices"].get<uint32_t>(), attributes.empty() ? "none" : attributes.c_str());
  if (!r["groups"].empty())
    std::printf("  %zu face groups (materials %s), %zu images\n", r["groups"].size(), group_names_text(r["groups"]).c_str(),
                r["images"].get<size_t>());
  if (!r["matrix"].is_null() || r["start_time"].get<double>() != 0 || !r["node_name"].get<std::string>().empty() ||
      !r["mesh_name"].get<std::string>().empty())
    std::printf("  placement: mesh \"%s\", node \"%s\", %s, first frame at %.6g s\n",
                printable(r["mesh_name"].get<std::string>()).c_str(), printable(r["node_name"].get<std::string>()).c_str(),
                r["matrix"].is_null() ? "no transform" : "a node transform", r["start_time"].get<double>());
}

void print_summary(const nlohmann::json& j) {
  std::printf("%s: %llu bytes, .dcrv %s\n", j["file"].get<std::string>().c_str(),
              (unsigned long long)j["bytes"].get<uint64_t>(), j["version"].get<std::string>().c_str());
  std::printf("  %u vertices, %u frames at %.3g fps, units \"%s\"\n", j["vertices"].get<uint32_t>(),
              j["frames"].get<uint32_t>(), j["frame_rate"].get<double>(), printable(j["units"].get<std::string>()).c_str());
  std::printf("  tolerance %.3g of L = %.6g; %.3f bits per vertex per frame; %s in-betweens\n",
              j["tolerance"].get<double>(), j["rest_diagonal"].get<double>(), j["bpvf"].get<double>(),
              j["inbetween"].get<std::string>().c_str());
  std::printf("  model: %s\n", j["model_text"].get<std::string>().c_str());
  if (j["face_order"] == "none")
    std::printf("  faces: none stored (the engine supplies the mesh)\n");
  else
    std::printf("  faces: %s\n", face_order_text(j["faces"].get<uint64_t>(), j["face_order"] == "coder",
                                                 j["connectivity_bytes"].get<uint64_t>(),
                                                 j["coder_order_connectivity_bytes"].get<uint64_t>())
                                     .c_str());
  const auto& r = j["residual"];
  if (r["present"].get<bool>())
    std::printf("  residual layer: grid step %.6g, %llu payload bytes in %u chunks of %u frames\n",
                r["grid_step"].get<double>(), (unsigned long long)r["payload_bytes"].get<uint64_t>(),
                r["chunks"].get<uint32_t>(), r["chunk_frames"].get<uint32_t>());
  else
    std::printf("  no residual layer: positions come from the motion model alone\n");
  print_render(j["render"], j["vertices"].get<uint32_t>());
}

// The curves and the PDE motions per segment (all Zero without a PDE model).
void print_curves_and_motions(const nlohmann::json& j) {
  std::printf("  FACE layout %s, %.3f bytes/triangle\n", j["face_layout"].get<std::string>().c_str(),
              j["face_bytes_per_triangle"].get<double>());
  const auto& c = j["curves"];
  std::printf("  %llu curves (%llu closed), length min %u / median %u / max %u, mean %.1f\n",
              (unsigned long long)c["count"].get<uint64_t>(), (unsigned long long)c["closed"].get<uint64_t>(),
              c["min_length"].get<uint32_t>(), c["median_length"].get<uint32_t>(), c["max_length"].get<uint32_t>(),
              c["mean_length"].get<double>());
  const auto& b = j["basis_use"];
  std::printf("  %zu segments; motions: %llu zero, %llu pde8 (cases %llu/%llu/%llu/%llu), %llu pde32\n",
              j["segments"].size(), (unsigned long long)b["zero"].get<uint64_t>(),
              (unsigned long long)b["pde8"].get<uint64_t>(), (unsigned long long)b["pde8_cases"][0].get<uint64_t>(),
              (unsigned long long)b["pde8_cases"][1].get<uint64_t>(),
              (unsigned long long)b["pde8_cases"][2].get<uint64_t>(),
              (unsigned long long)b["pde8_cases"][3].get<uint64_t>(), (unsigned long long)b["pde32"].get<uint64_t>());
  for (const auto& s : j["segments"])
    std::printf("    frames %5u..%-5u %-12s %llu zero, %llu pde8, %llu pde32\n", s["first_frame"].get<uint32_t>(),
                s["last_frame"].get<uint32_t>(), s["mode"].get<std::string>().c_str(),
                (unsigned long long)s["basis_use"]["zero"].get<uint64_t>(),
                (unsigned long long)s["basis_use"]["pde8"].get<uint64_t>(),
                (unsigned long long)s["basis_use"]["pde32"].get<uint64_t>());
}

// The low-rank model's parameters and the residual layer's predictor choices.
void print_residual_details(const nlohmann::json& j) {
  const auto& lr = j["low_rank"];
  if (lr["components"].get<uint32_t>() > 0)
    std::printf("  low-rank model (Model predictor): %u components, shift %u, mean shift %u, "
                "coefficient shifts %s, basis %llu bytes%s\n",
                lr["components"].get<uint32_t>(), lr["shift"].get<uint32_t>(), lr["mean_shift"].get<uint32_t>(),
                lr["coefficient_shifts"].empty() ? "none" : lr["coefficient_shifts"].dump().c_str(),
                (unsigned long long)lr["basis_payload_bytes"].get<uint64_t>(),
                lr["posed"].get<bool>()
                    ? (", posed: frame poses in " + std::to_string(lr["pose_bytes"].get<uint64_t>()) + " bytes").c_str()
                    : "");
  const auto& p = j["residual"]["predictors"];
  if (p.is_null()) return;
  std::printf("  predictors per frame and axis: %s; spatial corrections: %s; %s coding order\n",
              p["kind"].dump().c_str(), p["spatial"].dump().c_str(), p["coding_order"].get<std::string>().c_str());
  std::printf("  clusters: %s of up to %s vertices; %s candidates over %s frames with several; "
              "per cluster and axis: %s; motion maps: %s\n",
              p["clusters"].dump().c_str(), p["cluster_size"].dump().c_str(), p["candidates"].dump().c_str(),
              p["clustered_frames"].dump().c_str(), p["cluster_kind"].dump().c_str(),
              p["motion_transforms"].dump().c_str());
  std::vector<uint32_t> bytes = p["frame_stream_bytes"].get<std::vector<uint32_t>>();
  if (bytes.empty()) return;
  const uint32_t first = bytes[0];
  std::sort(bytes.begin(), bytes.end());
  std::printf("  residual stream bytes per frame: frame 0 %u; all frames min %u, median %u, max %u "
              "(--json lists them)\n",
              first, bytes.front(), bytes[bytes.size() / 2], bytes.back());
}

void print_sections(const nlohmann::json& j) {
  std::printf("  sections:\n");
  for (const auto& s : j["sections"])
    std::printf("    %s at %8llu  %-8s %-4s %10llu bytes stored, %10llu raw\n", s["tag"].get<std::string>().c_str(),
                (unsigned long long)s["offset"].get<uint64_t>(), s["required"].get<bool>() ? "required" : "optional",
                s["compressed"].get<bool>() ? "zstd" : "", (unsigned long long)s["stored_bytes"].get<uint64_t>(),
                (unsigned long long)s["raw_bytes"].get<uint64_t>());
}

void print_text(const nlohmann::json& j, bool verbose) {
  print_summary(j);
  if (!verbose) return;
  print_curves_and_motions(j);
  if (j["residual"]["present"].get<bool>()) print_residual_details(j);
  print_sections(j);
}

// Whether every frame decodes (decode's checks reach the chunks only when it evaluates them).
bool decodes_every_frame(const std::vector<uint8_t>& bytes, std::string* error) {
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), error);
  if (!dec) return false;
  auto cursor = dec->make_cursor();
  std::vector<float> xyz(size_t(dec->vertex_count()) * 3);
  Error e;
  for (uint32_t f = 0; f < dec->frame_count(); ++f)
    if (!cursor->evaluate_frame(f, xyz.data(), &e)) {
      *error = "frame " + std::to_string(f) + ": " + e.message;
      return false;
    }
  return true;
}

}  // namespace

Action add_info(CLI::App& app) {
  struct Opts {
    std::string input;
    bool json = false, verbose = false;
  };
  auto o = std::make_shared<Opts>();
  app.add_option("input", o->input, ".dcrv file")->required();
  app.add_flag("--json", o->json, "Print one JSON object on stdout");
  app.add_flag("-v,--verbose", o->verbose,
               "Also print the curves, PDE motions per segment, the residual layer's predictor choices and the "
               "sections");
  return [o]() {
    std::vector<uint8_t> bytes;
    std::string err;
    if (!read_file(o->input, &bytes, &err)) {
      std::fprintf(stderr, "dcurve info: %s\n", err.c_str());
      return 1;
    }
    Model m;
    std::vector<SectionInfo> sections;
    // The decoder's checks too: info describes only files that decode.
    if (!read_container(bytes.data(), bytes.size(), &m, &err, &sections) || !decodes_every_frame(bytes, &err)) {
      std::fprintf(stderr, "dcurve info: %s: %s\n", o->input.c_str(), err.c_str());
      return 1;
    }
    nlohmann::json j = describe(o->input, bytes, m, sections);
    if (o->json)  // units are bytes from the file: invalid UTF-8 becomes U+FFFD
      std::printf("%s\n", j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace).c_str());
    else
      print_text(j, o->verbose);
    return 0;
  };
}

}  // namespace dcurve::cli
