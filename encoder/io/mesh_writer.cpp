#include "encoder/io/mesh_writer.h"

#include <charconv>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace dcurve {
namespace {

// Appends x as the shortest decimal that parses back to exactly x.
void append_float(std::string* out, float x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out->append(buf, r.ptr);
}

void append_vertices(std::string* out, const char* prefix, const float* xyz, uint32_t vertex_count) {
  for (size_t i = 0; i < size_t(vertex_count) * 3; i += 3) {
    out->append(prefix);
    for (int a = 0; a < 3; ++a) {
      if (a) out->push_back(' ');
      append_float(out, xyz[i + a]);
    }
    out->push_back('\n');
  }
}

void append_triangles(std::string* out, const char* prefix, uint32_t first_id, const std::vector<uint32_t>& faces) {
  for (size_t t = 0; t + 2 < faces.size(); t += 3) {
    out->append(prefix);
    for (int k = 0; k < 3; ++k) {
      if (k) out->push_back(' ');
      out->append(std::to_string(faces[t + k] + first_id));
    }
    out->push_back('\n');
  }
}

template <typename T>
void append_binary(std::string* out, T value) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));  // dcurve's targets are little-endian, as the header says
  out->append(b, sizeof(T));
}

void ply_bytes(const float* xyz, uint32_t vertex_count, const std::vector<uint32_t>& faces, std::string* out) {
  *out = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertex_count) +
         "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces.size() / 3) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
  out->append(reinterpret_cast<const char*>(xyz), size_t(vertex_count) * 3 * sizeof(float));
  for (size_t t = 0; t + 2 < faces.size(); t += 3) {
    append_binary<uint8_t>(out, 3);
    for (int k = 0; k < 3; ++k) append_binary<int32_t>(out, int32_t(faces[t + k]));
  }
}

// A name (usemtl, mtllib) kept on its line: OBJ has no escapes, and a newline in a name would
// start records of its own (vertices that shift every face index), so each control character
// is written as \xNN.
std::string obj_name(const std::string& name) {
  std::string out;
  for (const unsigned char c : name) {
    if (c >= 0x20 && c != 0x7f) {
      out.push_back(char(c));
      continue;
    }
    char buf[8];
    std::snprintf(buf, sizeof buf, "\\x%02x", c);
    out += buf;
  }
  return out;
}

void append_corner(std::string* out, uint32_t vertex, uint32_t render, bool uv, bool normal) {
  out->append(std::to_string(vertex + 1));
  if (uv || normal) out->push_back('/');
  if (uv) out->append(std::to_string(render + 1));
  if (normal) out->append("/" + std::to_string(render + 1));
}

}  // namespace

void obj_render_bytes(const float* xyz, uint32_t vertex_count, const ObjRender& r, const float* normals,
                      std::string* bytes) {
  bytes->clear();
  if (!r.material_library.empty()) bytes->append("mtllib " + obj_name(r.material_library) + "\n");
  append_vertices(bytes, "v ", xyz, vertex_count);
  for (size_t i = 0; i < r.uv.size(); i += 2) {
    bytes->append("vt ");
    append_float(bytes, r.uv[i]);
    bytes->push_back(' ');
    append_float(bytes, 1.f - r.uv[i + 1]);  // OBJ's v runs up the image
    bytes->push_back('\n');
  }
  if (normals) append_vertices(bytes, "vn ", normals, uint32_t(r.source.size()));
  const std::vector<uint32_t> one_group = {uint32_t(r.corners.size() / 3)};
  const std::vector<uint32_t>& groups = r.group_faces.empty() ? one_group : r.group_faces;
  size_t t = 0;
  for (size_t g = 0; g < groups.size(); ++g) {
    if (g < r.group_names.size() && !r.group_names[g].empty()) bytes->append("usemtl " + obj_name(r.group_names[g]) + "\n");
    for (uint32_t end = uint32_t(t) + groups[g]; t < end; ++t) {
      bytes->append("f");
      for (int k = 0; k < 3; ++k) {
        const uint32_t id = r.corners[3 * t + k];
        bytes->push_back(' ');
        append_corner(bytes, r.source[id], id, !r.uv.empty(), normals != nullptr);
      }
      bytes->push_back('\n');
    }
  }
}

bool mesh_file_bytes(const std::string& extension, const float* xyz, uint32_t vertex_count,
                     const std::vector<uint32_t>& faces, std::string* bytes) {
  const std::string& ext = extension;
  bytes->clear();
  if (ext == ".obj") {
    append_vertices(bytes, "v ", xyz, vertex_count);
    append_triangles(bytes, "f ", 1, faces);
  } else if (ext == ".off") {
    *bytes = "OFF\n" + std::to_string(vertex_count) + " " + std::to_string(faces.size() / 3) + " 0\n";
    append_vertices(bytes, "", xyz, vertex_count);
    append_triangles(bytes, "3 ", 0, faces);
  } else if (ext == ".ply") {
    ply_bytes(xyz, vertex_count, faces, bytes);
  } else {
    return false;
  }
  return true;
}

}  // namespace dcurve
