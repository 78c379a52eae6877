#include "cli/decode_output.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "cli/staging_dir.h"
#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/frames.h"
#include "encoder/io/gltf_writer.h"
#include "encoder/io/point_cache.h"

namespace dcurve::cli {
namespace fs = std::filesystem;
namespace {

bool is_mesh_extension(const std::string& ext) { return ext == ".obj" || ext == ".ply" || ext == ".off"; }

std::string parent_folder(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? "." : parent.string();
}

}  // namespace

bool check_output_file(const std::string& path, std::string* error) {
  std::error_code ec;
  if (!fs::is_directory(parent_folder(path), ec)) return fail(error, path + ": folder " + parent_folder(path) + " does not exist");
  if (fs::is_directory(path, ec) ) return fail(error, path + ": is a folder, not a file");
  return true;
}

namespace {

// One mesh, written atomically by write_mesh.
class MeshSink : public FrameSink {
 public:
  explicit MeshSink(const OutputSpec& spec) : spec_(spec) {}
  bool add(uint32_t, const float* xyz, std::string*) override {
    xyz_.assign(xyz, xyz + size_t(spec_.vertex_count) * 3);
    return true;
  }
  bool finish(std::string* error) override {
    return write_mesh(spec_.path, xyz_.data(), spec_.vertex_count, spec_.faces, error);
  }

 private:
  OutputSpec spec_;
  std::vector<float> xyz_;
};

class GltfSink : public FrameSink {
 public:
  explicit GltfSink(const OutputSpec& spec)
      : path_(spec.path), writer_(spec.vertex_count, spec.faces, spec.frame_count, spec.frame_rate) {}
  bool add(uint32_t, const float* xyz, std::string*) override {
    writer_.add_frame(xyz);
    return true;
  }
  bool finish(std::string* error) override { return writer_.write(path_, error); }

 private:
  std::string path_;
  GltfWriter writer_;
};

// Streams into a file in a staging folder, renamed into place at the end.
class PointCacheSink : public FrameSink {
 public:
  ~PointCacheSink() override {
    if (file_) std::fclose(file_);
  }
  bool open(const OutputSpec& spec, std::string* error) {
    path_ = spec.path;
    PointCacheKind kind = PointCacheKind::Pc2;
    point_cache_kind(path_, &kind);
    if (!staging_.create(parent_folder(path_), error)) return false;
    staged_ = (fs::path(staging_.path()) / fs::path(path_).filename()).string();
    file_ = std::fopen(staged_.c_str(), "wb");
    if (!file_) return fail(error, path_ + ": cannot write: " + std::strerror(errno));
    writer_ = std::make_unique<PointCacheWriter>(kind, file_, spec.vertex_count);
    return writer_->write_header(spec.frame_count, spec.frame_rate > 0 ? spec.frame_rate : 30.0) ||
           fail(error, path_ + ": write failed: " + std::strerror(errno));
  }
  bool add(uint32_t, const float* xyz, std::string* error) override {
    return writer_->write_frame(xyz) || fail(error, path_ + ": write failed: " + std::strerror(errno));
  }
  bool finish(std::string* error) override {
    const bool closed = std::fclose(file_) == 0;
    file_ = nullptr;
    if (!closed) return fail(error, path_ + ": write failed: " + std::strerror(errno));
    std::error_code ec;
    fs::rename(staged_, path_, ec);
    return !ec || fail(error, path_ + ": cannot move into place: " + ec.message());
  }

 private:
  std::string path_, staged_;
  StagingDir staging_;
  std::FILE* file_ = nullptr;
  std::unique_ptr<PointCacheWriter> writer_;
};

// The mesh files a folder already holds.
std::vector<fs::path> mesh_files_in(const std::string& dir) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (is_mesh_extension(lowercase_extension(e.path().string()))) found.push_back(e.path());
  std::sort(found.begin(), found.end());  // the message names the first
  return found;
}

// Frames go into a staging folder beside the output; at the end the staging folder becomes
// the output folder, or (for an existing one) its files move in after the old frames go.
class FolderSink : public FrameSink {
 public:
  bool open(const OutputSpec& spec, std::string* error) {
    spec_ = spec;
    fs::path dir(spec.path);
    if (dir.filename().empty()) dir = dir.parent_path();  // "out/" names the folder "out"
    spec_.path = dir.string();
    std::error_code ec;
    exists_ = fs::exists(spec.path, ec);
    if (exists_ && !fs::is_directory(spec.path, ec)) return fail(error, spec.path + ": exists and is not a folder");
    old_ = exists_ ? mesh_files_in(spec.path) : std::vector<fs::path>{};
    if (!old_.empty() && !spec.force)
      return fail(error, spec.path + ": already holds frames (" + old_.front().filename().string() +
                             ", ...): choose another folder, or --force to replace its mesh files");
    std::string parent = exists_ ? spec_.path : parent_folder(spec_.path);
    if (!fs::is_directory(parent, ec)) return fail(error, spec.path + ": folder " + parent + " does not exist");
    return staging_.create(parent, error);
  }
  bool add(uint32_t index, const float* xyz, std::string* error) override {
    return write_mesh((fs::path(staging_.path()) / frame_name(index)).string(), xyz, spec_.vertex_count, spec_.faces,
                      error);
  }
  bool finish(std::string* error) override {
    if (!exists_) return staging_.move_to(spec_.path, error);
    std::error_code ec;
    for (const fs::path& f : old_)
      if (!fs::remove(f, ec) && ec) return fail(error, f.string() + ": cannot remove: " + ec.message());
    for (uint32_t i = 0; i < spec_.frame_count; ++i) {
      fs::rename(fs::path(staging_.path()) / frame_name(i), fs::path(spec_.path) / frame_name(i), ec);
      if (ec) return fail(error, spec_.path + ": cannot move " + frame_name(i) + " into place: " + ec.message());
    }
    return true;
  }

 private:
  std::string frame_name(uint32_t index) const {
    char name[64];
    std::snprintf(name, sizeof name, "frame_%05u.%s", index, spec_.folder_format.c_str());
    return name;
  }
  OutputSpec spec_;
  bool exists_ = false;
  std::vector<fs::path> old_;
  StagingDir staging_;
};

}  // namespace

OutputKind output_kind(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  if (is_mesh_extension(ext)) return OutputKind::Mesh;
  if (ext == ".glb" || ext == ".gltf") return OutputKind::Gltf;
  if (ext == ".pc2" || ext == ".mdd") return OutputKind::PointCache;
  return OutputKind::Folder;
}

std::unique_ptr<FrameSink> open_output(const OutputSpec& spec, std::string* error) {
  // The readers' rule (encoder/io/frames.h): no output holds a face they would refuse.
  if (const size_t bad = find_degenerate_triangle(spec.faces); bad != SIZE_MAX) {
    *error = spec.path + ": the file's triangle " + std::to_string(bad) +
             " uses a vertex twice; dcurve writes no degenerate triangle";
    return nullptr;
  }
  switch (output_kind(spec.path)) {
    case OutputKind::Mesh:
      if (!check_output_file(spec.path, error)) return nullptr;
      return std::make_unique<MeshSink>(spec);
    case OutputKind::Gltf:
      if (!check_output_file(spec.path, error)) return nullptr;
      if (!GltfWriter::check_size(spec.vertex_count, spec.faces.size(), spec.frame_count, error)) {
        *error = spec.path + ": " + *error;
        return nullptr;
      }
      return std::make_unique<GltfSink>(spec);
    case OutputKind::PointCache: {
      auto sink = std::make_unique<PointCacheSink>();
      if (!check_output_file(spec.path, error) || !sink->open(spec, error)) return nullptr;
      return sink;
    }
    case OutputKind::Folder: {
      auto sink = std::make_unique<FolderSink>();
      if (!sink->open(spec, error)) return nullptr;
      return sink;
    }
  }
  return nullptr;
}

}  // namespace dcurve::cli
