#include "python/arrays.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "python/error.h"
#include "python/render_input.h"

namespace py = pybind11;

namespace dcurve::python {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using IndexArray = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;

const char* const kAnimationKeywords[] = {"uvs", "normals", "colors", "face_groups", "group_names", "materials",
                                          "start_time", "matrix", "mesh_name", "node_name"};

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// `value` as a numpy array whose dtype is of `kinds` ("f": floats, "iu": integers).
py::array as_array(py::handle value, const char* name, const char* kinds, const char* kind_text) {
  py::array a = py::module_::import("numpy").attr("asarray")(value);
  const char kind = a.dtype().kind();
  if (std::string(kinds).find(kind) == std::string::npos)
    throw Error(std::string(name) + ": " + kind_text + " expected, got dtype " + py::str(a.dtype()).cast<std::string>());
  return a;
}

void check_finite(const FloatArray& a, const char* name) {
  const float* p = a.data();
  for (py::ssize_t i = 0; i < a.size(); ++i)
    if (!std::isfinite(p[i])) throw Error(std::string(name) + ": entry " + std::to_string(i) + " is not finite");
}

void read_frames(py::handle frames, Animation* anim) {
  py::array a = as_array(frames, "frames", "f", "float32 or float64 values");
  if (a.ndim() != 3 || a.shape(2) != 3 || a.shape(0) < 1 || a.shape(1) < 1 || a.shape(1) > py::ssize_t(UINT32_MAX))
    throw Error("frames: shape (frames, vertices, 3) expected with at least one of each, got " + shape_text(a));
  // Float64 beyond float32's range becomes infinite here and is refused by the encoder.
  FloatArray f = FloatArray::ensure(a);
  anim->vertex_count = uint32_t(f.shape(1));
  const size_t per_frame = size_t(f.shape(1)) * 3;
  anim->frames.resize(size_t(f.shape(0)));
  for (size_t i = 0; i < anim->frames.size(); ++i) anim->frames[i].assign(f.data() + i * per_frame, f.data() + (i + 1) * per_frame);
}

void read_faces(py::handle faces, Animation* anim) {
  py::array a = as_array(faces, "faces", "iu", "integer vertex ids");
  if (a.ndim() != 2 || a.shape(1) != 3) throw Error("faces: shape (triangles, 3) expected, got " + shape_text(a));
  IndexArray ids = IndexArray::ensure(a);
  anim->faces.resize(size_t(ids.size()));
  for (py::ssize_t i = 0; i < ids.size(); ++i) {
    const int64_t v = ids.data()[i];
    if (v < 0 || v >= int64_t(anim->vertex_count))
      throw Error("faces[" + std::to_string(i / 3) + ", " + std::to_string(i % 3) + "] = " + std::to_string(v) +
                  " is out of range for " + std::to_string(anim->vertex_count) + " vertices");
    anim->faces[size_t(i)] = uint32_t(v);
  }
}

// An attribute given per vertex (V, C) or per corner (T, 3, C), as per-corner values.
CornerAttribute corner_attribute(py::handle value, const char* name, AttributeSemantic semantic, const Animation& anim) {
  py::array a = as_array(value, name, "f", "float values");
  const size_t triangles = anim.faces.size() / 3;
  const bool per_vertex = a.ndim() == 2 && a.shape(0) == py::ssize_t(anim.vertex_count);
  const bool per_corner = a.ndim() == 3 && a.shape(0) == py::ssize_t(triangles) && a.shape(1) == 3;
  const uint32_t components = a.ndim() >= 2 ? uint32_t(a.shape(a.ndim() - 1)) : 0;
  if (!(per_vertex || per_corner) || !attribute_components_allowed(semantic, components))
    throw Error(std::string(name) + ": shape (vertices, C) or (triangles, 3, C) expected with " +
                std::to_string(anim.vertex_count) + " vertices and " + std::to_string(triangles) +
                " triangles (C: 2 for uvs, 3 for normals, 3 or 4 for colors), got " + shape_text(a));
  FloatArray f = FloatArray::ensure(a);
  check_finite(f, name);
  CornerAttribute out{semantic, components, {}};
  out.values.reserve(anim.faces.size() * components);
  for (size_t k = 0; k < anim.faces.size(); ++k) {
    const float* from = f.data() + (per_vertex ? anim.faces[k] : k) * components;
    out.values.insert(out.values.end(), from, from + components);
  }
  return out;
}

std::vector<CornerAttribute> read_attributes(const py::dict& kw, const Animation& anim) {
  struct Named {
    const char* name;
    AttributeSemantic semantic;
  };
  const Named named[] = {{"uvs", AttributeSemantic::TexCoord0}, {"colors", AttributeSemantic::Color0},
                         {"normals", AttributeSemantic::Normal}};
  std::vector<CornerAttribute> out;
  for (const Named& n : named)
    if (kw.contains(n.name) && !kw[n.name].is_none()) out.push_back(corner_attribute(kw[n.name], n.name, n.semantic, anim));
  return out;
}

// The materials as the JSON text MATL stores, and how many "materials" it lists.
std::string materials_text(py::handle value, size_t* count) {
  py::module_ json = py::module_::import("json");
  py::object doc = py::reinterpret_borrow<py::object>(value);
  try {
    if (py::isinstance<py::str>(value)) doc = json.attr("loads")(value);
  } catch (const py::error_already_set& e) {
    throw Error(std::string("materials: not JSON: ") + e.what());
  }
  if (!py::isinstance<py::dict>(doc)) throw Error("materials: a dict (or JSON text) like {\"materials\": [...]} expected");
  const py::dict d = doc.cast<py::dict>();
  *count = d.contains("materials") && py::isinstance<py::list>(d["materials"]) ? py::len(d["materials"]) : 0;
  return json.attr("dumps")(doc).cast<std::string>();
}

std::vector<std::string> group_names(const py::dict& kw) {
  if (!kw.contains("group_names") || kw["group_names"].is_none()) return {};
  try {
    return kw["group_names"].cast<std::vector<std::string>>();
  } catch (const py::cast_error&) {
    throw Error("group_names: a list of str expected, got " + py::repr(kw["group_names"]).cast<std::string>());
  }
}

// Face groups: per triangle a group in [0, G), G the number of names; group g draws with
// material g of `materials` when it lists one.
void read_groups(const py::dict& kw, Animation* anim) {
  size_t material_count = 0;
  if (kw.contains("materials") && !kw["materials"].is_none()) anim->materials.json = materials_text(kw["materials"], &material_count);
  if (!kw.contains("face_groups") || kw["face_groups"].is_none()) return;
  py::array a = as_array(kw["face_groups"], "face_groups", "iu", "integer group ids");
  const size_t triangles = anim->faces.size() / 3;
  if (a.ndim() != 1 || a.shape(0) != py::ssize_t(triangles))
    throw Error("face_groups: shape (" + std::to_string(triangles) + ",) expected, one group per triangle, got " + shape_text(a));
  const std::vector<std::string> names = group_names(kw);
  IndexArray ids = IndexArray::ensure(a);
  int64_t groups = int64_t(names.size());
  for (py::ssize_t t = 0; t < ids.size() && names.empty(); ++t) groups = std::max(groups, ids.data()[t] + 1);
  for (py::ssize_t t = 0; t < ids.size(); ++t) {
    if (ids.data()[t] < 0 || ids.data()[t] >= groups)
      throw Error("face_groups[" + std::to_string(t) + "] = " + std::to_string(ids.data()[t]) + " is out of range for " +
                  std::to_string(groups) + " groups");
    anim->render.face_group.push_back(uint32_t(ids.data()[t]));
  }
  for (int64_t g = 0; g < groups; ++g)
    anim->render.groups.push_back({size_t(g) < material_count ? int32_t(g) : -1, size_t(g) < names.size() ? names[size_t(g)] : ""});
}

std::string text_keyword(const py::dict& kw, const char* name) {
  if (!kw.contains(name)) return "";
  if (!py::isinstance<py::str>(kw[name])) throw Error(std::string(name) + ": a str expected");
  return kw[name].cast<std::string>();
}

void read_placement(const py::dict& kw, Placement* p) {
  if (kw.contains("start_time")) {
    const py::handle t = kw["start_time"];
    const bool number = (py::isinstance<py::float_>(t) || py::isinstance<py::int_>(t)) && !py::isinstance<py::bool_>(t);
    if (!number || !std::isfinite(t.cast<double>())) throw Error("start_time: a finite number of seconds expected");
    p->start_time = t.cast<double>();
  }
  if (kw.contains("matrix") && !kw["matrix"].is_none()) {
    py::array a = as_array(kw["matrix"], "matrix", "fiu", "numbers");
    if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4) throw Error("matrix: shape (4, 4) expected, got " + shape_text(a));
    py::array_t<double, py::array::c_style | py::array::forcecast> m(a);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) {
        p->matrix[c * 4 + r] = m.at(r, c);  // rows as numpy writes them; PLAC is column-major
        if (!std::isfinite(p->matrix[c * 4 + r])) throw Error("matrix: entries must be finite");
      }
    p->has_matrix = true;
  }
  p->mesh_name = text_keyword(kw, "mesh_name");
  p->node_name = text_keyword(kw, "node_name");
}

}  // namespace

bool is_animation_keyword(const std::string& name) {
  for (const char* k : kAnimationKeywords)
    if (name == k) return true;
  return false;
}

void animation_from_arrays(py::handle frames, py::handle faces, const py::dict& kw, Animation* anim) {
  read_frames(frames, anim);
  if (!faces.is_none()) read_faces(faces, anim);
  const std::vector<CornerAttribute> attributes = read_attributes(kw, *anim);
  const bool grouped = kw.contains("face_groups") && !kw["face_groups"].is_none();
  if ((!attributes.empty() || grouped) && anim->faces.empty()) throw Error("uvs, normals, colors and face_groups need faces");
  read_groups(kw, anim);
  if (!attributes.empty() || grouped) weld_corner_attributes(anim->faces, anim->vertex_count, attributes, &anim->render);
  read_placement(kw, &anim->placement);
}

}  // namespace dcurve::python
