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

/// Points of a mesh, in vertex order.
std::vector<Point3> mesh_points(const Mesh& mesh);

}  // namespace dcshell
