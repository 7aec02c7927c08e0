// Stage "remesh", step 1: simplification of a convex shell by progressive hull (Sander et al.
// 2000). Every edge collapse moves the two end points to one new vertex chosen by a small LP
// (CGAL's QP solver): outside the plane of every face around the edge, so each new tetrahedron
// adds volume and the shell keeps enclosing what it enclosed; inside every constraint plane, so
// it keeps its distance from its neighbours; least added volume first, or (order_by_gain) most
// fatness gained per unit of added volume first.
#pragma once
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "dcshell/cut_plane.h"
#include "dcshell/kernel.h"

namespace dcshell {

/// Halfspaces a shell must stay in while it is remeshed: what keeps it disjoint from its
/// neighbours. Both kinds are decided exactly on the doubles given.
struct ShellConstraints {
  /// Keep normal·x <= offset (the pipeline's own cut planes).
  std::vector<CutPlane> cut_planes;
  /// Keep every point on or below the plane through p, q, r, i.e. orientation(p, q, r, x) is not
  /// POSITIVE ((q-p)x(r-p) points outward). Used for a face shared with a neighbour, whose exact
  /// plane through three double points is not a CutPlane in general.
  std::vector<std::array<Point3, 3>> face_planes;
  /// Keep every point on or below (ON_NEGATIVE_SIDE or on) the exact plane: a separator with
  /// rational coefficients, for neighbours that touch along an edge or a cut face rounded
  /// differently on each side, so that no plane through their own double points separates them.
  std::vector<Epeck::Plane_3> exact_planes;

  /// Exact test of one point against every halfspace.
  bool satisfied_by(const Point3& x) const;
  bool empty() const { return cut_planes.empty() && face_planes.empty() && exact_planes.empty(); }
};

struct SimplifyOptions {
  /// Stop before the volume would exceed this (absolute, in cubic units).
  double max_volume = std::numeric_limits<double>::infinity();
  /// Stop when the face count would drop below this (0: no target).
  std::size_t target_faces = 0;
  /// One pass collapses an independent set of edges (no two share a neighbourhood), so that
  /// simplification can alternate with smoothing; false runs to the stopping criteria.
  bool single_pass = false;
  /// Skip a collapse whose new faces are less fat (area-weighted) than the faces they replace:
  /// volume is then spent only where it helps the net. Off for plain face-count reduction.
  bool fatter_only = false;
  /// Order collapses by the area-weighted fatness they gain per unit of added volume (free ones
  /// first) instead of least added volume first.
  bool order_by_gain = false;
};

struct SimplifyStats {
  std::size_t collapses = 0;
  std::size_t infeasible = 0;  ///< edges whose LP had no solution (skipped)
  std::size_t rejected = 0;    ///< LP solutions that failed the exact checks (skipped)
};

/// Simplifies a closed, exactly convex, outward triangle mesh in place. Invariants, each checked
/// exactly after rounding the new vertex to doubles (a move failing one is not made): the mesh
/// stays exactly convex, contains the mesh it was given, satisfies `constraints`, and its
/// (floating-point) volume stays <= options.max_volume. Returns the number of collapses.
std::size_t simplify_progressive_hull(Mesh& mesh, const ShellConstraints& constraints,
                                      const SimplifyOptions& options, SimplifyStats* stats = nullptr);

}  // namespace dcshell
