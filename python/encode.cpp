#include "python/encode.h"

#include <pybind11/numpy.h>

#include <new>
#include <string>
#include <vector>

#include "cli/encode_job.h"
#include "encoder/encoder.h"
#include "encoder/io/frames.h"
#include "python/arrays.h"
#include "python/error.h"
#include "python/options.h"
#include "python/progress.h"

namespace py = pybind11;

namespace dcurve::python {
namespace {

// The keywords of an encode call: those describing the animation, and the options.
void split_keywords(const py::kwargs& kwargs, py::dict* animation, py::dict* options) {
  for (auto item : kwargs) {
    const std::string name = py::str(item.first).cast<std::string>();
    (is_animation_keyword(name) ? *animation : *options)[item.first] = item.second;
  }
}

// encode_animation without the GIL; an allocation failure is an error, as in the CLI.
bool encode_released(const Animation& anim, const EncodeOptions& eo, std::vector<uint8_t>* bytes, std::string* err) {
  py::gil_scoped_release released;
  EncodeReport report;
  try {
    return encode_animation(anim, eo, bytes, &report, err);
  } catch (const std::bad_alloc&) {
    *err = "out of memory while encoding";
    return false;
  }
}

py::bytes encode(py::handle frames, py::handle faces, const py::kwargs& kwargs) {
  py::dict animation_keywords, option_keywords;
  split_keywords(kwargs, &animation_keywords, &option_keywords);
  EncodeSettings settings;
  apply_options(option_keywords, OptionScope::Arrays, &settings);
  Animation anim;
  animation_from_arrays(frames, faces, animation_keywords, &anim);
  anim.frame_rate = settings.input.fps > 0 ? settings.input.fps : kFolderFrameRate;
  if (faces.is_none()) settings.encode.connectivity = false;
  PythonProgress progress(settings.progress);
  settings.encode.progress = progress.callback();
  std::vector<uint8_t> bytes;
  std::string err;
  const bool ok = encode_released(anim, settings.encode, &bytes, &err);
  progress.rethrow();
  if (!ok) throw Error(err);
  return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

// The job's notes, kept to be shown as Python warnings once the GIL is back.
cli::EncodeListener collecting_listener(std::vector<std::string>* notes, const std::function<void(double)>& progress) {
  cli::EncodeListener l;
  l.note = [notes](const std::string& m) { notes->push_back(m); };
  l.progress = [progress](const std::string& stage) { return stage == "encode" ? progress : std::function<void(double)>(); };
  return l;
}

py::dict encode_file(py::handle input, py::handle output, const py::kwargs& kwargs) {
  EncodeSettings settings;
  apply_options(kwargs, OptionScope::File, &settings);
  py::module_ os = py::module_::import("os");
  cli::EncodeFileJob job;
  job.input = py::str(os.attr("fsdecode")(input)).cast<std::string>();
  job.output = py::str(os.attr("fsdecode")(output)).cast<std::string>();
  job.input_options = settings.input;
  job.options = settings.encode;
  job.force = settings.force;
  PythonProgress progress(settings.progress);
  std::vector<std::string> notes;
  const cli::EncodeListener listener = collecting_listener(&notes, progress.callback());
  EncodeReport report;
  std::string err;
  bool ok;
  {
    py::gil_scoped_release released;
    ok = cli::run_encode_file(job, listener, &report, &err);
  }
  progress.rethrow();
  py::module_ warnings = py::module_::import("warnings");
  for (const std::string& note : notes) warnings.attr("warn")(note);
  if (!ok) throw Error(err);
  return py::module_::import("json").attr("loads")(cli::encode_summary_json(job, report).dump());
}

}  // namespace

void add_encode_functions(py::module_& m) {
  m.def("encode", &encode, py::arg("frames"), py::arg("faces") = py::none(),
        R"(Encodes an animation into the bytes of a .dcrv file.

frames: float32/float64 array (F, V, 3). faces: integer array (T, 3) or None (no
connectivity). Keywords: tolerance=1e-3 (max error, fraction of the rest pose's
bounding-box diagonal), fps=30.0, the CLI's encode options with underscores (model,
low_rank, keep_all_motions, segment_frames, grid, effort, profile, chunk_frames, inbetween,
curve_points, keep_face_order, no_connectivity, uv_bits, threads), progress (a callable
taking the fraction done), and what a renderer draws: uvs, normals, colors ((V, C) per
vertex or (T, 3, C) per corner), face_groups ((T,) ints) with group_names and materials
(a glTF-style {"materials": [...]}: group g uses material g), start_time (seconds),
matrix (4x4 world transform), mesh_name, node_name. The GIL is released while encoding.
Raises dcurve.Error with the message the CLI gives.)");
  m.def("encode_file", &encode_file, py::arg("input"), py::arg("output"),
        R"(Encodes anything `dcurve encode` reads (a folder of OBJ/PLY/OFF frames, a glTF,
a point cache with mesh=REST, a scene file) into the .dcrv file `output`, exactly as the CLI
does, and returns the dict `dcurve encode --json` prints. Keywords: the CLI's options with
underscores (tolerance, fps, mesh, gltf_mesh, max_memory, allow_resources_outside, force,
model, low_rank, ...) and progress. Notes the CLI prints become warnings.)");
}

}  // namespace dcurve::python
