// Stage "certify": exact convexity and pairwise interior-disjointness.
#include "dcshell/certify.h"

#include <CGAL/boost/graph/helpers.h>

#include "dcshell/convex_hull.h"
#include "dcshell/exact_polytope.h"
#include "dcshell/mesh_volume.h"
#include "dcshell/overlaps.h"

#include <map>
#include <numeric>

namespace dcshell {

bool CertificationReport::certified() const {
  for (const auto& m : meshes)
    if (!m.ok()) return false;
  return overlaps.empty();
}

ConvexityVerdict check_convexity(const Mesh& mesh) {
  ConvexityVerdict v;
  if (mesh.number_of_faces() == 0) {
    v.reason = "no faces";
    return v;
  }
  if (!CGAL::is_closed(mesh)) {
    v.reason = "not closed (has boundary edges)";
    return v;
  }
  // Connected components of faces across edges (union–find; the mesh is const).
  std::vector<std::size_t> root(mesh.number_of_faces() + mesh.number_of_removed_faces());
  std::iota(root.begin(), root.end(), 0);
  auto find = [&](std::size_t x) {
    while (root[x] != x) x = root[x] = root[root[x]];
    return x;
  };
  for (auto e : mesh.edges()) {
    auto h = mesh.halfedge(e);
    root[find(std::size_t(mesh.face(h)))] = find(std::size_t(mesh.face(mesh.opposite(h))));
  }
  std::size_t ncc = 0;
  for (auto f : mesh.faces()) ncc += find(std::size_t(f)) == std::size_t(f);
  if (ncc != 1) {
    v.reason = "has " + std::to_string(ncc) + " connected components";
    return v;
  }
  long euler = long(mesh.number_of_vertices()) - long(mesh.number_of_edges()) + long(mesh.number_of_faces());
  if (euler != 2) {
    v.reason = "not of sphere topology (Euler characteristic " + std::to_string(euler) + ")";
    return v;
  }
  v.closed = true;
  CGAL::Mpzf six = six_signed_volume(mesh);
  v.volume = CGAL::to_double(six) / 6;
  v.outward = six > 0;
  // Convex: every face is planar and every vertex lies on the inner side (or on) its plane.
  std::vector<Point3> pts = mesh_points(mesh);
  // "Every vertex on the inner side of every face plane" is decided on the exact convex hull H
  // of the vertices instead of against every vertex: the halfspace is convex, so it holds for all
  // vertices iff it holds for H's corners, and on the convex polytope H a corner no neighbour of
  // which is farther from the plane is the farthest of all (the simplex method's argument). The
  // climb starts at the face's own corner, so it is O(degree) per face, not O(vertices).
  const Mesh hull = convex_hull_mesh(pts);
  std::vector<std::vector<Mesh::Vertex_index>> hull_nbr(hull.number_of_vertices() + hull.number_of_removed_vertices());
  std::map<Point3, Mesh::Vertex_index> hull_vertex;
  for (auto u : hull.vertices()) {
    hull_vertex.emplace(hull.point(u), u);
    for (auto h : CGAL::halfedges_around_target(hull.halfedge(u), hull)) hull_nbr[u].push_back(hull.source(h));
  }
  for (auto f : mesh.faces()) {
    std::vector<Point3> fp;
    for (auto h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh)) fp.push_back(mesh.point(mesh.target(h)));
    std::size_t k = 2;
    while (k < fp.size() && CGAL::collinear(fp[0], fp[1], fp[k])) ++k;
    if (k == fp.size()) {
      v.reason = "face " + std::to_string(std::size_t(f)) + " is degenerate (zero area)";
      return v;
    }
    // The non-collinear corner k and its predecessors fix the face orientation; for a
    // polygon the turn at fp[0], fp[1], fp[k] agrees with the loop's when the face is convex.
    const Point3 &a = fp[0], &b = fp[1], &c = fp[k];
    for (const auto& q : fp)
      if (CGAL::orientation(a, b, c, q) != CGAL::COPLANAR) {
        v.reason = "face " + std::to_string(std::size_t(f)) + " is not planar";
        return v;
      }
    if (hull.is_empty()) continue;  // all points coplanar: no vertex is off any face plane
    auto it = hull_vertex.find(a);
    Mesh::Vertex_index u = it != hull_vertex.end() ? it->second : *hull.vertices().begin();
    for (bool moved = true; moved;) {
      moved = false;
      for (auto w : hull_nbr[u])
        if (CGAL::compare_signed_distance_to_plane(a, b, c, hull.point(w), hull.point(u)) == CGAL::LARGER) {
          u = w;
          moved = true;
          break;
        }
    }
    if (CGAL::orientation(a, b, c, hull.point(u)) == CGAL::POSITIVE) {
      v.reason = "not convex: a vertex lies outside the plane of face " + std::to_string(std::size_t(f));
      return v;
    }
  }
  v.convex = true;
  if (!v.outward) {
    v.reason = CGAL::is_zero(six) ? "flat: encloses no volume (all vertices coplanar)" : "faces are oriented inward (negative volume)";
    return v;
  }
  // Closed, sphere-like and locally supporting everywhere: the surface bounds the hull of its
  // vertices exactly once iff the volumes agree (rules out multiply-covered surfaces).
  if (six_signed_volume(hull) != six) {
    v.convex = false;
    v.reason = "not convex: surface volume differs from its convex hull's";
  }
  return v;
}

CertificationReport certify(const std::vector<Mesh>& meshes) {
  CertificationReport rep;
  const std::size_t n = meshes.size();
  std::vector<std::vector<Point3>> pts(n);
  std::vector<ExactPolytope> poly(n);
  std::vector<double> vol(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    rep.meshes.push_back(check_convexity(meshes[i]));
    pts[i] = mesh_points(meshes[i]);
    poly[i] = exact_hull(pts[i], int(i));
    vol[i] = approximate_volume(poly[i]);
  }
  std::vector<CGAL::Bbox_3> boxes(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!pts[i].empty()) boxes[i] = CGAL::bbox_3(pts[i].begin(), pts[i].end());
  for (auto [i, j] : box_overlap_pairs(boxes)) {
    if (poly[i].empty() || poly[j].empty()) continue;
    // Filter: a face plane of one hull with every vertex of the other on or outside it
    // separates them (orientation on input doubles: exact and cheap, no constructions).
    auto separates = [&](std::size_t a, std::size_t b) {
      for (const auto& f : poly[a].faces) {
        bool all_out = true;
        for (const auto& q : pts[b])
          if (f.plane.oriented_side(Epeck::Point_3(q.x(), q.y(), q.z())) == CGAL::ON_NEGATIVE_SIDE) {
            all_out = false;
            break;
          }
        if (all_out) return true;
      }
      return false;
    };
    if (separates(i, j) || separates(j, i)) continue;
    ++rep.pairs_tested_exactly;
    ExactPolytope x = intersect(poly[i], poly[j]);
    if (x.empty()) continue;
    OverlapRecord r;
    r.a = i;
    r.b = j;
    auto iv = volume_interval(x);
    r.volume = 0.5 * (iv.inf() + iv.sup());
    double smaller = std::min(vol[i], vol[j]);
    r.ratio_to_smaller = smaller > 0 ? r.volume / smaller : 0.0;
    rep.overlaps.push_back(r);
  }
  return rep;
}

}  // namespace dcshell
