#include "encoder/io/frames.h"

// OpenMesh 9 headers trip GCC 12's -Wmaybe-uninitialized on a default-constructed Vec3f.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/frame_order.h"
#include "encoder/io/text_mesh_check.h"

namespace dcurve {
namespace fs = std::filesystem;
namespace {

struct Traits : OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3f Point;
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;

// OpenMesh reports every file it writes on its log streams; a codec's CLI must stay quiet.
void silence_openmesh() {
  static const bool done = [] {
    ::omlog().disable();
    ::omout().disable();
    return true;
  }();
  (void)done;
}

}  // namespace

bool read_mesh(const std::string& path, std::vector<float>* xyz, std::vector<uint32_t>* faces,
               std::string* error) {
  silence_openmesh();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return fail(error, path + ": no such file");
  if (!check_text_mesh_vertices(path, error)) return false;
  Mesh mesh;
  OpenMesh::IO::Options opt;
  if (!OpenMesh::IO::read_mesh(mesh, path, opt))
    return fail(error, path + ": cannot read mesh (unsupported format or malformed file)");
  if (mesh.n_vertices() == 0) return fail(error, path + ": mesh has no vertices");
  xyz->resize(mesh.n_vertices() * 3);
  for (auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(p[a])) return fail(error, path + ": vertex " + std::to_string(vh.idx()) + " is not finite");
      (*xyz)[3 * vh.idx() + a] = p[a];
    }
  }
  faces->clear();
  faces->reserve(mesh.n_faces() * 3);
  for (auto fh : mesh.faces())
    for (auto vh : mesh.fv_range(fh)) faces->push_back(uint32_t(vh.idx()));
  return true;
}

bool write_mesh(const std::string& path, const float* xyz, uint32_t vertex_count,
                const std::vector<uint32_t>& faces, std::string* error) {
  silence_openmesh();
  Mesh mesh;
  mesh.reserve(vertex_count, faces.size(), faces.size() / 3);
  std::vector<Mesh::VertexHandle> vh(vertex_count);
  for (uint32_t v = 0; v < vertex_count; ++v)
    vh[v] = mesh.add_vertex(Mesh::Point(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]));
  for (size_t t = 0; t + 2 < faces.size(); t += 3) {
    auto fh = mesh.add_face(vh[faces[t]], vh[faces[t + 1]], vh[faces[t + 2]]);
    if (!fh.is_valid()) return fail(error, path + ": face " + std::to_string(t / 3) + " is non-manifold; OpenMesh cannot write it");
  }
  fs::path target(path);
  fs::path tmp = target;
  tmp += ".tmp" + lowercase_extension(target.string());  // OpenMesh picks the writer from the extension
  OpenMesh::IO::Options opt;
  if (lowercase_extension(target.string()) == ".ply") opt += OpenMesh::IO::Options::Binary;
  if (!OpenMesh::IO::write_mesh(mesh, tmp.string(), opt, 9)) {
    std::remove(tmp.c_str());
    return fail(error, path + ": cannot write mesh");
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    std::remove(tmp.c_str());
    return fail(error, path + ": cannot rename into place: " + ec.message());
  }
  return true;
}

bool validate_animation(const Animation& anim, std::string* error) {
  if (anim.frames.empty()) return fail(error, "animation has no frames");
  if (anim.vertex_count == 0) return fail(error, "mesh has no vertices");
  for (uint32_t idx : anim.faces)
    if (idx >= anim.vertex_count) return fail(error, "face index out of range");
  for (size_t f = 0; f < anim.frames.size(); ++f) {
    if (anim.frames[f].size() != size_t(anim.vertex_count) * 3)
      return fail(error, "frame " + std::to_string(f) + " has a different vertex count");
    for (float x : anim.frames[f])
      if (!std::isfinite(x)) return fail(error, "frame " + std::to_string(f) + " has a non-finite coordinate");
  }
  return true;
}

bool read_frame_folder(const std::string& dir, Animation* anim, std::string* error) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return fail(error, dir + ": not a folder");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    std::string ext = lowercase_extension(e.path().string());
    if (e.is_regular_file() && (ext == ".obj" || ext == ".ply" || ext == ".off")) files.push_back(e.path());
  }
  if (ec) return fail(error, dir + ": " + ec.message());
  if (files.empty()) return fail(error, dir + ": no .obj, .ply or .off frames found");
  if (!order_frame_files(&files, error)) return false;
  *anim = Animation{};
  for (size_t f = 0; f < files.size(); ++f) {
    std::vector<float> xyz;
    std::vector<uint32_t> faces;
    if (!read_mesh(files[f].string(), &xyz, &faces, error)) return false;
    if (f == 0) {
      anim->vertex_count = uint32_t(xyz.size() / 3);
      anim->faces = std::move(faces);
    } else if (xyz.size() != size_t(anim->vertex_count) * 3) {
      return fail(error, files[f].string() + ": " + std::to_string(xyz.size() / 3) + " vertices, frame 0 has " +
                             std::to_string(anim->vertex_count));
    } else if (faces != anim->faces) {
      return fail(error, files[f].string() + ": connectivity differs from frame 0");
    }
    anim->frames.push_back(std::move(xyz));
  }
  return true;
}

bool write_frame_folder(const std::string& dir, const Animation& anim, const std::string& ext,
                        std::string* error) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return fail(error, dir + ": cannot create folder: " + ec.message());
  char name[64];
  for (size_t f = 0; f < anim.frames.size(); ++f) {
    std::snprintf(name, sizeof name, "frame_%05zu.%s", f, ext.c_str());
    if (!write_mesh((fs::path(dir) / name).string(), anim.frames[f].data(), anim.vertex_count, anim.faces, error))
      return false;
  }
  return true;
}

}  // namespace dcurve
