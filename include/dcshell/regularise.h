// Stage "remesh", step 2: convexity-preserving regularisation (constrained Laplacian smoothing).
// Each vertex moves to the point nearest the centroid of its neighbours that keeps the mesh
// convex, the original shell enclosed, the constraint planes respected and the volume bounded:
// a QP in three variables with linear constraints (CGAL's QP solver).
#pragma once
#include <cstddef>
#include <limits>
#include <vector>

#include "dcshell/kernel.h"
#include "dcshell/simplify.h"

namespace dcshell {

struct RegulariseOptions {
  int sweeps = 1;  ///< passes over all vertices
  /// No move may take the volume past this (absolute, in cubic units).
  double max_volume = std::numeric_limits<double>::infinity();
};

struct RegulariseStats {
  std::size_t moves = 0;
  std::size_t infeasible = 0;  ///< QP without a solution (vertex kept)
  std::size_t rejected = 0;    ///< QP solution failed the exact checks (vertex kept)
};

/// Smooths a closed, exactly convex, outward triangle mesh in place. Invariants, checked exactly
/// on the rounded doubles after every move (a failing move is not made): exactly convex, every
/// point of `enclose` inside or on the mesh, `constraints` satisfied, volume <= max_volume.
/// Returns the number of vertices moved.
std::size_t regularise_convex(Mesh& mesh, const std::vector<Point3>& enclose, const ShellConstraints& constraints,
                              const RegulariseOptions& options, RegulariseStats* stats = nullptr);

}  // namespace dcshell
