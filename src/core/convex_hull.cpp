// Stage "hulls": CGAL convex_hull_3 on the input doubles (Epick: exact predicates, and the hull
// needs no constructions, so it is exactly the hull of the given points).
#include "dcshell/convex_hull.h"

#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>

namespace dcshell {

bool spans_3d(const std::vector<Point3>& points) {
  if (points.size() < 4) return false;
  // Find three non-collinear points, then any point off their plane.
  const Point3& a = points[0];
  std::size_t i = 1;
  while (i < points.size() && points[i] == a) ++i;
  if (i == points.size()) return false;
  const Point3& b = points[i];
  std::size_t j = i + 1;
  while (j < points.size() && CGAL::collinear(a, b, points[j])) ++j;
  if (j == points.size()) return false;
  const Point3& c = points[j];
  for (const auto& p : points)
    if (CGAL::orientation(a, b, c, p) != CGAL::COPLANAR) return true;
  return false;
}

Mesh convex_hull_mesh(const std::vector<Point3>& points) {
  Mesh raw;
  if (!spans_3d(points)) return raw;
  CGAL::convex_hull_3(points.begin(), points.end(), raw);
  // Canonical order (vertices lexicographic, each triangle starting at its smallest index,
  // triangles sorted): the hull code orders its output by memory address in places, so two
  // calls in one process can differ; everything downstream must not.
  std::vector<Mesh::Vertex_index> order(raw.vertices().begin(), raw.vertices().end());
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return raw.point(a) < raw.point(b); });
  std::vector<std::size_t> rank(raw.number_of_vertices() + raw.number_of_removed_vertices());
  for (std::size_t i = 0; i < order.size(); ++i) rank[std::size_t(order[i])] = i;
  std::vector<std::array<std::size_t, 3>> tris;
  for (auto f : raw.faces()) {
    std::array<std::size_t, 3> t;
    std::size_t k = 0;
    for (auto v : CGAL::vertices_around_face(raw.halfedge(f), raw)) t[k++] = rank[std::size_t(v)];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    tris.push_back(t);
  }
  std::sort(tris.begin(), tris.end());
  Mesh hull;
  std::vector<Mesh::Vertex_index> vs;
  for (auto v : order) vs.push_back(hull.add_vertex(raw.point(v)));
  for (const auto& t : tris) hull.add_face(vs[t[0]], vs[t[1]], vs[t[2]]);
  return hull;
}

std::vector<Point3> mesh_points(const Mesh& mesh) {
  std::vector<Point3> pts;
  pts.reserve(mesh.number_of_vertices());
  for (auto v : mesh.vertices()) pts.push_back(mesh.point(v));
  return pts;
}

}  // namespace dcshell
