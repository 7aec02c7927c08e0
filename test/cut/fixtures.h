// Test polytopes for the cut module.
#pragma once
#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "dcshell/convex_polytope.h"
#include "dcshell/polytope_clip.h"

namespace dcshell::test {

// Axis-aligned box with quadrilateral faces (vertices of degree 3).
inline ConvexPolytope box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int tag = 0) {
  ConvexPolytope p;
  for (int i = 0; i < 8; ++i)
    p.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  p.faces = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  p.face_tags.assign(6, tag);
  return p;
}

inline ConvexPolytope unit_cube(int tag = 0) { return box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), tag); }

inline ConvexPolytope translated(ConvexPolytope p, const Eigen::Vector3d& t) {
  for (auto& v : p.vertices) v += t;
  return p;
}

inline double u01(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

// Hull of n random points in a ball (general position: simple vertices, triangles).
inline ConvexPolytope random_hull(std::uint64_t seed, int n, const Eigen::Vector3d& centre, double radius) {
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Vector3d> pts;
  while (int(pts.size()) < n) {
    Eigen::Vector3d x(2 * u01(rng) - 1, 2 * u01(rng) - 1, 2 * u01(rng) - 1);
    if (x.squaredNorm() <= 1) pts.push_back(centre + radius * x);
  }
  return convex_hull_polytope(pts);
}

// Hull of the integer lattice points in a ball: many coplanar triangles and vertices of high
// degree (non-simple), axis-parallel edges and faces.
inline ConvexPolytope lattice_ball(int r) {
  std::vector<Eigen::Vector3d> pts;
  for (int x = -r; x <= r; ++x)
    for (int y = -r; y <= r; ++y)
      for (int z = -r; z <= r; ++z)
        if (x * x + y * y + z * z <= r * r) pts.emplace_back(x, y, z);
  return convex_hull_polytope(pts);
}

// Pyramid over a regular k-gon: the apex has degree k, the base is one k-gon face.
inline ConvexPolytope pyramid(int k) {
  ConvexPolytope p;
  for (int i = 0; i < k; ++i) p.vertices.emplace_back(std::cos(2 * M_PI * i / k), std::sin(2 * M_PI * i / k), 0.0);
  p.vertices.emplace_back(0.1, -0.2, 1.3);
  std::vector<int> base;
  for (int i = k - 1; i >= 0; --i) base.push_back(i);
  p.faces.push_back(base);
  for (int i = 0; i < k; ++i) p.faces.push_back({i, (i + 1) % k, k});
  p.face_tags.assign(p.faces.size(), 0);
  return p;
}

inline ConvexPolytope tetrahedron() {
  ConvexPolytope p;
  p.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  p.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  p.face_tags.assign(4, 0);
  return p;
}

inline Eigen::Vector3d random_unit(std::mt19937_64& rng) {
  while (true) {
    Eigen::Vector3d x(2 * u01(rng) - 1, 2 * u01(rng) - 1, 2 * u01(rng) - 1);
    const double n = x.norm();
    if (n > 0.1 && n <= 1) return x / n;
  }
}

}  // namespace dcshell::test
