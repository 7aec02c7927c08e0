// Double-precision operations on ConvexPolytope: construction, half-space clipping,
// intersection, volume and plane sections. This is the fast path of the cut-plane optimisers
// and the pipeline's sweeps; certified results are recomputed exactly (exact_polytope.h).
#pragma once
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "dcshell/convex_polytope.h"
#include "dcshell/cut_plane.h"
#include "dcshell/kernel.h"

namespace dcshell {

/// Copies a closed convex mesh with outward faces. Every face gets `tag`.
ConvexPolytope polytope_from_mesh(const Mesh& mesh, int tag = 0);

/// Convex hull of points (CGAL convex_hull_3, triangular faces), every face tagged `tag`, in a
/// canonical order (vertices sorted lexicographically, faces sorted).
/// Empty when the points do not span 3D (fewer than 4 points, coplanar, collinear).
ConvexPolytope convex_hull_polytope(const std::vector<Eigen::Vector3d>& points, int tag = 0);

/// Triangulated surface mesh of the polytope (fan triangulation of each face).
Mesh to_mesh(const ConvexPolytope& p);

/// The part of `p` with plane.normal·x <= plane.offset. Vertices within a small relative
/// tolerance of the plane count as on it (no slivers); the crossing point of an edge is shared
/// by both faces of the edge; the cut face is tagged `cap_tag`. Faces reduced to fewer than
/// three vertices are dropped. Returns an empty polytope when nothing of positive volume is
/// left, and `p` unchanged when the plane does not cut it. The normal need not be unit.
ConvexPolytope clip(const ConvexPolytope& p, const CutPlane& plane, int cap_tag);

/// Outward plane of face f (unit normal; offset from the face's vertex mean).
CutPlane face_plane(const ConvexPolytope& p, std::size_t f);

/// p ∩ q: the operand with fewer vertices clipped by every face plane of the other. Faces keep
/// their tags (p's face_tags, or 0 when p has none; q's, or 1), so one can tell which faces
/// came from which operand.
ConvexPolytope intersect(const ConvexPolytope& p, const ConvexPolytope& q);

/// a ∩ b with the faces from a tagged 0 and those from b tagged 1 (so the curve ∂a ∩ ∂b is
/// the set of edges between a 0-face and a 1-face).
ConvexPolytope tagged_intersection(const ConvexPolytope& a, const ConvexPolytope& b);

/// Volume (positive for outward faces; 0 for an empty polytope).
double volume(const ConvexPolytope& p);

/// Centre of mass of the solid (vertex mean when the volume is zero).
Eigen::Vector3d centroid(const ConvexPolytope& p);

/// min and max of n·v over the vertices ({+inf, -inf} when empty).
std::pair<double, double> height_range(const ConvexPolytope& p, const Eigen::Vector3d& n);

/// Area of p ∩ {normal·x = offset} and its first moment ∫ x dA. These are the derivatives
/// of V(n, d) = vol(p ∩ {n·x >= d}): dV/dd = -area/|n|, and for a change δn of the normal
/// dV = δn·moment/|n| (exactly for unit n). Vertices on the plane count as below it, so the
/// result is well defined (a consistent perturbation) even when the plane contains a face.
struct PlaneSection {
  double area = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
};
PlaneSection section(const ConvexPolytope& p, const CutPlane& plane);

}  // namespace dcshell
