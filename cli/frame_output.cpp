#include "cli/frame_output.h"

#include <cstdint>
#include <string>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/frames.h"
#include "encoder/io/gltf_writer.h"
#include "encoder/io/mesh_writer.h"
#include "encoder/io/output_file.h"
#include "encoder/io/output_folder.h"
#include "encoder/io/point_cache.h"

namespace dcurve::cli {
namespace {

// An OBJ with the file's render data (UVs, normals, groups), when it has some.
bool with_render(const OutputSpec& spec, const std::string& ext) { return ext == ".obj" && !spec.obj.empty(); }

// One mesh, written when its frame is complete.
class MeshSink : public FrameSink {
 public:
  explicit MeshSink(const OutputSpec& spec) : spec_(spec) {}
  bool add(uint32_t, const float* xyz, const float* normals, std::string*) override {
    xyz_.assign(xyz, xyz + size_t(spec_.vertex_count) * 3);
    if (normals) normals_.assign(normals, normals + 3 * spec_.obj.source.size());
    return true;
  }
  bool finish(std::string* error) override {
    if (!with_render(spec_, lowercase_extension(spec_.path)))
      return write_mesh(spec_.path, xyz_.data(), spec_.vertex_count, spec_.faces, error, spec_.force);
    std::string bytes;
    obj_render_bytes(xyz_.data(), spec_.vertex_count, spec_.obj, normals_.empty() ? nullptr : normals_.data(), &bytes);
    OutputFile out;
    return out.open(spec_.path, spec_.force, error) && out.write(bytes.data(), bytes.size(), error) && out.commit(error);
  }

 private:
  OutputSpec spec_;
  std::vector<float> xyz_, normals_;
};

class GltfSink : public FrameSink {
 public:
  explicit GltfSink(const OutputSpec& spec)
      : writer_(spec.vertex_count, spec.faces, spec.frame_count, spec.frame_rate, lowercase_extension(spec.path) == ".glb",
                spec.gltf) {}
  bool open(const OutputSpec& spec, std::string* error) { return writer_.open(spec.path, spec.force, error); }
  bool add(uint32_t, const float* xyz, const float* normals, std::string* error) override {
    return writer_.add_frame(xyz, error, normals);
  }
  bool finish(std::string* error) override { return writer_.finish(error); }

 private:
  GltfWriter writer_;
};

class PointCacheSink : public FrameSink {
 public:
  bool open(const OutputSpec& spec, std::string* error) {
    PointCacheKind kind = PointCacheKind::Pc2;
    point_cache_kind(spec.path, &kind);
    if (!file_.open(spec.path, spec.force, error)) return false;
    writer_ = std::make_unique<PointCacheWriter>(kind, &file_, spec.vertex_count);
    return writer_->write_header(spec.frame_count, spec.frame_rate > 0 ? spec.frame_rate : 30.0, spec.start_time, error);
  }
  bool add(uint32_t, const float* xyz, const float*, std::string* error) override { return writer_->write_frame(xyz, error); }
  bool finish(std::string* error) override { return file_.commit(error); }

 private:
  OutputFile file_;
  std::unique_ptr<PointCacheWriter> writer_;
};

class FolderSink : public FrameSink {
 public:
  bool open(const OutputSpec& spec, std::string* error) {
    spec_ = spec;
    return folder_.open(spec.path, spec.force, error);
  }
  bool add(uint32_t index, const float* xyz, const float* normals, std::string* error) override {
    if (with_render(spec_, "." + spec_.folder_format)) {
      std::string bytes;
      obj_render_bytes(xyz, spec_.vertex_count, spec_.obj, normals, &bytes);
      return folder_.write_file(frame_file_name(index, spec_.folder_format), bytes.data(), bytes.size(), error);
    }
    return write_folder_frame(&folder_, index, spec_.folder_format, xyz, spec_.vertex_count, spec_.faces, error);
  }
  bool finish(std::string* error) override { return folder_.commit(error); }

 private:
  OutputSpec spec_;
  OutputFolder folder_;
};

template <class Sink>
std::unique_ptr<FrameSink> opened(std::unique_ptr<Sink> sink, const OutputSpec& spec, std::string* error) {
  if (!sink->open(spec, error)) return nullptr;
  return sink;
}

}  // namespace

std::unique_ptr<FrameSink> open_output(const OutputSpec& spec, std::string* error) {
  // The readers' rule (encoder/io/frames.h): no output holds a face they would refuse.
  if (const size_t bad = find_degenerate_triangle(spec.faces); bad != SIZE_MAX) {
    *error = spec.path + ": the file's triangle " + std::to_string(bad) +
             " uses a vertex twice; dcurve writes no degenerate triangle";
    return nullptr;
  }
  if (spec.kind != OutputKind::Folder && !check_output_file(spec.path, spec.force, spec.inputs, error)) return nullptr;
  switch (spec.kind) {
    case OutputKind::Mesh:
      return std::make_unique<MeshSink>(spec);
    case OutputKind::Gltf:
      return opened(std::make_unique<GltfSink>(spec), spec, error);
    case OutputKind::PointCache:
      return opened(std::make_unique<PointCacheSink>(), spec, error);
    case OutputKind::Folder:
      return opened(std::make_unique<FolderSink>(), spec, error);
    case OutputKind::Dcrv:
      break;
  }
  fail(error, spec.path + ": not a frame output");
  return nullptr;
}

}  // namespace dcurve::cli
