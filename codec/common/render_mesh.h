// What a game draws besides the animated positions (format 3.3 / 4.1, sections REND and PLAC,
// format_spec/dcrv.md sections 19 and 20): render vertices that split a position at UV or
// normal seams, their static attributes, and where and when the animation sits in its scene.
// Positions are coded once per source vertex (Model vertex), so seam copies never drift apart.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

// Attributes a render vertex carries, the glTF names' order (REND stores the number).
enum class AttributeSemantic : uint8_t { TexCoord0 = 0, TexCoord1 = 1, Color0 = 2, Normal = 3 };
constexpr uint8_t kAttributeSemanticCount = 4;
constexpr uint8_t kMaxAttributeBits = 16;
const char* attribute_gltf_name(AttributeSemantic s);  // "TEXCOORD_0", ...
// Components a semantic may have: 2 for texture coordinates, 3 for normals, 3 or 4 for colours.
bool attribute_components_allowed(AttributeSemantic s, uint32_t components);

// One static attribute, uniformly quantized per component: value = lo + q * (hi - lo) / (2^bits - 1).
struct RenderAttribute {
  AttributeSemantic semantic = AttributeSemantic::TexCoord0;
  uint8_t components = 2;
  uint8_t bits = 14;
  float lo[4] = {0, 0, 0, 0}, hi[4] = {0, 0, 0, 0};
  std::vector<uint16_t> q;  // render_count * components, each < 2^bits

  // In binary64, then rounded: hi - lo of finite binary32 ends can overflow binary32 (UVs
  // spanning +-3e38), a value between them cannot.
  float value(size_t render_vertex, uint32_t component) const {
    const double top = double((1u << bits) - 1), l = lo[component];
    return float(l + double(q[render_vertex * components + component]) * ((double(hi[component]) - l) / top));
  }
};

// Render vertices in the input's order: `source` maps each to the vertex whose position it
// shows, `corners` gives the render vertex of each corner of Model::faces (triangles keep the
// faces' order). Vertices are numbered in order of first appearance in `source` (so render
// vertex 0 shows vertex 0, and a mesh without copies has source[r] == r); REND stores source
// as "new" or a distance back, and each corner as which copy of its vertex it takes.
// Triangles drawn with one material (a glTF primitive, an OBJ usemtl block).
struct FaceGroup {
  int32_t material = -1;  // index into MaterialSet's "materials", -1: none
  std::string name;       // the material's name, for engines that match materials by name
};

struct RenderMesh {
  std::vector<uint32_t> source;
  std::vector<uint32_t> corners;
  std::vector<RenderAttribute> attributes;
  std::vector<FaceGroup> groups;     // empty: one group of every face, no material
  std::vector<uint32_t> face_group;  // per triangle of Model::faces when groups are present
  bool empty() const { return source.empty(); }
};

// The materials the groups use, as the input's glTF wrote them (MATL): a JSON object with the
// arrays "materials", "textures", "samplers" and "images" (each image {"name", "mimeType"},
// its bytes in `images` at the same index) and the extensions they use. Stored, not
// referenced: a .dcrv is one asset, and decoding reads nothing beside it.
struct MaterialImage {
  std::string mime_type;
  std::vector<uint8_t> bytes;
};
struct MaterialSet {
  std::string json;
  std::vector<MaterialImage> images;
  bool empty() const { return json.empty() && images.empty(); }
};

// Where the animation sits and when it starts, as the input said (PLAC).
struct Placement {
  double start_time = 0;  // seconds of frame 0 (a glTF first key, a cache's start frame / rate)
  bool has_matrix = false;
  double matrix[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // world transform, column-major
  std::string mesh_name, node_name;
  bool empty() const { return start_time == 0 && !has_matrix && mesh_name.empty() && node_name.empty(); }
};

// Whether `source` numbers the vertices 0..vertex_count-1 in order of first appearance.
bool render_source_in_first_use_order(const std::vector<uint32_t>& source, uint32_t vertex_count);

// The render vertices of each vertex in ascending order (offsets: vertex_count + 1 entries).
void render_copies(const std::vector<uint32_t>& source, uint32_t vertex_count, std::vector<uint32_t>* offsets,
                   std::vector<uint32_t>* copies);

// Corner k takes copy ordinals[k] of vertex faces[k]. False when an ordinal has no copy.
bool render_corners_from_ordinals(const std::vector<uint32_t>& faces, const std::vector<uint32_t>& source,
                                  uint32_t vertex_count, const std::vector<uint32_t>& ordinals,
                                  std::vector<uint32_t>* corners);
// The inverse; false when a corner's render vertex does not show the corner's vertex.
bool render_corner_ordinals(const std::vector<uint32_t>& faces, const RenderMesh& render, uint32_t vertex_count,
                            std::vector<uint32_t>* ordinals);

}  // namespace dcurve
