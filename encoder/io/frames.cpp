#include "encoder/io/frames.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/output_file.h"
#include "encoder/io/output_folder.h"
#include "encoder/io/frame_order.h"
#include "encoder/io/mesh_writer.h"
#include "encoder/io/obj_corners.h"
#include "encoder/io/obj_reader.h"
#include "encoder/io/polygon_reader.h"
#include "encoder/io/text_mesh_check.h"

namespace dcurve {
namespace fs = std::filesystem;
namespace {

// What was read must be what the file declares: a reader that skipped a record it could not
// parse or use would otherwise shift ids or lose faces without a word.
bool counts_match(const std::string& path, const DeclaredCounts& declared, const PolygonSoup& soup,
                  std::string* error) {
  const size_t vertices = soup.xyz.size() / 3;
  if (declared.vertices >= 0 && size_t(declared.vertices) != vertices)
    return fail(error, path + ": " + std::to_string(declared.vertices) + " vertices in the file, " +
                           std::to_string(vertices) + " read (a record the reader could not parse)");
  if (declared.faces >= 0 && size_t(declared.faces) != soup.polygon_count())
    return fail(error, path + ": " + std::to_string(declared.faces) + " faces in the file, " +
                           std::to_string(soup.polygon_count()) +
                           " read (a face with an index out of range or a malformed face record)");
  return true;
}

// Checks polygon p (at least 3 ids, each in range, none twice) and appends it as a fan of
// triangles from its first vertex, as OpenMesh triangulates.
bool append_polygon(const std::string& path, const PolygonSoup& soup, size_t p, std::vector<uint32_t>* faces,
                    std::string* error) {
  const uint32_t* ids = soup.ids.data() + soup.polygon_offsets[p];
  const size_t n = soup.polygon_offsets[p + 1] - soup.polygon_offsets[p];
  const size_t vertices = soup.xyz.size() / 3;
  const std::string face = path + ": face " + std::to_string(p) + ": ";
  if (n < 3) return fail(error, face + "fewer than 3 vertices");
  for (size_t k = 0; k < n; ++k)
    if (ids[k] >= vertices) return fail(error, face + "vertex index out of range");
  if (face_repeats_vertex(ids, n)) return fail(error, face + "uses a vertex twice (degenerate face)");
  for (size_t k = 1; k + 1 < n; ++k) faces->insert(faces->end(), {ids[0], ids[k], ids[k + 1]});
  return true;
}

bool coordinate_in_range(float x) { return std::isfinite(x) && std::fabs(x) <= kMaxCoordinate; }

std::string coordinate_range_text() {
  char buf[48];
  std::snprintf(buf, sizeof buf, "finite and within +-%g", double(kMaxCoordinate));
  return buf;
}

bool copy_finite_vertices(const std::string& path, const PolygonSoup& soup, std::vector<float>* xyz,
                          std::string* error) {
  for (size_t i = 0; i < soup.xyz.size(); ++i)
    if (!coordinate_in_range(soup.xyz[i]))
      return fail(error, path + ": vertex " + std::to_string(i / 3) + ": a coordinate is not " + coordinate_range_text());
  *xyz = soup.xyz;
  return true;
}

// OFF and PLY through OpenMesh's readers, checked before (text_mesh_check) and after
// (counts_match): those readers open no other file.
bool read_openmesh_soup(const std::string& path, PolygonSoup* soup, std::string* error) {
  DeclaredCounts declared;
  return check_text_mesh_vertices(path, &declared, error) && read_polygon_soup(path, soup, error) &&
         counts_match(path, declared, *soup, error);
}

}  // namespace

bool read_mesh(const std::string& path, std::vector<float>* xyz, std::vector<uint32_t>* faces,
               std::string* error, ObjCorners* corners) {
  if (!check_input_file(path, error)) return false;
  const bool obj = lowercase_extension(path) == ".obj";
  ObjMesh mesh;
  if (obj ? !read_obj(path, &mesh, error) : !read_openmesh_soup(path, &mesh.soup, error)) return false;
  const PolygonSoup& soup = mesh.soup;
  if (soup.xyz.empty()) return fail(error, path + ": mesh has no vertices");
  faces->clear();
  for (size_t p = 0; p < soup.polygon_count(); ++p)
    if (!append_polygon(path, soup, p, faces, error)) return false;
  if (corners) *corners = std::move(mesh.corners);
  return copy_finite_vertices(path, soup, xyz, error);
}

bool write_mesh(const std::string& path, const float* xyz, uint32_t vertex_count,
                const std::vector<uint32_t>& faces, std::string* error, bool replace) {
  const size_t bad = find_degenerate_triangle(faces);
  if (bad != SIZE_MAX)
    return fail(error, path + ": triangle " + std::to_string(bad) + " uses a vertex twice; degenerate triangles are not written");
  std::string bytes;
  if (!mesh_file_bytes(lowercase_extension(path), xyz, vertex_count, faces, &bytes))
    return fail(error, path + ": cannot write mesh: the extension is not .obj, .off or .ply");
  OutputFile out;
  return out.open(path, replace, error) && out.write(bytes.data(), bytes.size(), error) && out.commit(error);
}

bool face_repeats_vertex(const uint32_t* ids, size_t n) {
  if (n > 16) {  // sorted, not pairwise: a polygon of 100,000 corners must not take 10^10 steps
    std::vector<uint32_t> sorted(ids, ids + n);
    std::sort(sorted.begin(), sorted.end());
    return std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end();
  }
  for (size_t k = 1; k < n; ++k)
    if (std::find(ids, ids + k, ids[k]) != ids + k) return true;
  return false;
}

size_t find_degenerate_triangle(const std::vector<uint32_t>& faces) {
  for (size_t t = 0; t + 2 < faces.size(); t += 3)
    if (face_repeats_vertex(faces.data() + t, 3)) return t / 3;
  return SIZE_MAX;
}

bool validate_animation(const Animation& anim, std::string* error) {
  if (anim.frames.empty()) return fail(error, "animation has no frames");
  if (anim.vertex_count == 0) return fail(error, "mesh has no vertices");
  for (uint32_t idx : anim.faces)
    if (idx >= anim.vertex_count) return fail(error, "face index out of range");
  const size_t bad = find_degenerate_triangle(anim.faces);
  if (bad != SIZE_MAX)
    return fail(error, "triangle " + std::to_string(bad) + " uses a vertex twice (a degenerate triangle, refused in every format)");
  for (size_t f = 0; f < anim.frames.size(); ++f) {
    if (anim.frames[f].size() != size_t(anim.vertex_count) * 3)
      return fail(error, "frame " + std::to_string(f) + " has a different vertex count");
    for (size_t i = 0; i < anim.frames[f].size(); ++i)
      if (!coordinate_in_range(anim.frames[f][i]))
        return fail(error, "frame " + std::to_string(f) + ", vertex " + std::to_string(i / 3) + ": a coordinate is not " +
                               coordinate_range_text());
  }
  return true;
}

bool list_frame_files(const std::string& dir, std::vector<std::string>* files, std::string* error,
                      long long* frame_step) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return fail(error, dir + ": not a folder");
  std::vector<fs::path> paths;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    std::string ext = lowercase_extension(e.path().string());
    if (e.is_regular_file() && (ext == ".obj" || ext == ".ply" || ext == ".off")) paths.push_back(e.path());
  }
  if (ec) return fail(error, dir + ": " + ec.message());
  if (paths.empty()) return fail(error, dir + ": no .obj, .ply or .off frames found");
  if (!order_frame_files(&paths, error, frame_step)) return false;
  files->assign(paths.begin(), paths.end());
  return true;
}

bool read_frame_folder(const std::string& dir, Animation* anim, std::string* error,
                       const std::function<void(double)>& progress) {
  std::vector<std::string> files;
  ObjCorners corners;
  long long step = 1;
  if (!list_frame_files(dir, &files, error, &step)) return false;
  *anim = Animation{};
  anim->frame_rate = kFolderFrameRate / double(step);
  for (size_t f = 0; f < files.size(); ++f) {
    std::vector<float> xyz;
    std::vector<uint32_t> faces;
    if (!read_mesh(files[f], &xyz, &faces, error, f == 0 ? &corners : nullptr)) return false;
    if (f == 0) {
      anim->vertex_count = uint32_t(xyz.size() / 3);
      anim->faces = std::move(faces);
    } else if (xyz.size() != size_t(anim->vertex_count) * 3) {
      return fail(error, files[f] + ": " + std::to_string(xyz.size() / 3) + " vertices, frame 0 has " +
                             std::to_string(anim->vertex_count));
    } else if (faces != anim->faces) {
      return fail(error, files[f] + ": connectivity differs from frame 0");
    }
    anim->frames.push_back(std::move(xyz));
    if (progress) progress(double(f + 1) / double(files.size()));
  }
  // An OBJ's UVs, normals and materials, as frame 0 gives them (they do not animate).
  return obj_render(corners, anim, error) || fail(error, files[0] + ": " + *error);
}

std::string frame_file_name(size_t index, const std::string& ext) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%05zu.%s", index, ext.c_str());
  return name;
}

bool write_folder_frame(OutputFolder* folder, size_t index, const std::string& ext, const float* xyz,
                        uint32_t vertex_count, const std::vector<uint32_t>& faces, std::string* error) {
  const std::string name = frame_file_name(index, ext);
  std::string bytes;
  if (!mesh_file_bytes(lowercase_extension(name), xyz, vertex_count, faces, &bytes))
    return fail(error, name + ": cannot write mesh: the extension is not .obj, .off or .ply");
  return folder->write_file(name, bytes.data(), bytes.size(), error);
}

bool write_frame_folder(const std::string& dir, const Animation& anim, const std::string& ext,
                        std::string* error) {
  OutputFolder out;
  if (!out.open(dir, true, error)) return false;
  for (size_t f = 0; f < anim.frames.size(); ++f)
    if (!write_folder_frame(&out, f, ext, anim.frames[f].data(), anim.vertex_count, anim.faces, error)) return false;
  return out.commit(error);
}

}  // namespace dcurve
