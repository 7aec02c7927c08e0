// Stage "overlaps": which convex hulls share interior, decided exactly.
#pragma once
#include <CGAL/Bbox_3.h>

#include <utility>
#include <vector>

#include "dcshell/exact_polytope.h"

namespace dcshell {

/// Broad phase: index pairs (i < j, sorted) whose closed boxes meet (CGAL box_self_intersection_d).
std::vector<std::pair<std::size_t, std::size_t>> box_overlap_pairs(const std::vector<CGAL::Bbox_3>& boxes);

CGAL::Bbox_3 bbox(const ExactPolytope& p);

struct Overlap {
  std::size_t i = 0, j = 0;  ///< i < j
  ExactPolytope region;      ///< C_i ∩ C_j, exact, non-empty interior
  double volume = 0.0;       ///< certified enclosure midpoint
};

/// All pairs of polytopes whose interiors intersect, with the exact intersection. Pairs that only
/// touch (along a face, an edge or a point) are not overlaps.
std::vector<Overlap> find_overlaps(const std::vector<ExactPolytope>& polytopes);

}  // namespace dcshell
