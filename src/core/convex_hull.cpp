// Stage "hulls": CGAL convex_hull_3 on the input doubles (Epick: exact predicates, and the hull
// needs no constructions, so it is exactly the hull of the given points).
#include "dcshell/convex_hull.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/convex_hull_3.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

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

namespace {

// Delaunay triangulation of a strictly convex, exactly planar polygon given in boundary order:
// fat triangles, decided by exact predicates on the polygon projected along its dominant normal
// axis (dropping a coordinate is exact). Corners are inserted in the given order, so ties
// (cocircular corners) are broken the same way every time. Triangles keep the polygon's
// orientation.
std::vector<std::array<std::size_t, 3>> triangulate_convex_facet(const std::vector<Point3>& poly) {
  const std::size_t k = poly.size();
  if (k == 3) return {{0, 1, 2}};
  // Newell normal: only its dominant axis and that axis' sign are used. Computed on coordinates
  // relative to the first corner and scaled by the polygon's extent, so products neither
  // underflow (tiny models) nor overflow (huge ones).
  double scale = 0;
  for (const auto& q : poly)
    for (int d = 0; d < 3; ++d) scale = std::max(scale, std::fabs(q[d] - poly[0][d]));
  auto rel = [&](std::size_t i, int d) { return (poly[i % k][d] - poly[0][d]) / scale; };
  double n[3] = {0, 0, 0};
  for (std::size_t i = 0; i < k; ++i)
    for (int d = 0; d < 3; ++d) {
      const int u = (d + 1) % 3, w = (d + 2) % 3;
      n[d] += (rel(i, u) - rel(i + 1, u)) * (rel(i, w) + rel(i + 1, w));
    }
  int axis = 0;
  for (int d = 1; d < 3; ++d)
    if (std::fabs(n[d]) > std::fabs(n[axis])) axis = d;
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;  // (u, w, axis) is right-handed
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, Epick>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb>;
  CGAL::Delaunay_triangulation_2<Epick, Tds> dt;
  for (std::size_t i = 0; i < k; ++i) dt.insert(Epick::Point_2(poly[i][u], poly[i][w]))->info() = i;
  std::vector<std::array<std::size_t, 3>> tris;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    std::array<std::size_t, 3> t{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    if (n[axis] < 0) std::swap(t[1], t[2]);  // seen from below the projection plane
    tris.push_back(t);
  }
  return tris;
}

}  // namespace

Mesh convex_hull_mesh(const std::vector<Point3>& points) {
  Mesh raw;
  if (!spans_3d(points)) return raw;
  CGAL::convex_hull_3(points.begin(), points.end(), raw);
  // CGAL's quickhull orders work by vertex-handle address, so where input points are coplanar
  // on a hull facet (cut faces, boxes, grids), which of them become vertices and how the facet
  // is triangulated depend on the heap state: two calls in one process can differ. Rebuild a
  // canonical hull: the exact facets (maximal coplanar regions), only their corners, each facet
  // Delaunay-triangulated (fat triangles), vertices in lexicographic order, triangles sorted.
  const auto nf = raw.number_of_faces() + raw.number_of_removed_faces();
  std::vector<std::size_t> group(nf);
  std::iota(group.begin(), group.end(), std::size_t(0));
  const auto find = [&](std::size_t f) {
    while (group[f] != f) f = group[f] = group[group[f]];
    return f;
  };
  for (auto e : raw.edges()) {
    const auto h = raw.halfedge(e), o = raw.opposite(h);
    const Point3& p = raw.point(raw.source(h));
    const Point3& q = raw.point(raw.target(h));
    const Point3& r = raw.point(raw.target(raw.next(h)));
    const Point3& s = raw.point(raw.target(raw.next(o)));
    if (CGAL::orientation(p, q, r, s) == CGAL::COPLANAR) {
      const auto a = find(std::size_t(raw.face(h))), b = find(std::size_t(raw.face(o)));
      group[std::max(a, b)] = std::min(a, b);
    }
  }
  const auto same = [&](Mesh::Halfedge_index h) {
    return find(std::size_t(raw.face(h))) == find(std::size_t(raw.face(raw.opposite(h))));
  };
  // Facet boundaries, walked once from each facet's first boundary halfedge; straight-through
  // vertices (on an edge of the polytope) are dropped, as are facet-interior ones.
  std::vector<std::vector<Mesh::Vertex_index>> facets;
  std::vector<char> seen(raw.number_of_halfedges() + raw.number_of_removed_halfedges(), 0);
  for (auto h0 : raw.halfedges()) {
    if (raw.is_border(h0) || seen[std::size_t(h0)] || same(h0)) continue;
    std::vector<Mesh::Vertex_index> ring;
    auto h = h0;
    do {
      seen[std::size_t(h)] = 1;
      ring.push_back(raw.target(h));
      h = raw.next(h);
      while (same(h)) h = raw.next(raw.opposite(h));
    } while (h != h0);
    std::vector<Mesh::Vertex_index> corners;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const auto& a = raw.point(ring[(i + ring.size() - 1) % ring.size()]);
      const auto& c = raw.point(ring[(i + 1) % ring.size()]);
      if (!CGAL::collinear(a, raw.point(ring[i]), c)) corners.push_back(ring[i]);
    }
    facets.push_back(std::move(corners));
  }
  std::vector<Mesh::Vertex_index> order;
  std::vector<char> is_corner(raw.number_of_vertices() + raw.number_of_removed_vertices(), 0);
  for (const auto& f : facets)
    for (auto v : f)
      if (!is_corner[std::size_t(v)]) is_corner[std::size_t(v)] = 1, order.push_back(v);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return raw.point(a) < raw.point(b); });
  std::vector<std::size_t> rank(is_corner.size());
  for (std::size_t i = 0; i < order.size(); ++i) rank[std::size_t(order[i])] = i;
  std::vector<std::array<std::size_t, 3>> tris;
  std::vector<Point3> poly;
  for (const auto& f : facets) {
    poly.clear();
    std::vector<std::size_t> ids;
    for (auto v : f) poly.push_back(raw.point(v)), ids.push_back(rank[std::size_t(v)]);
    // Start at the smallest corner so the triangulation does not depend on the walk's start.
    const auto first = std::min_element(ids.begin(), ids.end()) - ids.begin();
    std::rotate(ids.begin(), ids.begin() + first, ids.end());
    std::rotate(poly.begin(), poly.begin() + first, poly.end());
    for (const auto& t : triangulate_convex_facet(poly)) {
      std::array<std::size_t, 3> tri{ids[t[0]], ids[t[1]], ids[t[2]]};
      std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
      tris.push_back(tri);
    }
  }
  std::sort(tris.begin(), tris.end());
  Mesh hull;
  std::vector<Mesh::Vertex_index> vs;
  for (auto v : order) vs.push_back(hull.add_vertex(raw.point(v)));
  for (const auto& t : tris) hull.add_face(vs[t[0]], vs[t[1]], vs[t[2]]);
  return hull;
}

Mesh pruned_convex_hull_mesh(const std::vector<Point3>& points, double delta, const std::vector<Point3>& keep,
                             std::size_t* pruned) {
  // The distance of a vertex to the hull of the others is at most its distance to any segment
  // or triangle of its neighbours (all inside that hull), so one that close can go. Neighbours
  // of a pruned vertex wait for the next round (their bound was measured against it); each of the
  // two rounds gets half of delta, so the pruned hull is within delta of the hull of the points.
  // (A round costs a hull: on a 24,864-face sphere cut by a plane, 95 cut vertices go in the
  // first, 16 in the second, 4 more in two further rounds.)
  constexpr int kRounds = 2;
  const double d = delta / kRounds, d2 = d * d;
  Mesh hull = convex_hull_mesh(points);
  for (int round = 0; round < kRounds && delta > 0 && hull.number_of_vertices() > 4; ++round) {
    std::vector<char> drop(hull.number_of_vertices(), 0), locked(hull.number_of_vertices(), 0);
    std::vector<Point3> link;
    bool any = false;
    for (auto v : hull.vertices()) {
      const Point3& q = hull.point(v);
      if (locked[v.idx()] || std::binary_search(keep.begin(), keep.end(), q)) continue;
      // Cheap refusal first: every point of the neighbours' hull lies at least min_w -m.(w - q)
      // below q along the vertex normal m, so a vertex whose neighbours all lie more than d below
      // it (any vertex with a visible bend) is farther than d from that hull.
      Eigen::Vector3d m = Eigen::Vector3d::Zero();
      for (auto f : CGAL::faces_around_target(hull.halfedge(v), hull)) {
        const auto h = hull.halfedge(f);
        const Point3 &a = hull.point(hull.source(h)), &b = hull.point(hull.target(h)),
                     &c = hull.point(hull.target(hull.next(h)));
        m += Eigen::Vector3d(b.x() - a.x(), b.y() - a.y(), b.z() - a.z())
                 .cross(Eigen::Vector3d(c.x() - a.x(), c.y() - a.y(), c.z() - a.z()));
      }
      link.clear();
      double rise = -std::numeric_limits<double>::infinity();
      const double mn = m.norm();
      for (auto w : CGAL::vertices_around_target(hull.halfedge(v), hull)) {
        const Point3& x = hull.point(w);
        link.push_back(x);
        if (mn > 0) rise = std::max(rise, m.dot(Eigen::Vector3d(x.x() - q.x(), x.y() - q.y(), x.z() - q.z())) / mn);
      }
      if (mn > 0 && rise < -2 * d) continue;
      bool close = false;
      for (std::size_t i = 0; i < link.size() && !close; ++i)
        for (std::size_t j = i + 1; j < link.size() && !close; ++j) {
          close = CGAL::squared_distance(q, Epick::Segment_3(link[i], link[j])) < d2;
          for (std::size_t k = j + 1; k < link.size() && !close; ++k)
            close = !CGAL::collinear(link[i], link[j], link[k]) &&
                    CGAL::squared_distance(q, Epick::Triangle_3(link[i], link[j], link[k])) < d2;
        }
      if (!close) continue;
      drop[v.idx()] = 1;
      any = true;
      for (auto w : CGAL::vertices_around_target(hull.halfedge(v), hull)) locked[w.idx()] = 1;
    }
    if (!any) break;
    std::vector<Point3> rest;
    for (auto v : hull.vertices())
      if (!drop[v.idx()]) rest.push_back(hull.point(v));
      else if (pruned) ++*pruned;
    hull = convex_hull_mesh(rest);
  }
  return hull;
}

double bbox_diagonal(const std::vector<Point3>& points) {
  if (points.empty()) return 0;
  const CGAL::Bbox_3 b = CGAL::bbox_3(points.begin(), points.end());
  return std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) + CGAL::square(b.zmax() - b.zmin()));
}

std::vector<Point3> mesh_points(const Mesh& mesh) {
  std::vector<Point3> pts;
  pts.reserve(mesh.number_of_vertices());
  for (auto v : mesh.vertices()) pts.push_back(mesh.point(v));
  return pts;
}

}  // namespace dcshell
