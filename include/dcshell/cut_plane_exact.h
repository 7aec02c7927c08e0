// Cut-plane method "exact" (the paper's): SVM normal, exactly optimal offset.
#pragma once
#include "dcshell/fit_cut_plane.h"

namespace dcshell {

/// The SVM normal with the offset minimising the objective (slice volumes of a, b and the
/// interference regions) over the overlap's range along the normal. The SVM's penalty is
/// fragile, so the SVM is solved at options.svm_c and a decade either side, and the normal whose
/// exactly optimal offset loses least is kept.
CutPlane exact_cut_plane(const CutProblem& problem, const CutOptions& options);

}  // namespace dcshell
