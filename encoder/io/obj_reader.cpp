#include "encoder/io/obj_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "codec/common/error.h"
#include "encoder/io/files.h"

namespace dcurve {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// A byte below 0x20 that is not white space: OBJ is text, and such a byte in a name would
// reach every output that writes names.
bool is_control(char c) { return static_cast<unsigned char>(c) < 0x20 && !is_space(c); }

// Whether `s` is well-formed UTF-8 (no overlong forms, surrogates or values past U+10FFFF):
// names go into JSON (MATL, glTF), which holds UTF-8 only.
bool valid_utf8(std::string_view s) {
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const int n = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : -1;
    if (n < 0 || s.size() - i <= size_t(n)) return false;
    uint32_t code = n == 0 ? c : c & (0x3F >> n);
    for (int k = 1; k <= n; ++k) {
      const unsigned char d = static_cast<unsigned char>(s[i + k]);
      if ((d >> 6) != 0x2) return false;
      code = code << 6 | (d & 0x3F);
    }
    static const uint32_t kLeast[4] = {0, 0x80, 0x800, 0x10000};
    if (code < kLeast[n] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return false;
    i += size_t(n) + 1;
  }
  return true;
}

// One line's bytes, read left to right. `#` at the start or after white space ends the
// record (a comment), so `f 1 2 3 # note` is a triangle.
struct Cursor {
  const char* p;
  const char* end;

  void skip_space() {
    while (p < end && is_space(*p)) ++p;
  }
  bool done() {
    skip_space();
    return p == end || *p == '#';
  }
  std::string_view token() {
    skip_space();
    const char* start = p;
    while (p < end && !is_space(*p)) ++p;
    return {start, size_t(p - start)};
  }
  // The rest of the record without its comment, trimmed: a name with spaces stays whole.
  std::string_view rest() {
    skip_space();
    const char* stop = p;
    for (const char* q = p; q < end && !(*q == '#' && (q == p || is_space(q[-1]))); ++q)
      if (!is_space(*q)) stop = q + 1;
    std::string_view r(p, size_t(stop - p));
    p = end;
    return r;
  }
};

// A decimal number within float range (hexadecimal floats, inf and nan refused), rounded
// once, straight to float, as a stream reads it (through double it could round twice).
bool parse_number(std::string_view t, float* x) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  if (t.empty() || t.find_first_of("xXiInN") != std::string_view::npos) return false;
  float f = 0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), f);
  if (r.ptr != t.data() + t.size()) return false;
  if (r.ec == std::errc::result_out_of_range) {  // below float's least: a stream reads 0 or a denormal
    double d = 0;
    const auto rd = std::from_chars(t.data(), t.data() + t.size(), d);
    if (rd.ec != std::errc() || !(std::fabs(d) <= 1.0)) return false;
    f = float(d);
  } else if (r.ec != std::errc() || !std::isfinite(f)) {
    return false;
  }
  *x = f;
  return true;
}

// An OBJ index (1-based, or negative: counted back from the last record read) as 0-based:
// "" or what is wrong with it (`kind` names the records it counts).
std::string parse_index(std::string_view t, size_t count, const char* kind, int64_t* out) {
  long long i = 0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), i);
  if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size()) return "malformed";
  const long long id = i > 0 ? i - 1 : (long long)count + i;
  if (i == 0 || id < 0 || (unsigned long long)id >= count) return std::string(kind) + " index " + std::to_string(i) + " out of range";
  *out = id;
  return "";
}

struct Corner {
  int64_t v = -1, vt = -1, vn = -1;
};

// The records of one OBJ, line by line; each returns "" or what is wrong with the line.
class Parser {
 public:
  explicit Parser(ObjMesh* out) : out_(out) { out_->soup.polygon_offsets.assign(1, 0); }

  std::string line(Cursor c) {
    const std::string_view key = c.token();
    if (key == "v") return numbers(c, 3, 3, &out_->soup.xyz) ? "" : "vertex values are not finite numbers within float range";
    if (key == "vt") return numbers(c, 1, 3, &out_->corners.texcoords) ? "" : "texture coordinates are not finite numbers within float range";
    if (key == "vn") return numbers(c, 3, 3, &out_->corners.normals) ? "" : "normal values are not finite numbers within float range";
    if (key == "f") return face(c);
    if (key == "usemtl") return use_material(c.rest());
    if (key == "mtllib") return library(c.rest());
    return "";
  }

 private:
  // Between `least` and `most` numbers; values kept: 3 for positions and normals, 2 for
  // texture coordinates (v = 0 when absent, as most readers take it; w dropped). Extra values
  // (a position's w or colour) are ignored.
  bool numbers(Cursor& c, int least, int most, std::vector<float>* into) {
    float x[3] = {0, 0, 0};
    int n = 0;
    for (; n < most && !c.done(); ++n)
      if (!parse_number(c.token(), &x[n])) return false;
    if (n < least) return false;
    const int kept = into == &out_->corners.texcoords ? 2 : 3;
    into->insert(into->end(), x, x + kept);
    return true;
  }

  // "" or what is wrong with the corner `t` ("v", "v/vt", "v//vn" or "v/vt/vn").
  std::string corner(std::string_view t, Corner* k) const {
    const size_t s1 = t.find('/');
    const size_t s2 = s1 == std::string_view::npos ? s1 : t.find('/', s1 + 1);
    const std::string_view v = t.substr(0, s1);
    const std::string_view vt = s1 == std::string_view::npos ? std::string_view() : t.substr(s1 + 1, s2 - s1 - 1);
    const std::string_view vn = s2 == std::string_view::npos ? std::string_view() : t.substr(s2 + 1);
    std::string problem = parse_index(v, out_->soup.xyz.size() / 3, "vertex", &k->v);
    if (problem.empty() && !vt.empty()) problem = parse_index(vt, out_->corners.texcoords.size() / 2, "texture coordinate", &k->vt);
    if (problem.empty() && !vn.empty()) problem = parse_index(vn, out_->corners.normals.size() / 3, "normal", &k->vn);
    return problem == "malformed" ? "face corner '" + std::string(t.substr(0, 40)) + "' is malformed" : problem;
  }

  std::string face(Cursor& c) {
    polygon_.clear();
    while (!c.done()) {
      polygon_.emplace_back();
      const std::string problem = corner(c.token(), &polygon_.back());
      if (!problem.empty()) return problem;
    }
    if (polygon_.size() < 3) return "a face needs 3 or more vertices";
    if (const int64_t v = repeated_vertex(); v >= 0)
      return "the face uses vertex " + std::to_string(v + 1) + " twice (degenerate face)";
    add_polygon();
    return "";
  }

  // A vertex the polygon names twice, or -1. Sorted, not pairwise: a face of 100,000
  // corners must not take 10^10 steps.
  int64_t repeated_vertex() {
    ids_.clear();
    for (const Corner& k : polygon_) ids_.push_back(k.v);
    std::sort(ids_.begin(), ids_.end());
    const auto it = std::adjacent_find(ids_.begin(), ids_.end());
    return it == ids_.end() ? -1 : *it;
  }

  void add_polygon() {
    start_pending_material();
    PolygonSoup& s = out_->soup;
    for (const Corner& k : polygon_) s.ids.push_back(uint32_t(k.v));
    s.polygon_offsets.push_back(uint32_t(s.ids.size()));
    ObjCorners& o = out_->corners;
    for (size_t k = 1; k + 1 < polygon_.size(); ++k) {
      for (const Corner* q : {&polygon_[0], &polygon_[k], &polygon_[k + 1]}) {
        o.vertex.push_back(uint32_t(q->v));
        o.texcoord.push_back(q->vt);
        o.normal.push_back(q->vn);
      }
      o.face_material.push_back(material_);
    }
  }

  // Named when a face uses it: `usemtl a` right before `usemtl b` gives no empty group.
  std::string use_material(std::string_view name) {
    if (!valid_utf8(name)) return "the material name is not UTF-8 text";
    pending_ = std::string(name);
    has_pending_ = true;
    return "";
  }

  void start_pending_material() {
    if (!has_pending_) return;
    has_pending_ = false;
    const auto it = material_ids_.emplace(std::move(pending_), int32_t(out_->corners.materials.size()));
    if (it.second) out_->corners.materials.push_back(it.first->first);
    material_ = it.first->second;
  }

  // The first library is kept, as a name only: it is never opened.
  std::string library(std::string_view name) {
    if (!valid_utf8(name)) return "the material library name is not UTF-8 text";
    if (out_->corners.material_library.empty()) out_->corners.material_library = std::string(name);
    return "";
  }

  ObjMesh* out_;
  std::vector<Corner> polygon_;
  std::vector<int64_t> ids_;
  std::unordered_map<std::string, int32_t> material_ids_;
  int32_t material_ = -1;
  std::string pending_;  // the last usemtl's name, until a face uses it
  bool has_pending_ = false;
};

}  // namespace

bool parse_obj(const std::string& path, std::string_view text, ObjMesh* out, std::string* error) {
  *out = ObjMesh{};
  Parser parser(out);
  size_t number = 1;
  for (size_t begin = 0; begin < text.size(); ++number) {
    size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    const char* p = text.data() + begin;
    const char* q = text.data() + end;
    std::string problem = std::find_if(p, q, is_control) != q ? "a control character in a text mesh file" : "";
    if (problem.empty()) problem = parser.line(Cursor{p, q});
    if (!problem.empty()) return fail(error, path + ": line " + std::to_string(number) + ": " + problem);
    begin = end + 1;
  }
  return true;
}

bool read_obj(const std::string& path, ObjMesh* out, std::string* error) {
  std::vector<uint8_t> bytes;
  if (!read_file(path, &bytes, error)) return false;
  return parse_obj(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), out, error);
}

}  // namespace dcurve
