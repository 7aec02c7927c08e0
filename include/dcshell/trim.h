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
};

/// hull ∩ {x : p.normal·x <= p.offset for every p in keep_below}, computed exactly, then
/// rounded: each vertex is rounded to doubles; a rounded vertex that falls outside a cut plane
/// or outside the hull (decided exactly) is moved toward the shell's interior by the smallest
/// step that restores every constraint; the result is the convex hull (exact predicates) of
/// those points. So the written shell is exactly convex and exactly inside each of its
/// halfspaces, hence interior-disjoint from every neighbour separated by a plane or by the hulls
/// themselves. Returns an empty mesh when nothing of positive volume remains.
Mesh trim_shell(const ExactPolytope& hull, const std::vector<CutPlane>& keep_below, TrimStats* stats = nullptr);

/// The exact trimmed polytope (before rounding).
ExactPolytope trim_exact(const ExactPolytope& hull, const std::vector<CutPlane>& keep_below);

}  // namespace dcshell
