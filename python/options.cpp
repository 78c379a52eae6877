#include "python/options.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "codec/common/inbetween.h"
#include "codec/common/render_mesh.h"
#include "encoder/io/frame_times.h"
#include "python/error.h"

namespace py = pybind11;

namespace dcurve::python {
namespace {

std::string shown(py::handle value) { return py::repr(value).cast<std::string>(); }

[[noreturn]] void refuse(const char* name, const std::string& what, py::handle value) {
  throw Error(std::string(name) + " must be " + what + ", got " + shown(value));
}

std::string range_text(double lo, double hi) {
  return "in [" + py::repr(py::float_(lo)).cast<std::string>() + ", " + py::repr(py::float_(hi)).cast<std::string>() + "]";
}

double number_in(py::handle value, const char* name, double lo, double hi) {
  if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)))
    refuse(name, "a number " + range_text(lo, hi), value);
  const double x = value.cast<double>();
  if (!(std::isfinite(x) && x >= lo && x <= hi)) refuse(name, "a number " + range_text(lo, hi), value);
  return x;
}

int64_t integer_in(py::handle value, const char* name, int64_t lo, int64_t hi) {
  const std::string what = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (py::isinstance<py::bool_>(value) || !py::isinstance<py::int_>(value)) refuse(name, what, value);
  const py::int_ lo_obj(lo), hi_obj(hi);
  if (value < lo_obj || value > hi_obj) refuse(name, what, value);
  return value.cast<int64_t>();
}

bool flag(py::handle value, const char* name) {
  if (!py::isinstance<py::bool_>(value)) refuse(name, "True or False", value);
  return value.cast<bool>();
}

bool is_text(py::handle value, const char* text) {
  return py::isinstance<py::str>(value) && value.cast<std::string>() == text;
}

std::string choice(py::handle value, const char* name, const std::vector<std::string>& allowed) {
  std::string list;
  for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + ("'" + a + "'");
  if (py::isinstance<py::str>(value))
    for (const std::string& a : allowed)
      if (value.cast<std::string>() == a) return a;
  refuse(name, "one of " + list, value);
}

// "auto" (returned as `auto_value`) or an integer in [lo, hi].
int64_t auto_or_integer(py::handle value, const char* name, int64_t lo, int64_t hi, int64_t auto_value) {
  if (is_text(value, "auto")) return auto_value;
  if (py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value)) return integer_in(value, name, lo, hi);
  refuse(name, "'auto' or an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", value);
}

std::string path_text(py::handle value, const char* name) {
  if (!py::isinstance<py::str>(value) && !py::hasattr(value, "__fspath__")) refuse(name, "a path", value);
  return py::str(py::module_::import("os").attr("fsdecode")(value)).cast<std::string>();
}

// One keyword's setter and where it applies.
struct Option {
  void (*apply)(py::handle value, EncodeSettings* s);
  bool file_only;
};

void set_model(py::handle v, EncodeSettings* s) {
  const std::string m = choice(v, "model", {"none", "pde8", "pde32", "pde"});
  s->encode.model = m == "pde8" ? ModelChoice::Pde8 : m == "pde32" ? ModelChoice::Pde32 : m == "pde" ? ModelChoice::Pde : ModelChoice::None;
}

void set_low_rank(py::handle v, EncodeSettings* s) {
  s->encode.low_rank = is_text(v, "off") ? 0 : int(auto_or_integer(v, "low_rank", 1, 64, -1));
}

void set_grid(py::handle v, EncodeSettings* s) {
  s->encode.grid_refinement = is_text(v, "auto") ? 0.0 : number_in(v, "grid", 1.0, 16.0);
}

void set_inbetween(py::handle v, EncodeSettings* s) {
  const std::string name = choice(v, "inbetween", {"auto", "linear", "catmull-rom", "hermite4"});
  Inbetween rule;
  s->encode.inbetween = inbetween_from_name(name.c_str(), &rule) ? int(rule) : -1;
}

void set_resource_dirs(py::handle v, EncodeSettings* s) {
  std::vector<std::string>& dirs = s->input.limits.resource_dirs;
  dirs.clear();
  if (py::isinstance<py::str>(v) || py::hasattr(v, "__fspath__")) {
    dirs.push_back(path_text(v, "allow_resources_outside"));
    return;
  }
  if (!py::isinstance<py::sequence>(v)) refuse("allow_resources_outside", "a folder or a list of folders", v);
  for (py::handle item : v) dirs.push_back(path_text(item, "allow_resources_outside"));
}

const std::map<std::string, Option>& option_table() {
  static const std::map<std::string, Option> table = {
      {"tolerance", {[](py::handle v, EncodeSettings* s) { s->encode.tolerance = number_in(v, "tolerance", kMinTolerance, 0.5); }, false}},
      {"fps", {[](py::handle v, EncodeSettings* s) { s->input.fps = number_in(v, "fps", kMinFrameRate, kMaxFrameRate); }, false}},
      {"model", {set_model, false}},
      {"low_rank", {set_low_rank, false}},
      {"keep_all_motions", {[](py::handle v, EncodeSettings* s) { s->encode.keep_all_motions = flag(v, "keep_all_motions"); }, false}},
      {"segment_frames", {[](py::handle v, EncodeSettings* s) { s->encode.segment_frames = uint32_t(auto_or_integer(v, "segment_frames", 1, 100000, 0)); }, false}},
      {"grid", {set_grid, false}},
      {"effort", {[](py::handle v, EncodeSettings* s) { s->encode.effort = int(integer_in(v, "effort", kMinEffort, kMaxEffort)); }, false}},
      {"profile", {[](py::handle v, EncodeSettings* s) { s->encode.profile = choice(v, "profile", {"fast", "small"}) == "fast" ? Profile::Fast : Profile::Small; }, false}},
      {"chunk_frames", {[](py::handle v, EncodeSettings* s) { s->encode.chunk_frames = uint32_t(auto_or_integer(v, "chunk_frames", 1, kMaxChunkFrames, 0)); }, false}},
      {"inbetween", {set_inbetween, false}},
      {"curve_points", {[](py::handle v, EncodeSettings* s) { s->encode.curve_points = uint32_t(integer_in(v, "curve_points", 2, 1000000)); }, false}},
      {"keep_face_order", {[](py::handle v, EncodeSettings* s) { s->encode.exact_face_order = flag(v, "keep_face_order"); }, false}},
      {"no_connectivity", {[](py::handle v, EncodeSettings* s) { s->encode.connectivity = !flag(v, "no_connectivity"); }, false}},
      {"uv_bits", {[](py::handle v, EncodeSettings* s) { s->encode.attributes.texcoord_bits = uint8_t(integer_in(v, "uv_bits", 1, kMaxAttributeBits)); }, false}},
      {"threads", {[](py::handle v, EncodeSettings* s) { s->encode.threads = int(integer_in(v, "threads", 0, 4096)); }, false}},
      {"progress", {[](py::handle v, EncodeSettings* s) {
         if (!v.is_none() && !py::isinstance<py::function>(v) && !py::hasattr(v, "__call__")) refuse("progress", "a callable or None", v);
         s->progress = py::reinterpret_borrow<py::object>(v);
       }, false}},
      {"mesh", {[](py::handle v, EncodeSettings* s) { s->input.rest_mesh = path_text(v, "mesh"); }, true}},
      {"gltf_mesh", {[](py::handle v, EncodeSettings* s) { s->input.gltf_mesh = int(integer_in(v, "gltf_mesh", 0, INT32_MAX)); }, true}},
      {"max_memory", {[](py::handle v, EncodeSettings* s) { s->input.limits.max_memory = uint64_t(integer_in(v, "max_memory", int64_t(1) << 20, INT64_MAX)); }, true}},
      {"allow_resources_outside", {set_resource_dirs, true}},
      {"force", {[](py::handle v, EncodeSettings* s) { s->force = flag(v, "force"); }, true}},
  };
  return table;
}

}  // namespace

void apply_options(const py::dict& options, OptionScope scope, EncodeSettings* settings) {
  const std::map<std::string, Option>& table = option_table();
  for (auto item : options) {
    const std::string name = py::str(item.first).cast<std::string>();
    auto it = table.find(name);
    if (it == table.end() || (it->second.file_only && scope != OptionScope::File))
      throw py::type_error(std::string(scope == OptionScope::File ? "encode_file" : "encode") +
                           "() got an unexpected keyword argument '" + name + "'");
    it->second.apply(item.second, settings);
  }
}

}  // namespace dcurve::python
