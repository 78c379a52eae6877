#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <new>

#include "cli/commands.h"
#include "cli/face_order_text.h"
#include "cli/messages.h"
#include "cli/number_range.h"
#include "cli/output_path.h"
#include "codec/common/inbetween.h"
#include "codec/common/render_mesh.h"
#include "encoder/curves/report_json.h"
#include "encoder/encoder.h"
#include "corpus/input.h"
#include "encoder/io/files.h"
#include "encoder/io/frame_times.h"
#include "encoder/io/gltf_references.h"
#include "encoder/io/output_file.h"
#include "corpus/sim/scene.h"

namespace dcurve::cli {
namespace {

// The files an encode of `input` reads: a folder's frames, or the input file (glTF, point
// cache, scene) with a glTF's buffers and images, a point cache's mesh or a scene's surface.
std::vector<std::string> input_files(const std::string& input, const std::string& rest_mesh) {
  std::vector<std::string> files;
  std::string ignored;  // an unreadable input is reported when it is loaded
  std::error_code ec;
  if (std::filesystem::is_directory(input, ec)) {
    if (!list_frame_files(input, &files, &ignored)) files.clear();
    return files;
  }
  files = gltf_referenced_files(input);
  files.push_back(input);
  if (!rest_mesh.empty()) files.push_back(rest_mesh);
  Scene scene;
  if (load_scene_file(input, &scene, &ignored) && !scene.mesh_file.empty()) files.push_back(scene.mesh_file);
  return files;
}

// Refuses, before a long encode, an output that is one of the inputs, may not be replaced
// (cli/output_path) or is not a .dcrv file.
bool check_encode_output(const std::string& input, const std::string& rest_mesh, const std::string& output, bool force,
                         std::string* error) {
  OutputKind kind;
  return check_output_file(output, force, input_files(input, rest_mesh), error) &&
         output_kind(output, {OutputKind::Dcrv}, &kind, error);
}

// Reads and encodes `input`; an allocation that fails anywhere (worker threads included,
// encoder/parallel.h) is an error naming the input, not an abort.
bool read_and_encode(const std::string& input, const InputOptions& io, EncodeOptions eo, const Messages& msg,
                     Animation* anim, std::vector<uint8_t>* bytes, EncodeReport* rep, std::string* err) {
  const char* stage = "reading it";
  try {
    if (!load_animation_input(input, io, msg.progress(input_stage_label(input)), anim, err)) return false;
    msg.detail("read " + std::to_string(anim->frames.size()) + " frames of " + std::to_string(anim->vertex_count) +
               " vertices, " + std::to_string(anim->faces.size() / 3) + " triangles, " +
               std::to_string(anim->frame_rate) + " fps from " + input);
    for (const std::string& note : anim->notes) msg.note(input + ": " + note);
    if (!eo.connectivity && !anim->render.empty())
      msg.note(input + ": --no-connectivity: the file keeps no render vertices (UVs, seams), which follow the faces");
    stage = "encoding it";
    eo.progress = msg.progress("encode");
    if (encode_animation(*anim, eo, bytes, rep, err)) return true;
    *err = input + ": " + *err;
  } catch (const std::bad_alloc&) {
    *err = input + ": out of memory while " + stage + " (--max-memory bounds what the readers allocate)";
  }
  return false;
}

}  // namespace

Action add_encode(CLI::App& app) {
  struct Opts {
    std::string input, output;
    double tolerance = 1e-3;
    bool json = false, no_connectivity = false, keep_face_order = false, reorder_faces = false;
    bool keep_all_motions = false, force = false;
    InputOptions input_options;
    int threads = 0, effort = EncodeOptions().effort;
    int uv_bits = EncodeOptions().attributes.texcoord_bits;
    std::string model = "none", low_rank = "auto", segment_frames = "auto", grid = "auto", chunk_frames = "auto";
    std::string inbetween = "auto", profile = "small";
    uint32_t curve_points = 64;
  };
  auto o = std::make_shared<Opts>();
  auto msg = std::make_shared<Messages>("encode");
  app.add_option("input", o->input,
                 "A folder of frames (OBJ/PLY/OFF, in frame-number order), a glTF file (.glb/.gltf: one mesh "
                 "with morph targets and a weights animation), a point cache (.pc2/.mdd, with --mesh) or a "
                 "scene file (.json)")
      ->required();
  app.add_option("--mesh", o->input_options.rest_mesh,
                 "For a point cache: the mesh (OBJ/PLY/OFF) whose faces it animates; same vertex count and order");
  app.add_option("--gltf-mesh", o->input_options.gltf_mesh, "For a glTF file holding several meshes: which one (index)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--fps", o->input_options.fps,
                 "Frames per second (default: the input's own rate where it has one, else 30)")
      ->check(CLI::Range(kMinFrameRate, kMaxFrameRate));
  app.add_option("--max-memory", o->input_options.limits.max_memory,
                 "Memory the input readers may allocate, bytes (suffixes KB, MB, GB, KiB, MiB, GiB); every count a "
                 "file declares is checked against it before allocating. Default: half the physical memory, at most 4 GiB")
      ->transform(CLI::AsSizeValue(false))
      ->check(CLI::Range(uint64_t(1) << 20, UINT64_MAX));
  app.add_option("--allow-resources-outside", o->input_options.limits.resource_dirs,
                 "A folder besides the glTF's own that its buffer uris may name (repeatable); by default a glTF reads "
                 "only files inside its own folder")
      ->check(CLI::ExistingDirectory);
  app.add_option("-o,--output", o->output, "Output .dcrv file")->required();
  app.add_flag("--force", o->force, "Replace an existing output file");
  app.add_option("--tolerance", o->tolerance, "Max error, fraction of the rest-pose bounding-box diagonal")
      ->check(finite_range(kMinTolerance, 0.5))
      ->capture_default_str();
  app.add_option("--model", o->model,
                 "Motion model beside the exact frames: none (in-betweens blend linearly), pde8, pde32 or pde "
                 "(either, chosen per curve and segment; in-betweens follow the fitted PDE curves where the "
                 "rate control keeps them)")
      ->check(CLI::IsMember({"none", "pde8", "pde32", "pde"}))
      ->capture_default_str();
  app.add_option("--low-rank", o->low_rank,
                 "Low-rank (PCA) model of the frames that the residual layer may predict from: auto (kept "
                 "only when the file gets smaller), off, or a component count 1..64 (always used)")
      ->check(CLI::IsMember({"auto", "off"}) | CLI::Range(1, 64))
      ->capture_default_str();
  app.add_flag("--keep-all-motions", o->keep_all_motions,
               "With a PDE model, keep every fitted motion even where it does not pay for its coefficients "
               "(default: keep only those that make the file smaller)");
  app.add_option("--segment-frames", o->segment_frames,
                 "PDE model time segment length, frames, or auto (chosen by the rate control among 4, 8 and 16)")
      ->check(CLI::IsMember({"auto"}) | CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--grid", o->grid,
                 "Residual grid: auto (the refinement of the coarsest safe grid that codes smallest in trial "
                 "encodes, about four times the encode time) or a refinement in [1, 16] (no trials)")
      ->check(CLI::IsMember({"auto"}) | finite_range(1.0, 16.0))
      ->capture_default_str();
  app.add_option("--effort", o->effort,
                 "Search effort with --grid auto: 2 tries two grids side by side, 1 encodes once on a grid 6x "
                 "finer than the coarsest, 3 walks the grids by trial encodes (about four encodes). Lower is "
                 "faster, higher finds the last percent")
      ->check(CLI::Range(kMinEffort, kMaxEffort))
      ->capture_default_str();
  app.add_option("--profile", o->profile,
                 "fast: format 4, built for decode speed (one dense predictor per frame, sparse residuals); "
                 "small: format 3's context-adaptive coder, smaller files that decode several times slower")
      ->check(CLI::IsMember({"fast", "small"}))
      ->capture_default_str();
  app.add_option("--chunk-frames", o->chunk_frames,
                 "Frames per independently decodable chunk: auto (chosen by the encoder by measured size) or "
                 "1..4096. A decoder decodes one chunk to reach any of its frames and holds two")
      ->check(CLI::IsMember({"auto"}) | CLI::Range(1u, kMaxChunkFrames))
      ->capture_default_str();
  app.add_option("--inbetween", o->inbetween,
                 "In-between rule the file records (how a decoder fills the time between frames): auto (the one "
                 "that best predicts held-out input frames), linear, catmull-rom or hermite4")
      ->check(CLI::IsMember({"auto", "linear", "catmull-rom", "hermite4"}))
      ->capture_default_str();
  app.add_option("--curve-points", o->curve_points, "Target vertices per extracted curve")
      ->check(CLI::Range(2, 1000000))
      ->capture_default_str();
  app.add_flag("--keep-face-order", o->keep_face_order,
               "Keep the input's index buffer exactly: its triangle order and each triangle's first corner "
               "(the faces then code 1.5-5x larger). Default: the same triangles, windings and vertex ids, in "
               "the face coder's order");
  // The default since the face coder's order became it; kept so scripts that asked for it
  // still run (hidden from --help).
  app.add_flag("--reorder-faces", o->reorder_faces, "Deprecated: the default")->group("");
  app.add_flag("--no-connectivity", o->no_connectivity, "Leave faces out of the file (the engine has the mesh)");
  app.add_option("--uv-bits", o->uv_bits,
                 "Precision of texture coordinates, bits per component over each one's range in the input "
                 "(14: 1/16383 of the range)")
      ->check(CLI::Range(1, int(kMaxAttributeBits)))
      ->capture_default_str();
  app.add_option("--threads", o->threads, "Worker threads, 0 = all cores (output is the same for any count)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--json", o->json, "Print one JSON object with the encode summary on stdout");
  msg->add_flags(app);
  return [o, msg]() {
    Animation anim;
    std::string err;
    if (!std::isfinite(o->input_options.fps)) {  // CLI11's range checks let "nan" through
      std::fprintf(stderr, "dcurve encode: --fps must be a number\n");
      return 2;
    }
    if (o->reorder_faces && o->keep_face_order) {
      std::fprintf(stderr, "dcurve encode: --reorder-faces (the default, deprecated) contradicts --keep-face-order\n");
      return 2;
    }
    if (!check_encode_output(o->input, o->input_options.rest_mesh, o->output, o->force, &err)) return msg->error(err);
    EncodeOptions eo;
    eo.tolerance = o->tolerance;
    eo.connectivity = !o->no_connectivity;
    eo.exact_face_order = o->keep_face_order;
    eo.threads = o->threads;
    eo.attributes.texcoord_bits = uint8_t(o->uv_bits);
    eo.model = o->model == "pde8"    ? ModelChoice::Pde8
               : o->model == "pde32" ? ModelChoice::Pde32
               : o->model == "pde"   ? ModelChoice::Pde
                                     : ModelChoice::None;
    eo.low_rank = o->low_rank == "auto" ? -1 : o->low_rank == "off" ? 0 : std::stoi(o->low_rank);
    eo.segment_frames = o->segment_frames == "auto" ? 0 : uint32_t(std::stoul(o->segment_frames));
    eo.grid_refinement = o->grid == "auto" ? 0.0 : std::stod(o->grid);
    eo.effort = o->effort;
    eo.profile = o->profile == "small" ? Profile::Small : Profile::Fast;
    eo.chunk_frames = o->chunk_frames == "auto" ? 0 : uint32_t(std::stoul(o->chunk_frames));
    eo.keep_all_motions = o->keep_all_motions;
    Inbetween forced;
    eo.inbetween = inbetween_from_name(o->inbetween.c_str(), &forced) ? int(forced) : -1;
    eo.curve_points = o->curve_points;
    std::vector<uint8_t> bytes;
    EncodeReport rep;
    if (!read_and_encode(o->input, o->input_options, eo, *msg, &anim, &bytes, &rep, &err)) return msg->error(err);
    OutputFile out;
    if (!out.open(o->output, o->force, &err) || !out.write(bytes.data(), bytes.size(), &err) || !out.commit(&err))
      return msg->error(err);
    if (eo.connectivity)
      msg->detail("faces: " + face_order_text(anim.faces.size() / 3, rep.faces_in_coder_order, rep.connectivity_bytes,
                                              rep.coder_order_connectivity_bytes));
    nlohmann::json j = {{"input", o->input},
                        {"output", o->output},
                        {"tolerance", o->tolerance},
                        {"bytes", rep.bytes},
                        {"motion_bytes", rep.motion_bytes},
                        {"connectivity_bytes", rep.connectivity_bytes},
                        {"face_order", eo.connectivity ? face_order_name(rep.faces_in_coder_order) : "none"},
                        {"coder_order_connectivity_bytes", rep.coder_order_connectivity_bytes},
                        {"vertices", rep.vertices},
                        {"frames", rep.frames},
                        {"segments", rep.segments},
                        {"max_error", rep.error.max_error},
                        {"rmse", rep.error.rmse},
                        {"kg_error_pct", rep.error.kg_error_pct},
                        {"bpvf", rep.bpvf},
                        {"encode_seconds", rep.encode_seconds},
                        {"model", o->model},
                        {"model_bytes", rep.model_bytes},
                        {"motions_fitted", rep.motions_fitted},
                        {"motions_kept", rep.motions_kept},
                        {"low_rank_components", rep.low_rank_components},
                        {"grid_refinement", rep.grid_refinement},
                        {"chunk_frames", rep.chunk_frames},
                        {"inbetween", inbetween_name(rep.inbetween)},
                        {"effort", o->effort},
                        {"profile", o->profile},
                        {"low_rank_bytes", rep.low_rank_bytes},
                        {"curve_fallback", rep.curve_fallback}};
    j.update(curve_report_json(rep.curves));
    if (o->json) {  // asked for explicitly: printed even with -q
      std::printf("%s\n", j.dump().c_str());
    } else if (!msg->quiet()) {
      std::printf("%s: %llu bytes, %u vertices x %u frames, %.3f bits/vertex/frame, max error %.3g (tolerance %.3g), "
                  "%.2f s\n",
                  o->output.c_str(), (unsigned long long)rep.bytes, rep.vertices, rep.frames, rep.bpvf,
                  rep.error.max_error, o->tolerance, rep.encode_seconds);
    }
    return 0;
  };
}

}  // namespace dcurve::cli
