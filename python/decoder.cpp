#include "python/decoder.h"

#include <pybind11/numpy.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include "dcurve.hpp"
#include "python/error.h"

namespace py = pybind11;

namespace dcurve::python {
namespace {

using Floats = py::array_t<float, py::array::c_style>;
using Ids = py::array_t<uint32_t, py::array::c_style>;

// A numpy copy of `count` rows of `width` values at `data`, or None when `data` is null.
template <typename T>
py::object rows(const T* data, size_t count, size_t width) {
  if (!data) return py::none();
  py::array_t<T, py::array::c_style> a({py::ssize_t(count), py::ssize_t(width)});
  std::copy(data, data + count * width, a.mutable_data());
  return std::move(a);
}

std::unique_ptr<Decoder> open(py::handle source) {
  std::string err;
  std::unique_ptr<Decoder> dec;
  if (py::isinstance<py::str>(source) || py::hasattr(source, "__fspath__")) {
    const std::string path = py::str(py::module_::import("os").attr("fsdecode")(source)).cast<std::string>();
    py::gil_scoped_release released;
    dec = Decoder::open_file(path, &err);
  } else {
    if (!py::isinstance<py::bytes>(source) && !PyByteArray_Check(source.ptr()) && !PyMemoryView_Check(source.ptr()))
      throw py::type_error("Decoder: bytes, bytearray, memoryview or a path expected");
    const py::bytes data = py::module_::import("builtins").attr("bytes")(source);
    char* bytes = nullptr;
    py::ssize_t size = 0;
    PyBytes_AsStringAndSize(data.ptr(), &bytes, &size);
    py::gil_scoped_release released;
    dec = Decoder::open_memory(bytes, size_t(size), &err);
  }
  if (!dec) throw python::Error(err);
  return dec;
}

// One open file; frames are decoded without the GIL through the decoder's own cursor.
class PyDecoder {
 public:
  explicit PyDecoder(py::handle source) : dec_(open(source)) {}

  const Decoder& get() const { return *dec_; }

  Floats frame(int64_t i) const {
    const int64_t n = dec_->frame_count();
    if (i < -n || i >= n) throw py::index_error("frame " + std::to_string(i) + " out of range for " + std::to_string(n) + " frames");
    return decoded([this, i, n](float* out, dcurve::Error* e) { return dec_->evaluate_frame(uint32_t(i < 0 ? i + n : i), out, e); });
  }

  Floats evaluate(double t) const {
    if (!std::isfinite(t)) throw python::Error("evaluate: t must be a finite number in [0, 1]");
    return decoded([this, t](float* out, dcurve::Error* e) { return dec_->evaluate(t, out, e); });
  }

  Floats frames() const {
    const size_t v = dec_->vertex_count(), n = dec_->frame_count();
    Floats all({py::ssize_t(n), py::ssize_t(v), py::ssize_t(3)});
    float* out = all.mutable_data();
    dcurve::Error e;
    bool ok = true;
    {
      py::gil_scoped_release released;
      for (size_t f = 0; f < n && ok; ++f) ok = dec_->evaluate_frame(uint32_t(f), out + f * v * 3, &e);
    }
    if (!ok) throw python::Error(e.message);
    return all;
  }

  // Per-vertex results of the file's connectivity from positions `xyz` (V, 3).
  py::object normals(const py::array_t<float, py::array::c_style | py::array::forcecast>& xyz) const {
    check_positions(xyz);
    Floats n({py::ssize_t(dec_->vertex_count()), py::ssize_t(3)});
    if (!dec_->compute_normals(xyz.data(), n.mutable_data())) return py::none();
    return std::move(n);
  }

  Floats render_positions(const py::array_t<float, py::array::c_style | py::array::forcecast>& xyz) const {
    check_positions(xyz);
    Floats r({py::ssize_t(dec_->render_vertex_count()), py::ssize_t(3)});
    dec_->render_positions(xyz.data(), r.mutable_data());
    return r;
  }

  py::object render_source() const {
    const uint32_t* source = dec_->render_source();
    if (!source) return py::none();
    Ids out(py::ssize_t(dec_->render_vertex_count()));
    std::copy(source, source + dec_->render_vertex_count(), out.mutable_data());
    return std::move(out);
  }

  py::object attribute(Attribute a) const {
    return rows(dec_->attribute(a), dec_->render_vertex_count(), dec_->attribute_components(a));
  }

  py::list groups() const {
    py::list out;
    for (uint32_t i = 0; i < dec_->group_count(); ++i) {
      const Group g = dec_->group(i);
      py::dict d;
      d["first_face"] = g.first_face;
      d["face_count"] = g.face_count;
      d["material"] = g.material;
      d["name"] = g.name;
      out.append(d);
    }
    return out;
  }

  py::list images() const {
    py::list out;
    for (uint32_t i = 0; i < dec_->image_count(); ++i) {
      size_t size = 0;
      const uint8_t* data = dec_->image(i, &size);
      out.append(py::make_tuple(dec_->image_mime_type(i), py::bytes(reinterpret_cast<const char*>(data), size)));
    }
    return out;
  }

  py::object world_matrix() const {
    double m[16];
    if (!dec_->world_matrix(m)) return py::none();
    py::array_t<double> out({4, 4});
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) out.mutable_at(r, c) = m[c * 4 + r];  // column-major in the file
    return std::move(out);
  }

 private:
  template <typename Evaluate>
  Floats decoded(Evaluate evaluate) const {
    Floats out({py::ssize_t(dec_->vertex_count()), py::ssize_t(3)});
    float* data = out.mutable_data();
    dcurve::Error e;
    bool ok;
    {
      py::gil_scoped_release released;
      ok = evaluate(data, &e);
    }
    if (!ok) throw python::Error(e.message);
    return out;
  }

  void check_positions(const py::array& xyz) const {
    if (xyz.ndim() != 2 || xyz.shape(0) != py::ssize_t(dec_->vertex_count()) || xyz.shape(1) != 3)
      throw python::Error("positions of shape (" + std::to_string(dec_->vertex_count()) + ", 3) expected");
  }

  std::unique_ptr<Decoder> dec_;
};

const char* interpolation_name(Interpolation rule) {
  switch (rule) {
    case Interpolation::CatmullRom: return "catmull-rom";
    case Interpolation::Hermite4: return "hermite4";
    case Interpolation::Linear: break;
  }
  return "linear";
}

py::object faces_of(const Decoder& d, const uint32_t* ids) { return rows(ids, d.face_count(), 3); }

void add_counts(py::class_<PyDecoder>& c) {
  c.def_property_readonly("vertex_count", [](const PyDecoder& d) { return d.get().vertex_count(); })
      .def_property_readonly("frame_count", [](const PyDecoder& d) { return d.get().frame_count(); })
      .def_property_readonly("face_count", [](const PyDecoder& d) { return d.get().face_count(); })
      .def_property_readonly("frame_rate", [](const PyDecoder& d) { return d.get().frame_rate(); })
      .def_property_readonly("tolerance", [](const PyDecoder& d) { return d.get().tolerance(); })
      .def_property_readonly("rest_diagonal", [](const PyDecoder& d) { return d.get().rest_diagonal(); })
      .def_property_readonly("chunk_frames", [](const PyDecoder& d) { return d.get().chunk_frames(); })
      .def_property_readonly("interpolation", [](const PyDecoder& d) { return interpolation_name(d.get().interpolation()); })
      .def_property_readonly("memory_bytes", [](const PyDecoder& d) { return d.get().memory_bytes(); })
      .def("__len__", [](const PyDecoder& d) { return d.get().frame_count(); });
}

void add_frames(py::class_<PyDecoder>& c) {
  c.def("frame", &PyDecoder::frame, py::arg("i"), "Input frame i (negative counts from the end) as float32 (V, 3).")
      .def("evaluate", &PyDecoder::evaluate, py::arg("t"), "The mesh at time t in [0, 1] (clamped) as float32 (V, 3).")
      .def("frames", &PyDecoder::frames, "Every input frame as float32 (F, V, 3).")
      .def("normals", &PyDecoder::normals, py::arg("xyz"), "Unit vertex normals of positions (V, 3); None without faces.")
      .def_property_readonly("faces", [](const PyDecoder& d) { return faces_of(d.get(), d.get().faces()); },
                             "uint32 (T, 3) vertex ids, None without connectivity.");
}

void add_render(py::class_<PyDecoder>& c) {
  c.def_property_readonly("render_vertex_count", [](const PyDecoder& d) { return d.get().render_vertex_count(); })
      .def_property_readonly("render_source", [](const PyDecoder& d) { return d.render_source(); })
      .def_property_readonly("render_faces", [](const PyDecoder& d) { return faces_of(d.get(), d.get().render_faces()); })
      .def("render_positions", &PyDecoder::render_positions, py::arg("xyz"))
      .def_property_readonly("uvs", [](const PyDecoder& d) { return d.attribute(Attribute::TexCoord0); })
      .def_property_readonly("uvs1", [](const PyDecoder& d) { return d.attribute(Attribute::TexCoord1); })
      .def_property_readonly("colors", [](const PyDecoder& d) { return d.attribute(Attribute::Color0); })
      .def_property_readonly("vertex_normals", [](const PyDecoder& d) { return d.attribute(Attribute::Normal); },
                             "The input's normals per render vertex, None when it gave none.");
}

void add_materials(py::class_<PyDecoder>& c) {
  c.def_property_readonly("groups", &PyDecoder::groups, "Face groups: dicts of first_face, face_count, material, name.")
      .def_property_readonly("group_faces", [](const PyDecoder& d) { return faces_of(d.get(), d.get().group_faces()); })
      .def_property_readonly("materials_json", [](const PyDecoder& d) { return d.get().materials_json(); })
      .def_property_readonly("materials", [](const PyDecoder& d) {
        const std::string& j = d.get().materials_json();
        return j.empty() ? py::object(py::none()) : py::module_::import("json").attr("loads")(j);
      })
      .def_property_readonly("images", &PyDecoder::images, "(mime_type, bytes) per image of the materials.")
      .def_property_readonly("start_time", [](const PyDecoder& d) { return d.get().start_time(); })
      .def_property_readonly("world_matrix", &PyDecoder::world_matrix, "4x4 float64 (rows), None when the file has none.")
      .def_property_readonly("mesh_name", [](const PyDecoder& d) { return d.get().mesh_name(); })
      .def_property_readonly("node_name", [](const PyDecoder& d) { return d.get().node_name(); });
}

}  // namespace

void add_decoder_class(py::module_& m) {
  py::class_<PyDecoder> c(m, "Decoder", "A .dcrv file opened from bytes (bytes, bytearray, memoryview) or a path.");
  c.def(py::init<py::handle>(), py::arg("data"));
  add_counts(c);
  add_frames(c);
  add_render(c);
  add_materials(c);
}

}  // namespace dcurve::python
