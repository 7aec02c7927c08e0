// Exact convex polytope: the representation every certificate rests on.
//
// Boundary representation over Epeck (lazy exact): face loops with their supporting planes.
// A vertex created by clipping is the meet of three planes (two face planes and the cutting
// plane), never an interpolation along an edge, so exact numbers stay of bounded size however
// many clips a polytope has been through.
#pragma once
#include <CGAL/Exact_rational.h>

#include <vector>

#include "dcshell/convex_polytope.h"
#include "dcshell/cut_plane.h"
#include "dcshell/kernel.h"

namespace dcshell {

using ExactRational = CGAL::Exact_rational;

struct ExactPolytope {
  using Point = Epeck::Point_3;
  using Plane = Epeck::Plane_3;
  struct Face {
    Plane plane;            ///< outward: the polytope lies on its negative side
    std::vector<int> loop;  ///< vertex indices, counter-clockwise seen from outside
    int tag = -1;           ///< where the plane came from (caller-defined)
  };
  std::vector<Point> vertices;
  std::vector<Face> faces;

  /// True when the polytope has no interior (the result of clipping everything away).
  bool empty() const { return faces.size() < 4; }
};

/// Builds the polytope of the convex hull of `points` (CGAL convex_hull_3 with exact predicates
/// on the doubles); coplanar hull triangles are merged into one polygonal face. Returns an empty
/// polytope when the points are coplanar or fewer than 4. Every face gets `tag`.
ExactPolytope exact_hull(const std::vector<Point3>& points, int tag = 0);

/// The exact plane normal·x = offset, oriented so that normal·x > offset is its positive side.
Epeck::Plane_3 exact_plane(const CutPlane& plane);

/// P ∩ {x : h(x) <= 0} (h's negative side, boundary included). Exact. The cap face gets `tag`.
/// The result is empty when P has no interior point strictly on h's negative side.
ExactPolytope clip(const ExactPolytope& p, const Epeck::Plane_3& h, int tag);

/// Exact intersection of two convex polytopes (empty when their interiors are disjoint).
ExactPolytope intersect(const ExactPolytope& a, const ExactPolytope& b);

/// Exact volume.
ExactRational exact_volume(const ExactPolytope& p);

/// Certified enclosure of the volume, from the interval approximations that Epeck keeps of
/// every coordinate: the filter tried before exact_volume. `tight` first evaluates exactly every
/// vertex whose coordinates are not yet known to the ulp (slower, a much narrower enclosure).
CGAL::Interval_nt<false> volume_interval(const ExactPolytope& p, bool tight = false);

/// Volume from rounded coordinates (fast; for reporting and optimisation only).
double approximate_volume(const ExactPolytope& p);

/// Rounds to doubles (nearest), keeping loops and tags: the fast-path representation.
ConvexPolytope to_double(const ExactPolytope& p);

/// Sign of h at point q, exactly.
CGAL::Oriented_side side(const Epeck::Plane_3& h, const Epeck::Point_3& q);

}  // namespace dcshell
