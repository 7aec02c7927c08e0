// Cut-plane method "full": normal (2 DOF) and offset optimised together.
#pragma once
#include "dcshell/fit_cut_plane.h"

namespace dcshell {

/// Multi-start search: the exact plane, the LSF normal, the principal axes of the overlap and
/// options.full_directions Fibonacci-sphere directions, each with its exactly optimal offset;
/// the best options.full_starts distinct ones are polished by BFGS on the sphere (gradient =
/// first moments of the sections). Returns the best plane seen, so never worse than exact.
/// With options.warm_start: polishes from it and from the best of options.warm_directions
/// scanned directions instead (never worse than the warm start's normal with its best offset).
CutPlane full_cut_plane(const CutProblem& problem, const CutOptions& options);

}  // namespace dcshell
