#include "encoder/io/text_mesh_check.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "codec/common/error.h"
#include "encoder/io/files.h"

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

// The record's keyword ("v", "f", ...) at line[i], followed by a blank.
bool obj_record(const std::string& line, size_t i, char keyword) {
  return i != std::string::npos && line[i] == keyword && i + 1 < line.size() && (line[i + 1] == ' ' || line[i + 1] == '\t');
}

// What is wrong with the "f" record `p` (after the keyword) when `vertices` are defined so
// far, or "" when nothing is: OpenMesh's OBJ reader drops a face with an index out of range
// or a vertex used twice. Indices are 1-based, or negative counting back from the last.
std::string obj_face_problem(const char* p, long long vertices) {
  std::vector<long long> ids;
  for (;;) {
    while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
    if (*p == '\0' || *p == '#') break;
    char* end = nullptr;
    const long long i = std::strtoll(p, &end, 10);
    if (end == p) return "a face vertex is not an index";
    const long long id = i < 0 ? vertices + i : i - 1;
    if (i == 0 || id < 0 || id >= vertices) return "vertex index " + std::to_string(i) + " out of range";
    if (std::find(ids.begin(), ids.end(), id) != ids.end())
      return "the face uses vertex " + std::to_string(id + 1) + " twice (degenerate face)";
    ids.push_back(id);
    p = end;
    while (*p != '\0' && *p != ' ' && *p != '\t' && *p != '\r') ++p;  // "/texcoord/normal"
  }
  return ids.size() < 3 ? "a face needs 3 or more vertices" : "";
}

bool check_obj(std::ifstream& in, const std::string& path, DeclaredCounts* declared, std::string* error) {
  std::string line;
  declared->vertices = declared->faces = 0;
  for (size_t number = 1; std::getline(in, line); ++number) {
    const size_t i = line.find_first_not_of(" \t");
    if (obj_record(line, i, 'f')) {
      ++declared->faces;
      const std::string problem = obj_face_problem(line.c_str() + i + 1, declared->vertices);
      if (!problem.empty()) return fail(error, path + ": line " + std::to_string(number) + ": " + problem);
    }
    if (!obj_record(line, i, 'v')) continue;
    ++declared->vertices;
    if (!finite_numbers(line.c_str() + i + 1, 3)) return bad_record(path, number, error);
  }
  return true;
}

// Next line that is neither blank nor a comment; false at the end of the file.
bool next_content_line(std::ifstream& in, std::string* line, size_t* number) {
  while (std::getline(in, *line)) {
    ++*number;
    const size_t i = line->find_first_not_of(" \t\r");
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
  if (!next_content_line(in, &line, &number)) return true;  // empty: OpenMesh's error
  std::istringstream header(line);
  std::string magic, binary;
  header >> magic;
  if (!off_keyword(magic)) return true;  // not OFF: OpenMesh's error
  if (header >> binary && binary == "BINARY") return true;  // counts are binary: checked after reading
  long long vertices = -1, faces = -1;
  std::istringstream counts(line.substr(line.find(magic) + magic.size()));
  if (!(counts >> vertices) && next_content_line(in, &line, &number)) {
    counts = std::istringstream(line);
    counts >> vertices;
  }
  counts >> faces;
  declared->vertices = vertices;
  declared->faces = faces;
  for (long long v = 0; v < vertices; ++v) {
    if (!next_content_line(in, &line, &number)) return true;  // truncated: OpenMesh's error
    if (!finite_numbers(line.c_str(), 3)) return bad_record(path, number, error);
  }
  return check_face_records(in, faces, vertices, path, &number, error);
}

bool check_ply(std::ifstream& in, const std::string& path, DeclaredCounts* declared, std::string* error) {
  std::string line, word;
  size_t number = 0;
  bool ascii = false, vertex_seen = false, faces_follow = false;  // the face element right after "vertex"
  std::string previous;
  long long lines_before = 0, vertices = 0;  // data lines of the elements before "vertex"
  while (std::getline(in, line)) {
    ++number;
    std::istringstream s(line);
    if (!(s >> word)) continue;
    if (word == "end_header") break;
    if (word == "format") {
      ascii = (s >> word) && word == "ascii";
    } else if (word == "element") {
      std::string name;
      long long count = 0;
      s >> name >> count;
      if (name == "face") declared->faces = count;
      faces_follow = faces_follow || (name == "face" && previous == "vertex");
      previous = name;
      if (vertex_seen) continue;
      vertex_seen = name == "vertex";
      (vertex_seen ? vertices : lines_before) += std::max(count, 0LL);
    }
  }
  declared->vertices = vertices;
  if (!ascii || vertices == 0) return true;
  for (long long k = 0; k < lines_before && std::getline(in, line); ++k) ++number;
  for (long long v = 0; v < vertices && std::getline(in, line); ++v) {
    ++number;
    if (!finite_numbers(line.c_str(), -1)) return bad_record(path, number, error);
  }
  return !faces_follow || check_face_records(in, declared->faces, vertices, path, &number, error);
}

}  // namespace

bool check_text_mesh_vertices(const std::string& path, DeclaredCounts* declared, std::string* error) {
  *declared = DeclaredCounts{};
  const std::string ext = lowercase_extension(path);
  if (ext != ".obj" && ext != ".off" && ext != ".ply") return true;
  std::ifstream in(path, std::ios::binary);
  if (!in) return true;  // unreadable: OpenMesh reports it
  if (ext == ".obj") return check_obj(in, path, declared, error);
  if (ext == ".off") return check_off(in, path, declared, error);
  return check_ply(in, path, declared, error);
}

}  // namespace dcurve
