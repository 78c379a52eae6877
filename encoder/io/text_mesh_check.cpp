#include "encoder/io/text_mesh_check.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "codec/common/error.h"
#include "encoder/io/files.h"

namespace dcurve {
namespace {

// Parses up to `count` numbers from `p` (all the remaining ones when count < 0): false when
// one is missing or not a finite value within float range.
bool finite_numbers(const char* p, int count) {
  for (int k = 0; count < 0 || k < count; ++k) {
    while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
    if (count < 0 && *p == '\0') return true;
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

bool check_obj(std::ifstream& in, const std::string& path, std::string* error) {
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    const size_t i = line.find_first_not_of(" \t");
    if (i == std::string::npos || line[i] != 'v' || i + 1 >= line.size() || (line[i + 1] != ' ' && line[i + 1] != '\t'))
      continue;
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

bool check_off(std::ifstream& in, const std::string& path, std::string* error) {
  std::string line;
  size_t number = 0;
  if (!next_content_line(in, &line, &number)) return true;  // empty: OpenMesh's error
  std::istringstream header(line);
  std::string magic;
  header >> magic;
  if (magic != "OFF") return true;  // variants (COFF, NOFF, binary...) are left to OpenMesh
  long long vertices = -1;
  if (!(header >> vertices) && next_content_line(in, &line, &number)) std::istringstream(line) >> vertices;
  for (long long v = 0; v < vertices; ++v) {
    if (!next_content_line(in, &line, &number)) return true;  // truncated: OpenMesh's error
    if (!finite_numbers(line.c_str(), 3)) return bad_record(path, number, error);
  }
  return true;
}

bool check_ascii_ply(std::ifstream& in, const std::string& path, std::string* error) {
  std::string line, word;
  size_t number = 0;
  bool ascii = false, vertex_seen = false;
  long long lines_before = 0, vertices = 0;  // data lines of the elements before "vertex"
  while (std::getline(in, line)) {
    ++number;
    std::istringstream s(line);
    if (!(s >> word)) continue;
    if (word == "end_header") break;
    if (word == "format") {
      ascii = (s >> word) && word == "ascii";
    } else if (word == "element" && !vertex_seen) {
      std::string name;
      long long count = 0;
      s >> name >> count;
      vertex_seen = name == "vertex";
      (vertex_seen ? vertices : lines_before) += std::max(count, 0LL);
    }
  }
  if (!ascii || vertices == 0) return true;
  for (long long k = 0; k < lines_before && std::getline(in, line); ++k) ++number;
  for (long long v = 0; v < vertices && std::getline(in, line); ++v) {
    ++number;
    if (!finite_numbers(line.c_str(), -1)) return bad_record(path, number, error);
  }
  return true;
}

}  // namespace

bool check_text_mesh_vertices(const std::string& path, std::string* error) {
  const std::string ext = lowercase_extension(path);
  if (ext != ".obj" && ext != ".off" && ext != ".ply") return true;
  std::ifstream in(path, std::ios::binary);
  if (!in) return true;  // unreadable: OpenMesh reports it
  if (ext == ".obj") return check_obj(in, path, error);
  if (ext == ".off") return check_off(in, path, error);
  return check_ascii_ply(in, path, error);
}

}  // namespace dcurve
