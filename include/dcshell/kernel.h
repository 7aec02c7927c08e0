// Kernels and mesh type used across dcshell. Instantiated in few translation units.
//
// Exactness is stated in the type:
//  - Epick: double coordinates, exact predicates (filtered). Input points are doubles,
//    so orientation tests on input points are exact: the fast path.
//  - Epeck: lazy exact constructions (interval filter, GMP rationals behind). Everything a
//    certificate rests on (intersections, volumes, disjointness) is decided here.
#pragma once
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

namespace dcshell {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;

using Point3 = Epick::Point_3;
using Vector3 = Epick::Vector_3;

/// Triangle (or polygon) surface mesh with double coordinates: what the remesher and
/// the unfolder operate on, and what is written to disk.
using Mesh = CGAL::Surface_mesh<Point3>;

}  // namespace dcshell
