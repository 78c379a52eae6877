#include "encoder/io/text_mesh_check.h"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/ply_header.h"

namespace dcurve {
namespace {

// A hexadecimal float ("0x1p-1"): strtod takes it, OpenMesh's stream readers do not.
bool hexadecimal(const char* p) {
  if (*p == '+' || *p == '-') ++p;
  return p[0] == '0' && (p[1] == 'x' || p[1] == 'X');
}

// Parses up to `count` numbers from `p` (all the remaining ones when count < 0): false when
// one is missing or not a finite decimal value within float range.
bool finite_numbers(const char* p, int count) {
  for (int k = 0; count < 0 || k < count; ++k) {
    while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
    if (count < 0 && *p == '\0') return true;
    if (hexadecimal(p)) return false;
    char* end = nullptr;
    const double x = std::strtod(p, &end);
    if (end == p || !(std::fabs(x) <= double(FLT_MAX))) return false;
    p = end;
  }
  return true;
}

bool bad_record(const std::string& path, size_t line, std::string* error) {
  return fail(error, path + ": line " + std::to_string(line) + ": vertex values are not finite numbers within float range");
}

// Next line that is neither blank nor a comment; false at the end of the file.
bool next_content_line(std::ifstream& in, std::string* line, size_t* number) {
  while (std::getline(in, *line)) {
    ++*number;
    const size_t i = line->find_first_not_of(" \t\r\f\v");
    if (i != std::string::npos && (*line)[i] != '#') return true;
  }
  return false;
}

// Whether a face record "n i0 i1 ... i(n-1)" holds n >= 3 ids, each in [0, vertices).
bool valid_face_record(const std::string& line, long long vertices) {
  std::istringstream s(line);
  long long n = 0, id = 0;
  if (!(s >> n) || n < 3) return false;
  for (long long k = 0; k < n; ++k)
    if (!(s >> id) || id < 0 || id >= vertices) return false;
  return true;
}

// The `faces` face records of an OFF or ASCII PLY file: OpenMesh's readers reuse the last
// values read for a short or missing record and skip one with an id out of range.
bool check_face_records(std::ifstream& in, long long faces, long long vertices, const std::string& path, size_t* number,
                        std::string* error) {
  std::string line;
  for (long long f = 0; f < faces; ++f) {
    if (!next_content_line(in, &line, number))
      return fail(error, path + ": the file ends after " + std::to_string(f) + " of its " + std::to_string(faces) + " faces");
    if (!valid_face_record(line, vertices))
      return fail(error, path + ": line " + std::to_string(*number) + ": face " + std::to_string(f) +
                             " needs 3 or more vertex ids within the " + std::to_string(vertices) + " vertices");
  }
  return true;
}

// OFF's header keyword: "OFF" with the variant prefixes of ST, C, N, 4 and n.
bool off_keyword(const std::string& word) {
  return word.size() >= 3 && word.compare(word.size() - 3, 3, "OFF") == 0 &&
         word.find_first_not_of("STCN4n") == word.size() - 3;
}

bool check_off(std::ifstream& in, const std::string& path, DeclaredCounts* declared, std::string* error) {
  std::string line;
  size_t number = 0;
  if (!next_content_line(in, &line, &number)) return fail(error, path + ": empty file");
  std::istringstream header(line);
  std::string magic, rest;
  header >> magic;
  if (!off_keyword(magic)) return fail(error, path + ": not an OFF file (no OFF header)");
  // OpenMesh's binary OFF reader trusts its counts; no check can precede it without parsing it all.
  const bool more = bool(header >> rest);
  if (more && rest == "BINARY") return fail(error, path + ": binary OFF is not supported");
  // OpenMesh reads the counts (vertices, faces, edges) from the line after the keyword's.
  long long vertices = -1, faces = -1, edges = 0;
  std::istringstream counts;
  if (!more && next_content_line(in, &line, &number)) counts = std::istringstream(line);
  if (!(counts >> vertices >> faces) || vertices < 0 || faces < 0 || (counts >> edges && counts >> rest) ||
      (!counts.eof() && !counts.fail()))
    return fail(error, path + ": line " + std::to_string(number) + ": an OFF file needs its keyword alone on a line, "
                       "then its vertex, face and edge counts alone on the next");
  declared->vertices = vertices;
  declared->faces = faces;
  for (long long v = 0; v < vertices; ++v) {
    if (!next_content_line(in, &line, &number))
      return fail(error, path + ": the file ends after " + std::to_string(v) + " of its " + std::to_string(vertices) +
                             " vertices");
    if (!finite_numbers(line.c_str(), 3)) return bad_record(path, number, error);
  }
  return check_face_records(in, faces, vertices, path, &number, error);
}

bool check_ply(std::ifstream& in, const std::string& path, DeclaredCounts* declared, std::string* error) {
  PlyHeader h;
  size_t number = 0;
  if (!read_ply_header(in, path, &h, &number, error)) return false;
  long long lines_before = 0, vertices = -1;  // data lines of the elements before "vertex"
  bool faces_follow = false;                   // the face element right after "vertex"
  for (size_t e = 0; e < h.elements.size(); ++e) {
    const std::string& name = h.elements[e].name;
    const long long count = h.elements[e].count;
    if (name == "face") declared->faces = count;
    faces_follow = faces_follow || (name == "face" && e > 0 && h.elements[e - 1].name == "vertex");
    if (vertices < 0 && name == "vertex") vertices = count;
    if (vertices < 0) lines_before += count;
  }
  declared->vertices = std::max(vertices, 0LL);
  // OpenMesh's binary reader allocates a list's count before reading it: bound the count.
  if (!h.ascii && h.wide_list_count)
    return fail(error, path + ": binary PLY lists with 32-bit counts are not supported (use uchar or ushort)");
  if (!h.ascii && !binary_ply_fits(in, h)) return fail(error, path + ": the file is shorter than its PLY header declares");
  if (!h.ascii || vertices <= 0) return true;
  std::string line;
  for (long long k = 0; k < lines_before && std::getline(in, line); ++k) ++number;
  for (long long v = 0; v < vertices; ++v) {
    if (!std::getline(in, line))
      return fail(error, path + ": the file ends after " + std::to_string(v) + " of its " + std::to_string(vertices) +
                             " vertices");
    ++number;
    if (!finite_numbers(line.c_str(), -1)) return bad_record(path, number, error);
  }
  return !faces_follow || check_face_records(in, declared->faces, vertices, path, &number, error);
}

// The first line holding a control character (a byte below 0x20 other than white space) in
// the text part of a file, 0 when none: OpenMesh's readers and these checks would part ways.
// `header_only`: up to "end_header" (a binary PLY's body is not text).
size_t control_character_line(std::ifstream& in, bool header_only) {
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    for (unsigned char c : line)
      if (c < 0x20 && !std::isspace(c)) return number;
    if (header_only && line.rfind("end_header", 0) == 0) break;
  }
  return 0;
}

bool ply_is_ascii(std::ifstream& in) {
  std::string line;
  while (std::getline(in, line) && line.rfind("end_header", 0) != 0)
    if (line.rfind("format ascii", 0) == 0) return true;
  return false;
}

void rewind(std::ifstream& in) {
  in.clear();
  in.seekg(0);
}

}  // namespace

bool check_text_mesh_vertices(const std::string& path, DeclaredCounts* declared, std::string* error) {
  *declared = DeclaredCounts{};
  const std::string ext = lowercase_extension(path);
  if (ext != ".off" && ext != ".ply") return true;
  std::ifstream in(path, std::ios::binary);
  if (!in) return true;  // unreadable: OpenMesh reports it
  const bool binary_ply = ext == ".ply" && !ply_is_ascii(in);
  rewind(in);
  if (const size_t line = control_character_line(in, binary_ply))
    return fail(error, path + ": line " + std::to_string(line) + ": a control character in a text mesh file");
  rewind(in);
  if (ext == ".off") return check_off(in, path, declared, error);
  return check_ply(in, path, declared, error);
}

}  // namespace dcurve
