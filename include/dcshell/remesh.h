// Stage "remesh": the driver combining simplification (simplify.h) and regularisation
// (regularise.h), as the paper's "--simplify-iterations N --max-volume-increase R" does, plus
// the constraints a set of existing shells imposes on each other.
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

#include "dcshell/flat_facets.h"
#include "dcshell/kernel.h"
#include "dcshell/simplify.h"

namespace dcshell {

struct RemeshOptions {
  int iterations = 10;               ///< simplify + smooth rounds (the paper: 10)
  double max_volume_increase = 0.05; ///< bound on (V_after - V_before) / V_before (the paper: 5%)
  std::size_t target_faces = 0;      ///< optional lower bound on the face count (0: none)
  /// Faces the result may have (0: the input's): Steiner points may spend up to this many.
  std::size_t max_faces = 0;
  /// Finish by re-triangulating flat facets (cut faces above all) by their fattest triangulation
  /// (fatten_flat_facets): free in faces, about 1e-9 of their size in depth.
  bool fatten_flat_facets = true;
  /// ... and may spend the faces simplification saved (up to the input's face count) on Steiner
  /// points inside the facets that gain most from them.
  bool steiner_points = true;
  /// Collapses ordered by the fatness they gain per unit of added volume (SimplifyOptions::
  /// order_by_gain) rather than least added volume first.
  bool order_by_gain = true;
  /// Each iteration may also split edges with lifted points (two faces each, paid from the faces
  /// the collapses saved below the input's count; max_faces is left to the Steiner points), where
  /// that raises area x fatness: the big hull slivers between few extreme points, which
  /// collapses cannot fix.
  bool edge_splits = true;
  /// Each iteration may also flip edges ab -> cd by lifting c just above the plane of the face
  /// across (no faces added, a little volume), where that raises area x fatness: the long thin
  /// triangles a stretched hull's vertices force, which neither collapses nor moves change.
  bool edge_flips = true;
  /// Called after each iteration with the working mesh (convex; for benchmarks and progress).
  std::function<void(int iteration, const Mesh& mesh)> on_iteration;
};

struct RemeshStats {
  std::size_t faces_before = 0, faces_after = 0;
  double fatness_before = 0, fatness_after = 0;  ///< weighted_fatness
  double volume_before = 0, volume_after = 0;
  std::size_t collapses = 0, moves = 0, splits = 0, flips = 0;
  FlatFacetStats flat;  ///< the final flat-facet step
  double volume_increase() const { return volume_before > 0 ? volume_after / volume_before - 1.0 : 0.0; }
};

/// Simplifies and regularises one convex shell. The result is the convex_hull_3 of its vertices
/// (closed, outward, exactly convex triangles, double coordinates) and, checked exactly on those
/// doubles, contains `shell` and satisfies `constraints`; it has at most the faces of `shell` (or
/// options.max_faces) and volume <= (1 + max_volume_increase) * volume(shell) (floating-point
/// volumes). Each iteration is one simplification pass (an independent set of collapses, by gain
/// per volume or cheapest first, each only if its new faces are fatter than those it removes)
/// then one smoothing sweep,
/// both within the whole volume budget; the first N iterations
/// of a run are the same whatever N, and it stops early once an iteration changes nothing.
/// Vertices on a constraint plane stay on it or inside, so cut faces stay where they were.
/// With options.fatten_flat_facets the result's flat facets are finally re-triangulated
/// (flat_facets.h), with Steiner points in the faces left (options.steiner_points): a facet on a
/// constraint plane may then sink by about 1e-9 of its size, the
/// only place where the result does not contain `shell` exactly (stats->flat.max_inward says how far).
/// Throws InputError if `shell` is not exactly convex and closed or violates `constraints`.
Mesh remesh_convex_shell(const Mesh& shell, const ShellConstraints& constraints, const RemeshOptions& options,
                         RemeshStats* stats = nullptr);

/// Convenience for the pipeline: constraints are the shell's own cut planes.
Mesh remesh_convex_shell(const Mesh& shell, const std::vector<CutPlane>& keep_inside, const RemeshOptions& options,
                         RemeshStats* stats = nullptr);

/// For a set of pairwise interior-disjoint convex shells, the halfspaces that keep each one off
/// its neighbours while they all grow: for every pair whose bounding boxes touch, a face plane
/// of one that has the other entirely on its outer side (decided exactly), preferring a face
/// the two share (coplanar, opposite orientation, overlapping). Both shells of the pair get the
/// same exact plane, one from each side, so the pair stays disjoint whatever else moves.
/// `unseparated` receives pairs (i < j) for which no face plane separates (an edge-edge contact);
/// they are left unconstrained and the final certification decides.
std::vector<ShellConstraints> neighbour_constraints(const std::vector<Mesh>& shells,
                                                    std::vector<std::pair<std::size_t, std::size_t>>* unseparated = nullptr);

}  // namespace dcshell
