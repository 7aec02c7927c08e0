// Shapes and helpers for the unfold tests.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "dcshell/convex_hull.h"
#include "dcshell/kernel.h"
#include "unfold/unfold_internal.h"

namespace dcshell::test {

/// Mesh from vertex list and polygon loops (counter-clockwise seen from outside).
inline Mesh make_mesh(const std::vector<std::array<double, 3>>& v, const std::vector<std::vector<int>>& faces) {
  Mesh m;
  std::vector<Mesh::Vertex_index> vi;
  for (auto& p : v) vi.push_back(m.add_vertex(Point3(p[0], p[1], p[2])));
  for (auto& f : faces) {
    std::vector<Mesh::Vertex_index> loop;
    for (int i : f) loop.push_back(vi[i]);
    m.add_face(loop);
  }
  return m;
}

inline Mesh tetrahedron() { return make_mesh({{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}, {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}}); }

/// Unit cube [0,1]^3 as 12 triangles (the diagonals are flat edges).
inline Mesh cube_triangles() {
  std::vector<std::array<double, 3>> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  std::vector<std::vector<int>> quads = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::vector<std::vector<int>> tris;
  for (auto& q : quads) tris.push_back({q[0], q[1], q[2]}), tris.push_back({q[0], q[2], q[3]});
  return make_mesh(v, tris);
}

inline Mesh octahedron() {
  return make_mesh({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                   {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
}

inline Mesh icosahedron() {
  const double p = (1 + std::sqrt(5.0)) / 2;
  std::vector<std::array<double, 3>> v = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                                          {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  return make_mesh(v, {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                       {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                       {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}});
}

/// Dodecahedron as 12 pentagons (fan-triangulated by the unfolder: 36 triangles).
inline Mesh dodecahedron() {
  const double p = (1 + std::sqrt(5.0)) / 2, q = 1 / p;
  std::vector<std::array<double, 3>> v = {
      {1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {1, -1, -1}, {-1, 1, 1}, {-1, 1, -1}, {-1, -1, 1}, {-1, -1, -1},
      {0, q, p}, {0, q, -p}, {0, -q, p}, {0, -q, -p}, {q, p, 0}, {q, -p, 0}, {-q, p, 0}, {-q, -p, 0},
      {p, 0, q}, {p, 0, -q}, {-p, 0, q}, {-p, 0, -q}};
  std::vector<std::vector<int>> f = {{0, 8, 10, 2, 16}, {0, 16, 17, 1, 12}, {0, 12, 14, 4, 8}, {1, 17, 3, 11, 9},
                                     {1, 9, 5, 14, 12}, {2, 10, 6, 15, 13}, {2, 13, 3, 17, 16}, {3, 13, 15, 7, 11},
                                     {4, 14, 5, 19, 18}, {4, 18, 6, 10, 8}, {5, 9, 11, 7, 19}, {6, 18, 19, 7, 15}};
  // Orient every pentagon outward (the list above mixes orientations).
  for (auto& loop : f) {
    Eigen::Vector3d a(v[loop[0]].data()), b(v[loop[1]].data()), c(v[loop[2]].data());
    if ((b - a).cross(c - a).dot(a) < 0) std::reverse(loop.begin(), loop.end());
  }
  return make_mesh(v, f);
}

/// Cube [0,n]^3 with every face split into n x n squares of 2 triangles: 6 facets, 12 n^2 triangles.
inline Mesh subdivided_cube(int n) {
  std::vector<std::array<double, 3>> v;
  std::vector<std::vector<int>> tris;
  // Each face: origin o, axes u, w with u x w outward; vertices duplicated per face and then
  // merged by coordinates so the faces share their edges.
  const std::array<std::array<std::array<double, 3>, 3>, 6> faces = {{
      {{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}}, {{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}},
      {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}}, {{{0, 1, 0}, {0, 0, 1}, {1, 0, 0}}},
      {{{0, 0, 0}, {0, 0, 1}, {0, 1, 0}}}, {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}}};
  auto id = [&](std::array<double, 3> p) {
    auto it = std::find(v.begin(), v.end(), p);
    if (it != v.end()) return static_cast<int>(it - v.begin());
    v.push_back(p);
    return static_cast<int>(v.size()) - 1;
  };
  for (auto& f : faces)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        auto at = [&](int a, int b) {
          std::array<double, 3> p;
          for (int k = 0; k < 3; ++k) p[k] = n * f[0][k] + a * f[1][k] + b * f[2][k];
          return id(p);
        };
        int p00 = at(i, j), p10 = at(i + 1, j), p11 = at(i + 1, j + 1), p01 = at(i, j + 1);
        tris.push_back({p00, p10, p11}), tris.push_back({p00, p11, p01});
      }
  return make_mesh(v, tris);
}

/// A right pyramid over a regular n-gon (radius 1, apex at height h), the base fan-triangulated
/// from its centre: n thin lateral faces around the apex, like the shared pyramid2 (n = 4096).
inline Mesh fine_pyramid(int n, double h) {
  std::vector<std::array<double, 3>> v = {{0, 0, h}, {0, 0, 0}};
  std::vector<std::vector<int>> tris;
  for (int i = 0; i < n; ++i) v.push_back({std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0});
  for (int i = 0; i < n; ++i) {
    int a = 2 + i, b = 2 + (i + 1) % n;
    tris.push_back({a, b, 0}), tris.push_back({b, a, 1});
  }
  return make_mesh(v, tris);
}

/// Convex hull of n seeded random points on an ellipsoid with axes 1, ay, az.
inline Mesh ellipsoid_hull(int n, std::uint64_t seed, double ay, double az) {
  unfold_detail::Rng rng(seed);
  std::vector<Point3> pts;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d d = rng.direction();
    pts.emplace_back(d.x(), ay * d.y(), az * d.z());
  }
  return convex_hull_mesh(pts);
}

inline std::string shared_data() { return DCSHELL_SHARED_DATA; }
inline bool have_shared_data() { return std::filesystem::is_directory(shared_data()); }

}  // namespace dcshell::test
