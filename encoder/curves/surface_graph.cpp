#include "encoder/curves/surface_graph.h"

// OpenMesh 9 headers trip GCC 12's -Wmaybe-uninitialized on a default-constructed Vec3f
// (clang, which builds the sanitizer and fuzz passes, has no such warning to ignore).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <cmath>

namespace dcurve {
namespace curves_detail {
namespace {

struct Traits : OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3f Point;
  typedef OpenMesh::Vec3f Normal;
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;

bool fail(std::string* error, const std::string& msg) {
  if (error) *error = "curve extraction: " + msg;
  return false;
}

// OpenMesh prints "complex edge" on its error stream when it rejects a face; we report the
// face ourselves, so the stream is muted while faces are added (and restored afterwards).
class MutedOpenMeshErrors {
 public:
  MutedOpenMeshErrors() : was_enabled_(::omerr().is_enabled()) { ::omerr().disable(); }
  ~MutedOpenMeshErrors() {
    if (was_enabled_) ::omerr().enable();
  }

 private:
  bool was_enabled_;
};

std::string face_text(size_t f, const uint32_t* ids) {
  return "face " + std::to_string(f) + " (" + std::to_string(ids[0]) + ", " + std::to_string(ids[1]) +
         ", " + std::to_string(ids[2]) + ")";
}

}  // namespace

bool SurfaceGraph::adjacent(uint32_t a, uint32_t b) const {
  if (a >= vertex_count || b >= vertex_count) return false;
  auto first = adj.begin() + adj_offsets[a], last = adj.begin() + adj_offsets[a + 1];
  return std::binary_search(first, last, b);
}

bool build_surface_graph(const std::vector<float>& xyz, uint32_t vertex_count,
                         const std::vector<uint32_t>& faces, SurfaceGraph* graph,
                         std::string* error) {
  if (vertex_count == 0) return fail(error, "mesh has no vertices");
  if (xyz.size() != size_t(vertex_count) * 3)
    return fail(error, "got " + std::to_string(xyz.size()) + " coordinates for " +
                           std::to_string(vertex_count) + " vertices (need 3 per vertex)");
  for (size_t i = 0; i < xyz.size(); ++i)
    if (!std::isfinite(xyz[i])) return fail(error, "vertex " + std::to_string(i / 3) + " is not finite");
  if (faces.size() % 3 != 0) return fail(error, "face list length is not a multiple of 3");

  Mesh mesh;
  mesh.reserve(vertex_count, faces.size(), faces.size() / 3);
  std::vector<Mesh::VertexHandle> vh(vertex_count);
  for (uint32_t v = 0; v < vertex_count; ++v)
    vh[v] = mesh.add_vertex(Mesh::Point(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]));
  {
    MutedOpenMeshErrors muted;
    for (size_t f = 0; f * 3 < faces.size(); ++f) {
      const uint32_t* ids = &faces[3 * f];
      for (int k = 0; k < 3; ++k)
        if (ids[k] >= vertex_count)
          return fail(error, face_text(f, ids) + " refers to a vertex >= vertex count " +
                                 std::to_string(vertex_count));
      if (ids[0] == ids[1] || ids[1] == ids[2] || ids[0] == ids[2])
        return fail(error, face_text(f, ids) + " repeats a vertex");
      if (!mesh.add_face(vh[ids[0]], vh[ids[1]], vh[ids[2]]).is_valid())
        return fail(error, face_text(f, ids) +
                               " makes the mesh non-manifold (an edge with more than two faces, a "
                               "vertex joining separate fans, or a duplicate/flipped face); "
                               "curve extraction needs a manifold mesh");
    }
  }
  mesh.request_face_normals();
  mesh.request_vertex_normals();
  mesh.update_normals();

  SurfaceGraph& g = *graph;
  g = SurfaceGraph();
  g.vertex_count = vertex_count;
  g.edges.reserve(mesh.n_edges());
  for (auto eh : mesh.edges()) {
    uint32_t a = uint32_t(mesh.from_vertex_handle(mesh.halfedge_handle(eh, 0)).idx());
    uint32_t b = uint32_t(mesh.to_vertex_handle(mesh.halfedge_handle(eh, 0)).idx());
    g.edges.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(g.edges.begin(), g.edges.end());

  g.adj_offsets.assign(vertex_count + 1, 0);
  for (const auto& e : g.edges) {
    ++g.adj_offsets[e[0] + 1];
    ++g.adj_offsets[e[1] + 1];
  }
  for (uint32_t v = 0; v < vertex_count; ++v) g.adj_offsets[v + 1] += g.adj_offsets[v];
  g.adj.resize(g.adj_offsets.back());
  std::vector<uint32_t> fill(g.adj_offsets.begin(), g.adj_offsets.end() - 1);
  for (const auto& e : g.edges) {
    g.adj[fill[e[0]]++] = e[1];
    g.adj[fill[e[1]]++] = e[0];
  }
  for (uint32_t v = 0; v < vertex_count; ++v)
    std::sort(g.adj.begin() + g.adj_offsets[v], g.adj.begin() + g.adj_offsets[v + 1]);

  g.normals.assign(size_t(vertex_count) * 3, 0.f);
  for (auto v : mesh.vertices()) {
    if (mesh.is_isolated(v)) continue;
    const auto& n = mesh.normal(v);
    float len = n.norm();
    if (!(len > 0.f)) continue;
    for (int a = 0; a < 3; ++a) g.normals[3 * v.idx() + a] = n[a] / len;
  }

  // Components by breadth-first search in vertex order, so numbering is deterministic.
  const uint32_t unset = UINT32_MAX;
  g.component.assign(vertex_count, unset);
  std::vector<uint32_t> queue;
  queue.reserve(vertex_count);
  for (uint32_t s = 0; s < vertex_count; ++s) {
    if (g.component[s] != unset) continue;
    const uint32_t c = g.component_count++;
    queue.clear();
    queue.push_back(s);
    g.component[s] = c;
    for (size_t head = 0; head < queue.size(); ++head) {
      uint32_t v = queue[head];
      for (uint32_t k = g.adj_offsets[v]; k < g.adj_offsets[v + 1]; ++k)
        if (g.component[g.adj[k]] == unset) {
          g.component[g.adj[k]] = c;
          queue.push_back(g.adj[k]);
        }
    }
  }
  return true;
}

}  // namespace curves_detail
}  // namespace dcurve
