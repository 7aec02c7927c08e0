// Stage "hulls": convex hull of a part as a triangle Surface_mesh.
#pragma once
#include <vector>

#include "dcshell/kernel.h"

namespace dcshell {

/// Convex hull (CGAL convex_hull_3, exact predicates on the input doubles, so the result is
/// exactly convex and its vertices are input points). Canonical: only the polytope's corners
/// are vertices (points inside a facet or on an edge are dropped), each facet is Delaunay-
/// triangulated, vertices are in lexicographic order and triangles sorted, so the result depends
/// only on the set of points. Triangulated, outward. Empty mesh when the points are coplanar or
/// fewer than 4.
Mesh convex_hull_mesh(const std::vector<Point3>& points);

/// True when the points span 3D (at least 4 points, not all coplanar), decided exactly.
bool spans_3d(const std::vector<Point3>& points);

/// convex_hull_mesh(points) less its vertices within `delta` of the hull of the others: a vertex a
/// few ulps off the line of an edge (its faces are slivers along the edge, whose folds have no
/// usable direction and whose normals are rounding noise) or barely above the plane of its
/// neighbours. Points in `keep` (sorted) stay. The result lies inside the hull of `points` and
/// within `delta` of it, so whatever held inside the one holds for the other; its vertices are
/// input points. `pruned` (if given) is increased by the number left out.
Mesh pruned_convex_hull_mesh(const std::vector<Point3>& points, double delta, const std::vector<Point3>& keep = {},
                             std::size_t* pruned = nullptr);

/// Length of the diagonal of the points' bounding box (0 for none): the size tolerances scale with.
double bbox_diagonal(const std::vector<Point3>& points);

/// Points of a mesh, in vertex order.
std::vector<Point3> mesh_points(const Mesh& mesh);

}  // namespace dcshell
