#include "corpus/surfaces.h"

#include <cmath>

namespace dcurve::corpus {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Splits quad a-b-c-d (counter-clockwise seen from outside) into two triangles.
void add_quad(SurfaceMesh* m, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  m->faces.insert(m->faces.end(), {a, b, c, a, c, d});
}

uint32_t add_vertex(SurfaceMesh* m, double x, double y, double z) {
  m->xyz.insert(m->xyz.end(), {x, y, z});
  return uint32_t(m->xyz.size() / 3 - 1);
}

}  // namespace

SurfaceMesh box_surface(double sx, double sy, double sz, int nx, int ny, int nz) {
  const int n[3] = {nx, ny, nz};
  SurfaceMesh m;
  // Only lattice points on the boundary become vertices; the index grid shares them
  // between the six sides so the surface is watertight.
  std::vector<int64_t> id(size_t(nx + 1) * (ny + 1) * (nz + 1), -1);
  auto index = [&](int i, int j, int k) -> uint32_t {
    int64_t& slot = id[(size_t(k) * (ny + 1) + j) * (nx + 1) + i];
    if (slot < 0)
      slot = add_vertex(&m, sx * (double(i) / nx - 0.5), sy * (double(j) / ny - 0.5), sz * (double(k) / nz - 0.5));
    return uint32_t(slot);
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      const int fixed = side ? n[axis] : 0;
      for (int v = 0; v < n[c]; ++v)
        for (int u = 0; u < n[b]; ++u) {
          uint32_t q[4];
          const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
          for (int corner = 0; corner < 4; ++corner) {
            int ijk[3];
            ijk[axis] = fixed;
            ijk[b] = u + du[corner];
            ijk[c] = v + dv[corner];
            q[corner] = index(ijk[0], ijk[1], ijk[2]);
          }
          // e_b x e_c = +e_axis, so the (b, c) order faces outward on the max side.
          if (side)
            add_quad(&m, q[0], q[1], q[2], q[3]);
          else
            add_quad(&m, q[0], q[3], q[2], q[1]);
        }
    }
  }
  return m;
}

SurfaceMesh sphere_surface(double radius, int divisions) {
  SurfaceMesh m = box_surface(2.0, 2.0, 2.0, divisions, divisions, divisions);
  for (size_t v = 0; v < m.xyz.size(); v += 3) {
    // Equal-angle cube-to-sphere map keeps the triangles close to the same size.
    double p[3];
    for (int k = 0; k < 3; ++k) p[k] = std::tan(m.xyz[v + k] * kPi / 4.0);
    const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int k = 0; k < 3; ++k) m.xyz[v + k] = radius * p[k] / len;
  }
  return m;
}

SurfaceMesh tube_surface(double inner_radius, double outer_radius, double length, int around, int along) {
  SurfaceMesh m;
  // Ring r (0 = outer, 1 = inner), angle i, height j.
  auto id = [&](int r, int i, int j) {
    return uint32_t((size_t(r) * (along + 1) + j) * around + (i % around));
  };
  for (int r = 0; r < 2; ++r)
    for (int j = 0; j <= along; ++j)
      for (int i = 0; i < around; ++i) {
        const double a = 2.0 * kPi * i / around, rad = r ? inner_radius : outer_radius;
        add_vertex(&m, rad * std::cos(a), length * j / along, rad * std::sin(a));
      }
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < around; ++i) {
      // up x (increasing angle) points outward radially.
      add_quad(&m, id(0, i, j), id(0, i, j + 1), id(0, i + 1, j + 1), id(0, i + 1, j));
      add_quad(&m, id(1, i, j), id(1, i + 1, j), id(1, i + 1, j + 1), id(1, i, j + 1));
    }
  for (int i = 0; i < around; ++i) {
    // radial x (increasing angle) points down: the bottom cap goes inner -> outer.
    add_quad(&m, id(1, i, 0), id(0, i, 0), id(0, i + 1, 0), id(1, i + 1, 0));
    add_quad(&m, id(1, i, along), id(1, i + 1, along), id(0, i + 1, along), id(0, i, along));
  }
  return m;
}

namespace {

bool number(const nlohmann::json& spec, const char* key, double lo, double hi, double* out, std::string* error) {
  auto it = spec.find(key);
  if (it == spec.end() || !it->is_number()) {
    *error = std::string("mesh generator needs a number \"") + key + "\"";
    return false;
  }
  *out = it->get<double>();
  if (!(*out >= lo && *out <= hi)) {
    *error = std::string("mesh generator \"") + key + "\" must be in [" + std::to_string(lo) + ", " +
             std::to_string(hi) + "]";
    return false;
  }
  return true;
}

bool integer(const nlohmann::json& spec, const char* key, int lo, int hi, int* out, std::string* error) {
  double v = 0;
  if (!number(spec, key, lo, hi, &v, error)) return false;
  *out = int(v);
  if (double(*out) != v) {
    *error = std::string("mesh generator \"") + key + "\" must be an integer";
    return false;
  }
  return true;
}

bool triple(const nlohmann::json& spec, const char* key, double lo, double hi, double out[3], std::string* error) {
  auto it = spec.find(key);
  if (it == spec.end() || !it->is_array() || it->size() != 3) {
    *error = std::string("mesh generator needs \"") + key + "\": [x, y, z]";
    return false;
  }
  for (int k = 0; k < 3; ++k) {
    nlohmann::json one = {{key, (*it)[k]}};
    if (!number(one, key, lo, hi, &out[k], error)) return false;
  }
  return true;
}

}  // namespace

bool generate_surface(const nlohmann::json& spec, SurfaceMesh* out, std::string* error) {
  // Limits keep a typo from asking for billions of vertices.
  constexpr int kMaxDivisions = 4000;
  constexpr double kMaxSize = 1e6;
  if (!spec.is_object() || !spec.contains("generator") || !spec["generator"].is_string()) {
    *error = "mesh needs \"file\" or \"generator\"";
    return false;
  }
  const std::string gen = spec["generator"].get<std::string>();
  if (gen == "box") {
    double size[3], div[3];
    if (!triple(spec, "size", 1e-9, kMaxSize, size, error) || !triple(spec, "divisions", 1, kMaxDivisions, div, error))
      return false;
    *out = box_surface(size[0], size[1], size[2], int(div[0]), int(div[1]), int(div[2]));
    return true;
  }
  if (gen == "sphere") {
    double radius = 0;
    int div = 0;
    if (!number(spec, "radius", 1e-9, kMaxSize, &radius, error) || !integer(spec, "divisions", 1, kMaxDivisions, &div, error))
      return false;
    *out = sphere_surface(radius, div);
    return true;
  }
  if (gen == "tube") {
    double inner = 0, outer = 0, length = 0;
    int around = 0, along = 0;
    if (!number(spec, "inner_radius", 1e-9, kMaxSize, &inner, error) ||
        !number(spec, "outer_radius", 1e-9, kMaxSize, &outer, error) ||
        !number(spec, "length", 1e-9, kMaxSize, &length, error) ||
        !integer(spec, "around", 3, kMaxDivisions, &around, error) ||
        !integer(spec, "along", 1, kMaxDivisions, &along, error))
      return false;
    if (inner >= outer) {
      *error = "tube needs inner_radius < outer_radius";
      return false;
    }
    *out = tube_surface(inner, outer, length, around, along);
    return true;
  }
  *error = "unknown mesh generator \"" + gen + "\" (box, sphere, tube)";
  return false;
}

}  // namespace dcurve::corpus
