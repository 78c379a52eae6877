#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/encode_job.h"
#include "cli/messages.h"
#include "cli/number_range.h"
#include "codec/common/inbetween.h"
#include "codec/common/render_mesh.h"
#include "corpus/input.h"
#include "encoder/encoder.h"
#include "encoder/io/frame_times.h"

namespace dcurve::cli {
namespace {

// The job's messages as the subcommand prints them (-q, -v, progress bars or lines).
EncodeListener listener_of(const std::shared_ptr<Messages>& msg) {
  EncodeListener l;
  l.note = [msg](const std::string& m) { msg->note(m); };
  l.detail = [msg](const std::string& m) { msg->detail(m); };
  l.progress = [msg](const std::string& stage) { return msg->progress(stage); };
  return l;
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
                 "finer than the coarsest, 3 walks the grids by trial encodes (about four encodes) and tries "
                 "a Fit weight table per frame where it shrinks a chunk by 2 % (a slower decode). Lower is "
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
  app.add_option("--threads", o->threads, "Worker threads, at most the cores, 0 = all cores (output is the same for any count)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--json", o->json, "Print one JSON object with the encode summary on stdout");
  msg->add_flags(app);
  return [o, msg]() {
    std::string err;
    if (!std::isfinite(o->input_options.fps)) {  // CLI11's range checks let "nan" through
      std::fprintf(stderr, "dcurve encode: --fps must be a number\n");
      return 2;
    }
    if (o->reorder_faces && o->keep_face_order) {
      std::fprintf(stderr, "dcurve encode: --reorder-faces (the default, deprecated) contradicts --keep-face-order\n");
      return 2;
    }
    EncodeFileJob job;
    job.input = o->input;
    job.output = o->output;
    job.input_options = o->input_options;
    job.force = o->force;
    EncodeOptions& eo = job.options;
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
    EncodeReport rep;
    if (!run_encode_file(job, listener_of(msg), &rep, &err)) return msg->error(err);
    const nlohmann::json j = encode_summary_json(job, rep);
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
