// Stage "trim": a hull cut by its separating planes, exactly, then rounded to doubles in a way
// that keeps every guarantee (convex, inside each cut plane, inside the hull).
#pragma once
#include <vector>

#include "dcshell/cut_plane.h"
#include "dcshell/exact_polytope.h"
#include "dcshell/kernel.h"

namespace dcshell {

struct TrimStats {
  std::size_t nudged_vertices = 0;   ///< rounded vertices moved inward to restore a constraint
  std::size_t dropped_vertices = 0;  ///< vertices that could not be restored (sliver) and were left out
  std::size_t merged_vertices = 0;   ///< vertices left out as closer than kMergeDistance to a kept one
  /// Vertices the cuts made within kMergeDistance of the hull of the others, left out
  /// (pruned_convex_hull_mesh); build_shells adds the part's hull vertices it left out so.
  std::size_t flat_vertices = 0;
};

/// Rounded vertices closer than this fraction of the shell's bounding-box diagonal to an earlier
/// kept vertex are left out before the final hull (0.1 micrometre on a 1 m part). Dropping hull
/// vertices only shrinks the shell, so every guarantee stays exact; it removes the ulp-long
/// edges and needle faces that appear where a cut passes next to a hull vertex, which no
/// simulation or paper net can use (a fold about a 1e-11 edge has no defined direction).
constexpr double kMergeDistance = 1e-7;

/// hull ∩ {x : p.normal·x <= p.offset for every p in keep_below}, computed exactly, then
/// rounded: each vertex is rounded to doubles; a rounded vertex that falls outside a cut plane
/// or outside the hull (decided exactly) is moved toward the shell's interior by the smallest
/// step that restores every constraint; the result is the convex hull (exact predicates) of
/// those points, less those within kMergeDistance of another and the vertices the cuts made within
/// kMergeDistance of the hull of the others. So the written shell is exactly
/// convex and exactly inside each of its halfspaces, hence interior-disjoint from every
/// neighbour separated by a plane or by the hulls themselves. Returns an empty mesh when nothing
/// of positive volume remains.
Mesh trim_shell(const ExactPolytope& hull, const std::vector<CutPlane>& keep_below, TrimStats* stats = nullptr);

/// The exact trimmed polytope (before rounding).
ExactPolytope trim_exact(const ExactPolytope& hull, const std::vector<CutPlane>& keep_below);

}  // namespace dcshell
