// Cut-plane method "exact" (the paper's): SVM normal, exactly optimal offset.
#pragma once
#include "dcshell/fit_cut_plane.h"

namespace dcshell {

/// The SVM normal with the offset minimising the objective (slice volumes of a, b and the
/// interference regions) over the overlap's range along the normal.
CutPlane exact_cut_plane(const CutProblem& problem, const CutOptions& options);

}  // namespace dcshell
