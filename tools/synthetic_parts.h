// Seeded synthetic composite inputs with deep overlaps (random boxes, plank stars, spheres
// around one point), shared by the benchmarks and the tests: the same parts on every platform.
#pragma once
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "dcshell/load_parts.h"

namespace dcshell::synthetic {

/// Uniform in [a, b) from the top 53 bits of one draw: unlike std::uniform_real_distribution,
/// the same on every standard library.
inline double uniform(std::mt19937_64& rng, double a, double b) { return a + (b - a) * double(rng() >> 11) * 0x1p-53; }

/// n boxes, centres uniform in [0, side]^3, half extents uniform in [h_min, h_max], uniformly
/// random rotations, drawn from `rng` with hand-made uniforms so that every platform generates
/// the same boxes.
inline std::vector<Part> random_boxes(std::mt19937_64& rng, int n, double side, double h_min, double h_max) {
  auto u = [&](double a, double b) { return uniform(rng, a, b); };
  std::vector<Part> parts(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double c[3] = {u(0, side), u(0, side), u(0, side)}, h[3] = {u(h_min, h_max), u(h_min, h_max), u(h_min, h_max)};
    // Uniform rotation from a uniform unit quaternion (Shoemake).
    const double u1 = u(0, 1), u2 = u(0, 2 * M_PI), u3 = u(0, 2 * M_PI);
    const double x = std::sqrt(1 - u1) * std::sin(u2), y = std::sqrt(1 - u1) * std::cos(u2),
                 z = std::sqrt(u1) * std::sin(u3), w = std::sqrt(u1) * std::cos(u3);
    const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                            {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                            {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    parts[std::size_t(k)].name = "box" + std::to_string(k);
    for (int corner = 0; corner < 8; ++corner) {
      const double p[3] = {(corner & 1 ? 1 : -1) * h[0], (corner & 2 ? 1 : -1) * h[1], (corner & 4 ? 1 : -1) * h[2]};
      double q[3];
      for (int i = 0; i < 3; ++i) q[i] = c[i] + r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2];
      parts[std::size_t(k)].points.emplace_back(q[0], q[1], q[2]);
    }
  }
  return parts;
}

/// k planks 8 x 0.6 x 0.1, the i-th turned by 180·i/k degrees about the z axis and raised by
/// dz·i: with k·dz < 0.1 every subset of them overlaps around the axis.
inline std::vector<Part> plank_star(int k, double dz) {
  std::vector<Part> planks(static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i) {
    const double a = M_PI * i / k, c = std::cos(a), s = std::sin(a);
    planks[std::size_t(i)].name = "plank" + std::to_string(i);
    for (int corner = 0; corner < 8; ++corner) {
      const double x = corner & 1 ? 4 : -4, y = corner & 2 ? 0.3 : -0.3, z = corner & 4 ? 0.05 : -0.05;
      planks[std::size_t(i)].points.emplace_back(c * x - s * y, s * x + c * y, z + dz * i);
    }
  }
  return planks;
}

/// n UV spheres (lat x 2·lat grid, poles included), radii uniform in [0.8, 1.2], centres
/// uniform in [-spread, spread]^3: with a small spread every subset overlaps near the origin.
inline std::vector<Part> random_spheres(std::mt19937_64& rng, int n, int lat, double spread) {
  auto u = [&](double a, double b) { return uniform(rng, a, b); };
  std::vector<Part> parts(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double c[3] = {u(-spread, spread), u(-spread, spread), u(-spread, spread)}, r = u(0.8, 1.2);
    auto& pts = parts[std::size_t(k)].points;
    parts[std::size_t(k)].name = "sphere" + std::to_string(k);
    pts.emplace_back(c[0], c[1], c[2] + r);
    pts.emplace_back(c[0], c[1], c[2] - r);
    for (int i = 1; i < lat; ++i)
      for (int j = 0; j < 2 * lat; ++j) {
        const double th = M_PI * i / lat, ph = M_PI * j / lat;
        pts.emplace_back(c[0] + r * std::sin(th) * std::cos(ph), c[1] + r * std::sin(th) * std::sin(ph), c[2] + r * std::cos(th));
      }
  }
  return parts;
}

/// n cones along z, each the hull of its apex and `points` random points on its surface (side and
/// base by area), base radius and height uniform in [0.5, 1.5], centres uniform in [0, side]^3.
/// The side is ruled: the hull's edges run along it to the apex, whose star then holds hundreds
/// of faces and spans the whole cone; the base is exactly flat (one z), as a CAD cone's is.
inline std::vector<Part> random_cones(std::mt19937_64& rng, int n, int points, double side) {
  auto u = [&](double a, double b) { return uniform(rng, a, b); };
  std::vector<Part> parts(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double c[3] = {u(0, side), u(0, side), u(0, side)}, r = u(0.5, 1.5), h = u(0.5, 1.5);
    const double base = c[2] - h / 2, apex = c[2] + h / 2;
    parts[std::size_t(k)].name = "cone" + std::to_string(k);
    auto& pts = parts[std::size_t(k)].points;
    pts.emplace_back(c[0], c[1], apex);
    const double side_area = M_PI * r * std::hypot(r, h), base_area = M_PI * r * r;
    for (int i = 0; i < points; ++i) {
      const double pick = u(0, side_area + base_area), th = u(0, 2 * M_PI), f = std::sqrt(u(0, 1));
      // f: distance from the apex (side) or the axis (base) as a fraction, uniform by area.
      const bool on_side = pick < side_area;
      const double rho = r * f, z = on_side ? apex - h * f : base;
      pts.emplace_back(c[0] + rho * std::cos(th), c[1] + rho * std::sin(th), z);
    }
  }
  return parts;
}

}  // namespace dcshell::synthetic
