// Least-squares plane through the intersection curve of two convex shells.
#include "dcshell/cut_plane_lsf.h"

#include <CGAL/linear_least_squares_fitting_3.h>

#include <cstdint>
#include <unordered_map>

#include "dcshell/kernel.h"
#include "dcshell/polytope_clip.h"

namespace dcshell {

namespace {

Point3 to_point(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

CutPlane lsf_cut_plane(const ConvexPolytope& a, const ConvexPolytope& b) {
  return lsf_cut_plane(a, b, tagged_intersection(a, b));
}

CutPlane lsf_cut_plane(const ConvexPolytope& a, const ConvexPolytope& b, const ConvexPolytope& ab) {
  const Eigen::Vector3d ca = centroid(a), cb = centroid(b);
  Eigen::Vector3d axis = cb - ca;
  if (!(axis.norm() > 0)) axis = Eigen::Vector3d::UnitX();
  axis.normalize();

  // Tags 0 (faces of a) and 1 (faces of b): an edge of a ∩ b between a 0-face and a 1-face
  // lies on both boundaries, i.e. on the intersection curve.
  if (ab.empty()) return {axis, axis.dot(0.5 * (ca + cb))};
  std::unordered_map<std::uint64_t, int> edge_face;
  auto key = [](int u, int v) { return (std::uint64_t(std::uint32_t(u)) << 32) | std::uint32_t(v); };
  for (std::size_t f = 0; f < ab.faces.size(); ++f) {
    const auto& l = ab.faces[f];
    for (std::size_t i = 0; i < l.size(); ++i) edge_face.emplace(key(l[i], l[(i + 1) % l.size()]), int(f));
  }
  std::vector<Epick::Segment_3> curve;
  for (std::size_t f = 0; f < ab.faces.size(); ++f) {
    if (ab.face_tags[f] != 0) continue;
    const auto& l = ab.faces[f];
    for (std::size_t i = 0; i < l.size(); ++i) {
      const int u = l[i], v = l[(i + 1) % l.size()];
      auto it = edge_face.find(key(v, u));
      if (it != edge_face.end() && ab.face_tags[it->second] == 1 && ab.vertices[u] != ab.vertices[v])
        curve.emplace_back(to_point(ab.vertices[u]), to_point(ab.vertices[v]));
    }
  }
  Epick::Plane_3 plane;
  Point3 c;
  if (!curve.empty()) {
    CGAL::linear_least_squares_fitting_3(curve.begin(), curve.end(), plane, c, CGAL::Dimension_tag<1>());
  } else {  // nested shells: no curve; fit the overlap's vertices
    std::vector<Point3> pts;
    for (const auto& v : ab.vertices) pts.push_back(to_point(v));
    CGAL::linear_least_squares_fitting_3(pts.begin(), pts.end(), plane, c, CGAL::Dimension_tag<0>());
  }
  Eigen::Vector3d n(plane.a(), plane.b(), plane.c());
  n.normalize();
  if (n.dot(axis) < 0) n = -n;
  return {n, n.dot(Eigen::Vector3d(c.x(), c.y(), c.z()))};
}

}  // namespace dcshell
