#include "dcshell/trim.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "dcshell/convex_hull.h"

namespace dcshell {

namespace {

// Keeps the first of every group of points closer than `delta` to an already kept one (index
// order, so deterministic). The hull of a subset lies inside the hull of the set, so nothing
// the caller proved about the points' hull is lost; what goes are the ulp-long edges and
// needle faces that rounding leaves where a cut passes next to a hull vertex.
std::vector<Point3> merge_close_points(const std::vector<Point3>& pts, double delta, std::size_t* merged) {
  if (!(delta > 0)) return pts;
  auto cell = [&](double x) { return static_cast<std::int64_t>(std::floor(x / delta)); };
  auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return (static_cast<std::uint64_t>(i) * 73856093ULL) ^ (static_cast<std::uint64_t>(j) * 19349663ULL) ^
           (static_cast<std::uint64_t>(k) * 83492791ULL);
  };
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
  std::vector<Point3> out;
  out.reserve(pts.size());
  for (const auto& q : pts) {
    const std::int64_t i = cell(q.x()), j = cell(q.y()), k = cell(q.z());
    bool close = false;
    for (std::int64_t di = -1; di <= 1 && !close; ++di)
      for (std::int64_t dj = -1; dj <= 1 && !close; ++dj)
        for (std::int64_t dk = -1; dk <= 1 && !close; ++dk) {
          auto it = grid.find(key(i + di, j + dj, k + dk));
          if (it == grid.end()) continue;
          for (std::size_t o : it->second)
            if (CGAL::squared_distance(out[o], q) < delta * delta) {
              close = true;
              break;
            }
        }
    if (close) {
      ++*merged;
      continue;
    }
    grid[key(i, j, k)].push_back(out.size());
    out.push_back(q);
  }
  return out;
}

}  // namespace

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
  for (std::size_t i = 0; i < rounded.size(); ++i) {
    const Point3& q = rounded[i];
    // A vertex whose exact coordinates are doubles (a hull corner no cut touched: its interval
    // approximation is a single point) rounds to itself, which lies in the polytope: no test.
    // Only the vertices cuts created are tested, so an uncut hull of n vertices costs O(n).
    const auto& e = p.vertices[i];
    auto is_double = [](const Epeck::FT& x) { return CGAL::approx(x).inf() == CGAL::approx(x).sup(); };
    if ((is_double(e.x()) && is_double(e.y()) && is_double(e.z())) || inside(q)) {
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
  if (kept.size() < 4) return convex_hull_mesh(kept);
  const double diag = bbox_diagonal(kept);
  kept = merge_close_points(kept, kMergeDistance * diag, &st.merged_vertices);
  std::vector<Point3> hull_points;
  for (const auto& v : hull.vertices)
    hull_points.emplace_back(CGAL::to_double(v.x()), CGAL::to_double(v.y()), CGAL::to_double(v.z()));
  std::sort(hull_points.begin(), hull_points.end());
  // The cut's own vertices within that distance of the hull of the others go too (the hull's are
  // where the part or the remesher put them: its 1e-9 domes and lifted splits are near-flat on
  // purpose): a cut ending a few ulps off the line of a hull edge leaves slivers along it.
  return pruned_convex_hull_mesh(kept, kMergeDistance * diag, hull_points, &st.flat_vertices);
}

}  // namespace dcshell
