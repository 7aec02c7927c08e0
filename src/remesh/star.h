// Private to the remesh module: a local replacement on a convex triangle mesh. Both the edge
// collapse and the vertex move replace the star of one or two vertices by a cone from a new
// point over the same ring; this is the shared bookkeeping, its LP/QP rows and its exact checks.
#pragma once
#include <Eigen/Core>
#include <vector>

#include "dcshell/fatness.h"  // FatArea: what the moves trade
#include "dcshell/kernel.h"
#include "dcshell/simplify.h"
#include "remesh/qp3.h"

namespace dcshell::remesh_detail {

using V = Mesh::Vertex_index;
using F = Mesh::Face_index;
using H = Mesh::Halfedge_index;

inline Eigen::Vector3d vec(const Point3& p) { return {p.x(), p.y(), p.z()}; }
inline Point3 pt(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

/// The star of the vertices being replaced and the ring around it.
struct Star {
  std::vector<V> removed;  ///< the vertex moved (1) or the edge's end points (2)
  std::vector<V> ring;     ///< counter-clockwise seen from outside: cone faces are (w, ring[i], ring[i+1])
  std::vector<F> faces;    ///< faces incident to a removed vertex
  /// For ring edge i (ring[i] -> ring[i+1]): the vertex opposite it in the face across, outside the star.
  std::vector<V> across;
  bool valid = false;      ///< false when the replacement would not be a manifold (link condition)
};

/// Star of one vertex.
Star vertex_star(const Mesh& mesh, V v);
/// Star of the edge of halfedge h (both end points replaced by one vertex).
Star edge_star(const Mesh& mesh, H h);

/// Star of the vertex c of face abc (h = a->b) grown by the face bad across h: the cone from a
/// new point over its ring (d inserted between a and b) is the edge flip ab -> cd with c moved,
/// which on a convex mesh needs c lifted above the plane of bad.
Star flip_star(const Mesh& mesh, H h);

/// Local frame of a replacement: y = (x - origin) / scale keeps the LP/QP coefficients O(1).
struct Frame {
  Eigen::Vector3d origin;
  double scale;
  Eigen::Vector3d to_local(const Eigen::Vector3d& x) const { return (x - origin) / scale; }
  Eigen::Vector3d to_world(const Eigen::Vector3d& y) const { return origin + scale * y; }
};

/// Exact: normal·x <= offset (a floating-point filter, rationals only near the plane).
bool on_or_below(const CutPlane& p, const Point3& x);

/// Rows a·y <= b keeping the new point y (local) on the inner side of every constraint plane,
/// with a margin of `margin` (in local units).
void add_constraint_rows(const ShellConstraints& c, const Frame& f, double margin, std::vector<Row>& rows);

/// Row for "x on or below the plane through p, q, r" (orientation(p, q, r, x) <= 0), with margin
/// (local units, along the unit normal). Degenerate (collinear) triples give no row.
void add_below_row(const Point3& p, const Point3& q, const Point3& r, const Frame& f, double margin,
                   std::vector<Row>& rows);

/// Exact: the mesh with `star` replaced by the cone from w is a closed convex surface with
/// non-degenerate faces, every point of `enclose` is inside or on it, and w satisfies `constraints`.
/// Points of `enclose` far from the star are skipped by an exact bounding-box argument.
bool replacement_is_valid(const Mesh& mesh, const Star& star, const Point3& w, const std::vector<Point3>& enclose,
                          const ShellConstraints& constraints);

/// Volume change (floating point) of replacing the star by the cone from w.
double volume_change(const Mesh& mesh, const Star& star, const Point3& w);

/// Every point on or below every face plane of the convex mesh `hull` (exact).
bool mesh_encloses(const Mesh& hull, const std::vector<Point3>& points);

/// Indices (ascending) of the points strictly above some face plane of the convex mesh `hull`
/// (exact). Points equal to a vertex of `hull` are never tested: a convex polytope's vertex is
/// above none of its faces (most points checked are kept vertices).
std::vector<std::size_t> points_outside(const Mesh& hull, const std::vector<Point3>& points);

/// Signed volume of a closed triangle mesh (floating point).
double mesh_volume(const Mesh& mesh);

}  // namespace dcshell::remesh_detail
