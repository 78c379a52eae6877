// Area-weighted unit normals, shared by the vertex and render-vertex normal calls.
#pragma once
#include <cstddef>
#include <cstdint>

namespace dcurve {

// Corner k of the triangles sits at xyz[3 * faces[k]] and adds its face's area-weighted
// normal to out[3 * targets[k]]; out holds target_count normals, normalized at the end.
void area_normals(const float* xyz, const uint32_t* faces, size_t corner_count, const uint32_t* targets,
                  size_t target_count, float* out);

}  // namespace dcurve
