// Private to the remesh module: fat triangulations of a convex polygon with interior (Steiner)
// points. A cut face has corners only on its boundary, so every triangulation of it is fan-like
// where the boundary is uneven; points inside let it have fat triangles, at two faces a point.
// The triangulation is the Delaunay one, which is regular: lifting every point onto a paraboloid
// makes it the lower hull, so flat_facets.cpp can realise it as a dome like the others.
#pragma once
#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace dcshell::remesh_detail {

/// A convex polygon's corners (counter-clockwise, every one a vertex of the Delaunay
/// triangulation's hull) plus interior points.
struct SteinerMesh {
  std::vector<Eigen::Vector2d> interior;
  double score = -1;  ///< sum of area x fatness of the Delaunay triangles (-1: not a valid layout)
};

/// Greedy refinements of the polygon with 1, 2, ..., max_points interior points (element k - 1
/// holds k points; shorter when a point cannot be placed): each adds a point at the centre of the
/// largest empty circle inside the polygon, then smooths the interior points (optimal Delaunay
/// triangulation steps). Deterministic. Empty when the polygon's Delaunay hull misses a corner
/// (a corner straight to rounding).
std::vector<SteinerMesh> refine_convex_polygon(const std::vector<Eigen::Vector2d>& corners, std::size_t max_points);

/// Heights (corners then interior points, scaled to [0, 1]) of a paraboloid whose lower hull is
/// the Delaunay triangulation, and the weakest interior point's rise above the lower hull of the
/// others, relative to the heights' range: the dome keeps every interior point a vertex against
/// noise e in the heights when 2 e < margin x depth.
std::vector<double> paraboloid_heights(const std::vector<Eigen::Vector2d>& corners,
                                       const std::vector<Eigen::Vector2d>& interior, double* margin);

}  // namespace dcshell::remesh_detail
