#include "dcshell/trim.h"

#include "dcshell/convex_hull.h"

namespace dcshell {

ExactPolytope trim_exact(const ExactPolytope& hull, const std::vector<CutPlane>& keep_below) {
  ExactPolytope p = hull;
  for (std::size_t k = 0; k < keep_below.size() && !p.empty(); ++k)
    p = clip(p, exact_plane(keep_below[k]), -2 - int(k));
  return p;
}

Mesh trim_shell(const ExactPolytope& hull, const std::vector<CutPlane>& keep_below, TrimStats* stats) {
  TrimStats local;
  TrimStats& st = stats ? *stats : local;
  ExactPolytope p = trim_exact(hull, keep_below);
  if (p.empty()) return Mesh();
  // Every constraint the rounded vertices must meet, as exact planes.
  std::vector<Epeck::Plane_3> planes;
  for (const auto& c : keep_below) planes.push_back(exact_plane(c));
  for (const auto& f : hull.faces) planes.push_back(f.plane);
  auto inside = [&](const Point3& q) {
    Epeck::Point_3 e(q.x(), q.y(), q.z());
    for (const auto& h : planes)
      if (h.oriented_side(e) == CGAL::ON_POSITIVE_SIDE) return false;
    return true;
  };
  std::vector<Point3> rounded;
  rounded.reserve(p.vertices.size());
  for (const auto& v : p.vertices) rounded.emplace_back(CGAL::to_double(v.x()), CGAL::to_double(v.y()), CGAL::to_double(v.z()));
  // The vertex mean of a full-dimensional polytope is interior: the direction to move along.
  double cx = 0, cy = 0, cz = 0;
  for (const auto& q : rounded) cx += q.x(), cy += q.y(), cz += q.z();
  const double n = double(rounded.size());
  const Point3 c(cx / n, cy / n, cz / n);
  std::vector<Point3> kept;
  kept.reserve(rounded.size());
  for (const auto& q : rounded) {
    if (inside(q)) {
      kept.push_back(q);
      continue;
    }
    bool fixed = false;
    for (double t = 0x1p-50; t <= 0.25 && !fixed; t *= 2) {
      Point3 m(q.x() + t * (c.x() - q.x()), q.y() + t * (c.y() - q.y()), q.z() + t * (c.z() - q.z()));
      if (inside(m)) {
        kept.push_back(m);
        fixed = true;
      }
    }
    if (fixed)
      ++st.nudged_vertices;
    else
      ++st.dropped_vertices;
  }
  return convex_hull_mesh(kept);
}

}  // namespace dcshell
