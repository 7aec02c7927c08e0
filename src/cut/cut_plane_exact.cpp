// The paper's method: SVM normal, exactly optimal offset.
#include "dcshell/cut_plane_exact.h"

#include "cut/cut_objective.h"
#include "dcshell/cut_plane_svm.h"
#include "dcshell/polytope_clip.h"

namespace dcshell {

CutPlane exact_cut_plane(const CutProblem& problem_in, const CutOptions& options) {
  std::optional<CutProblem> storage;
  const CutProblem& problem = with_current_overlap(problem_in, storage);
  CutObjective objective(problem, options.lambda);
  const double overlap_volume = volume(*problem.current_overlap);
  // The SVM's penalty is fragile (the paper says so): the normal it gives for overlapping
  // hulls swings with it. Try a decade either side and let the exact objective choose.
  CutObjective::Best best;
  bool first = true;
  for (double scale : {1.0, 0.1, 10.0}) {
    const CutPlane svm = svm_cut_plane(problem.a, problem.b, scale * options.svm_c, options.svm_samples, options.seed,
                                       overlap_volume);
    const CutObjective::Best b = objective.best_offset(svm.normal);
    if (first || b.value < best.value) best = b, first = false;
  }
  return best.plane;
}

}  // namespace dcshell
