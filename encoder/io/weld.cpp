#include "encoder/io/weld.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "codec/common/mixed_hash.h"

namespace dcurve {
namespace {

bool same_in_every_frame(const Animation& anim, uint32_t a, uint32_t b) {
  for (const std::vector<float>& f : anim.frames)
    if (std::memcmp(&f[3 * size_t(a)], &f[3 * size_t(b)], 3 * sizeof(float)) != 0) return false;
  return true;
}

// Per render vertex, the lowest-numbered render vertex equal to it in every frame.
std::vector<uint32_t> find_representatives(const Animation& anim) {
  const uint32_t R = anim.vertex_count;
  std::vector<std::pair<uint64_t, uint32_t>> keyed(R);
  for (uint32_t r = 0; r < R; ++r) {
    uint64_t h = 0;
    for (const std::vector<float>& f : anim.frames)
      for (int a = 0; a < 3; ++a) {
        uint32_t bits;
        std::memcpy(&bits, &f[3 * size_t(r) + a], 4);
        h = MixedHash{}(h + bits);
      }
    keyed[r] = {h, r};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint32_t> rep(R);
  for (size_t i = 0; i < R;) {
    size_t end = i;
    while (end < R && keyed[end].first == keyed[i].first) ++end;
    // Within one hash, each vertex joins the first earlier one it equals (collisions are rare).
    for (size_t j = i; j < end; ++j) {
      const uint32_t r = keyed[j].second;
      rep[r] = r;
      for (size_t k = i; k < j; ++k)
        if (rep[keyed[k].second] == keyed[k].second && same_in_every_frame(anim, keyed[k].second, r)) {
          rep[r] = keyed[k].second;
          break;
        }
    }
    i = end;
  }
  return rep;
}

// Vertex ids in order of first appearance among the render vertices.
uint32_t number_vertices(const std::vector<uint32_t>& rep, std::vector<uint32_t>* source) {
  source->resize(rep.size());
  uint32_t next = 0;
  for (size_t r = 0; r < rep.size(); ++r) (*source)[r] = rep[r] == r ? next++ : (*source)[rep[r]];
  return next;
}

void keep_vertices(const std::vector<uint32_t>& source, uint32_t vertex_count, Animation* anim) {
  for (std::vector<float>& f : anim->frames) {
    std::vector<float> kept(size_t(vertex_count) * 3);
    for (size_t r = source.size(); r-- > 0;) std::memcpy(&kept[3 * size_t(source[r])], &f[3 * r], 3 * sizeof(float));
    f.swap(kept);
  }
  anim->vertex_count = vertex_count;
}

// Faces over vertices, corners over render vertices; drops triangles that use a vertex twice.
void split_faces(const std::vector<uint32_t>& source, Animation* anim) {
  std::vector<uint32_t> faces, corners, groups;
  const std::vector<uint32_t>& face_group = anim->render.face_group;
  size_t dropped = 0;
  for (size_t t = 0; t + 2 < anim->faces.size(); t += 3) {
    const uint32_t* c = &anim->faces[t];
    const uint32_t a = source[c[0]], b = source[c[1]], d = source[c[2]];
    if (a == b || b == d || a == d) {
      ++dropped;
      continue;
    }
    faces.insert(faces.end(), {a, b, d});
    corners.insert(corners.end(), {c[0], c[1], c[2]});
    if (!face_group.empty()) groups.push_back(face_group[t / 3]);
  }
  anim->render.face_group.swap(groups);
  if (dropped > 0)
    anim->notes.push_back("dropped " + std::to_string(dropped) +
                          " triangles whose corners sit at one point in every frame (zero area, nothing to draw)");
  anim->faces.swap(faces);
  anim->render.corners.swap(corners);
}

}  // namespace

void weld_copies(Animation* anim, std::vector<AnimationRender::Attribute> attributes) {
  std::vector<uint32_t> source;
  const uint32_t vertices = number_vertices(find_representatives(*anim), &source);
  if (vertices == anim->vertex_count && attributes.empty() && anim->render.groups.empty()) return;
  keep_vertices(source, vertices, anim);
  split_faces(source, anim);
  anim->render.source = std::move(source);
  anim->render.attributes = std::move(attributes);
}

}  // namespace dcurve
