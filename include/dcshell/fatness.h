// Stage "remesh" metric: how fat (foldable) the triangles of a shell are.
#pragma once
#include "dcshell/kernel.h"

namespace dcshell {

/// cos a + cos b + cos c - 1 of the triangle's angles: 0.5 for an equilateral triangle, tending
/// to 0 for a needle or a sliver (it equals inradius / circumradius). 0 for a degenerate triangle.
double triangle_fatness(const Point3& a, const Point3& b, const Point3& c);

/// Sums of area x fatness and of area over triangles: the area-weighted fatness is their ratio,
/// and a remeshing move is judged by what it changes in both.
struct FatArea {
  double fa = 0, a = 0;
  void add(const Point3& p, const Point3& q, const Point3& r);
  double ratio() const { return a > 0 ? fa / a : 0; }
};

/// Area-weighted average of triangle_fatness over the faces (polygons are fan-triangulated);
/// the quantity the paper plots. 0 for a mesh without area.
double weighted_fatness(const Mesh& mesh);

}  // namespace dcshell
