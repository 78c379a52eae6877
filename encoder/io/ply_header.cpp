#include "encoder/io/ply_header.h"

#include <algorithm>
#include <sstream>
#include <utility>

#include "codec/common/error.h"

namespace dcurve {
namespace {

// Bytes of a PLY scalar type; 0 for a name that is not one (or a real type when integer_only).
int ply_type_bytes(const std::string& t, bool integer_only = false) {
  static const std::pair<const char*, int> kTypes[] = {
      {"char", 1},  {"uchar", 1}, {"int8", 1},  {"uint8", 1},   {"short", 2},   {"ushort", 2},
      {"int16", 2}, {"uint16", 2}, {"int", 4},  {"uint", 4},    {"int32", 4},   {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (const auto& [name, bytes] : kTypes)
    if (t == name) return integer_only && (t[0] == 'f' || t[0] == 'd') ? 0 : bytes;
  return 0;
}

// One property line; false when malformed or before any element.
bool ply_property(std::istringstream& s, PlyHeader* h) {
  std::string a, b, c, name, rest;
  if (h->elements.empty() || !(s >> a >> b)) return false;
  const bool list = a == "list";
  const int bytes = list ? ply_type_bytes(b, true) : ply_type_bytes(a);
  if (bytes == 0 || (list && (!(s >> c >> name) || ply_type_bytes(c, true) == 0)) || s >> rest) return false;
  h->wide_list_count = h->wide_list_count || (list && bytes > 2);
  h->elements.back().min_bytes += bytes;
  if (h->elements.back().name == "vertex") h->vertex_properties.push_back(list ? name : b);
  return true;
}

// One header line after "ply"; false when it is not one PLY allows (OpenMesh's PLY reader
// crashes on some, e.g. a property before any element).
bool ply_header_line(std::istringstream& s, const std::string& word, PlyHeader* h) {
  std::string a, b;
  if (word == "comment" || word == "obj_info") return true;
  if (word == "format") {
    if (!(s >> a >> b) || b != "1.0") return false;
    h->ascii = a == "ascii";
    return h->ascii || a == "binary_little_endian" || a == "binary_big_endian";
  }
  if (word != "element") return word == "property" && ply_property(s, h);
  if (!(s >> a >> b) || b.empty() || b.size() > 10 || b.find_first_not_of("0123456789") != std::string::npos)
    return false;
  for (const PlyElement& e : h->elements)
    if (e.name == a) return false;  // a second "vertex" element: which one is the mesh's?
  h->elements.push_back({a, std::stoll(b), 0});
  return h->elements.back().count <= 0x7fffffff;
}

}  // namespace

bool read_ply_header(std::ifstream& in, const std::string& path, PlyHeader* h, size_t* number, std::string* error) {
  std::string line, word;
  for (*number = 0; std::getline(in, line);) {
    ++*number;
    std::istringstream s(line);
    if (!(s >> word) && *number > 1) continue;
    if (*number == 1) {
      if (word != "ply") return fail(error, path + ": not a PLY file (no \"ply\" line)");
      continue;
    }
    if (word == "end_header") {
      for (const char* axis : {"x", "y", "z"})
        if (std::find(h->vertex_properties.begin(), h->vertex_properties.end(), axis) == h->vertex_properties.end())
          return fail(error, path + ": the PLY vertex element has no " + axis + " property");
      return true;
    }
    if (!ply_header_line(s, word, h)) return fail(error, path + ": line " + std::to_string(*number) + ": malformed PLY header");
  }
  return fail(error, path + ": the PLY header has no end_header");
}

bool binary_ply_fits(std::ifstream& in, const PlyHeader& h) {
  const std::streamoff body = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  long long need = 0;
  for (const PlyElement& e : h.elements) need += e.count * std::max(e.min_bytes, 1LL);
  return body >= 0 && need <= size - body;
}

}  // namespace dcurve
