#include "cli/encode_job.h"

#include <filesystem>
#include <new>

#include "cli/face_order_text.h"
#include "cli/output_path.h"
#include "codec/common/inbetween.h"
#include "corpus/sim/scene.h"
#include "encoder/curves/report_json.h"
#include "encoder/io/frames.h"
#include "encoder/io/gltf_references.h"
#include "encoder/io/output_file.h"

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
bool check_encode_output(const EncodeFileJob& job, std::string* error) {
  OutputKind kind;
  return check_output_file(job.output, job.force, input_files(job.input, job.input_options.rest_mesh), error) &&
         output_kind(job.output, {OutputKind::Dcrv}, &kind, error);
}

void tell(const std::function<void(const std::string&)>& to, const std::string& message) {
  if (to) to(message);
}

std::function<void(double)> stage_progress(const EncodeListener& listener, const std::string& stage) {
  return listener.progress ? listener.progress(stage) : std::function<void(double)>();
}

// Reads and encodes the input; an allocation that fails anywhere (worker threads included,
// encoder/parallel.h) is an error naming the input, not an abort.
bool read_and_encode(const EncodeFileJob& job, const EncodeListener& listener, Animation* anim,
                     std::vector<uint8_t>* bytes, EncodeReport* rep, std::string* err) {
  const std::string& input = job.input;
  const char* stage = "reading it";
  try {
    if (!load_animation_input(input, job.input_options, stage_progress(listener, input_stage_label(input)), anim, err)) return false;
    tell(listener.detail, "read " + std::to_string(anim->frames.size()) + " frames of " +
                              std::to_string(anim->vertex_count) + " vertices, " +
                              std::to_string(anim->faces.size() / 3) + " triangles, " +
                              std::to_string(anim->frame_rate) + " fps from " + input);
    for (const std::string& note : anim->notes) tell(listener.note, input + ": " + note);
    if (!job.options.connectivity && !anim->render.empty())
      tell(listener.note, input + ": --no-connectivity: the file keeps no render vertices (UVs, seams), which follow the faces");
    stage = "encoding it";
    EncodeOptions eo = job.options;
    eo.progress = stage_progress(listener, "encode");
    if (encode_animation(*anim, eo, bytes, rep, err)) return true;
    *err = input + ": " + *err;
  } catch (const std::bad_alloc&) {
    *err = input + ": out of memory while " + stage + " (--max-memory bounds what the readers allocate)";
  }
  return false;
}

}  // namespace

bool run_encode_file(const EncodeFileJob& job, const EncodeListener& listener, EncodeReport* report,
                     std::string* error) {
  if (!check_encode_output(job, error)) return false;
  Animation anim;
  std::vector<uint8_t> bytes;
  if (!read_and_encode(job, listener, &anim, &bytes, report, error)) return false;
  OutputFile out;
  if (!out.open(job.output, job.force, error) || !out.write(bytes.data(), bytes.size(), error) || !out.commit(error))
    return false;
  if (job.options.connectivity)
    tell(listener.detail, "faces: " + face_order_text(anim.faces.size() / 3, report->faces_in_coder_order,
                                                      report->connectivity_bytes, report->coder_order_connectivity_bytes));
  return true;
}

const char* model_choice_name(ModelChoice model) {
  switch (model) {
    case ModelChoice::Pde8: return "pde8";
    case ModelChoice::Pde32: return "pde32";
    case ModelChoice::Pde: return "pde";
    case ModelChoice::None: break;
  }
  return "none";
}

const char* profile_name(Profile profile) { return profile == Profile::Fast ? "fast" : "small"; }

nlohmann::json encode_summary_json(const EncodeFileJob& job, const EncodeReport& rep) {
  const EncodeOptions& eo = job.options;
  nlohmann::json j = {{"input", job.input},
                      {"output", job.output},
                      {"tolerance", eo.tolerance},
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
                      {"model", model_choice_name(eo.model)},
                      {"model_bytes", rep.model_bytes},
                      {"motions_fitted", rep.motions_fitted},
                      {"motions_kept", rep.motions_kept},
                      {"low_rank_components", rep.low_rank_components},
                      {"grid_refinement", rep.grid_refinement},
                      {"chunk_frames", rep.chunk_frames},
                      {"inbetween", inbetween_name(rep.inbetween)},
                      {"effort", eo.effort},
                      {"profile", profile_name(eo.profile)},
                      {"low_rank_bytes", rep.low_rank_bytes},
                      {"curve_fallback", rep.curve_fallback}};
  j.update(curve_report_json(rep.curves));
  return j;
}

}  // namespace dcurve::cli
