// The paper's method: SVM normal, exactly optimal offset.
#include "dcshell/cut_plane_exact.h"

#include "cut/cut_objective.h"
#include "dcshell/cut_plane_svm.h"

namespace dcshell {

CutPlane exact_cut_plane(const CutProblem& problem, const CutOptions& options) {
  const CutPlane svm = svm_cut_plane(problem.a, problem.b, options.svm_c, options.svm_samples, options.seed);
  CutObjective objective(problem, options.lambda);
  return objective.best_offset(svm.normal).plane;
}

}  // namespace dcshell
