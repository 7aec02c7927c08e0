// Cut-plane method "lsf": least-squares plane through the intersection curve of two shells.
#pragma once
#include "dcshell/convex_polytope.h"
#include "dcshell/cut_plane.h"

namespace dcshell {

/// Plane fitted (CGAL linear_least_squares_fitting_3, segments) to the curve ∂a ∩ ∂b: the
/// edges of a ∩ b between a face of a and a face of b. When the curve is empty (one shell
/// inside the other) the vertices of a ∩ b are fitted instead; when a and b are disjoint, the
/// plane halfway between their centroids. Unit normal oriented from a toward b (centroids).
CutPlane lsf_cut_plane(const ConvexPolytope& a, const ConvexPolytope& b);

/// The same with a ∩ b given, faces tagged 0 (from a) and 1 (from b): `tagged_intersection`.
CutPlane lsf_cut_plane(const ConvexPolytope& a, const ConvexPolytope& b, const ConvexPolytope& a_cap_b);

}  // namespace dcshell
