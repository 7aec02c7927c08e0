// Dispatcher over the cut-plane methods.
#include "dcshell/fit_cut_plane.h"

#include <algorithm>
#include <chrono>

#include "cut/cut_objective.h"
#include "dcshell/cut_plane_exact.h"
#include "dcshell/cut_plane_full.h"
#include "dcshell/cut_plane_lsf.h"
#include "dcshell/cut_plane_svm.h"
#include "dcshell/error.h"
#include "dcshell/polytope_clip.h"

namespace dcshell {

CutMethod parse_cut_method(const std::string& name) {
  for (CutMethod m : {CutMethod::lsf, CutMethod::svm, CutMethod::exact, CutMethod::full})
    if (name == to_string(m)) return m;
  throw InputError("unknown cut method '" + name + "' (expected lsf, svm, exact or full)");
}

const char* to_string(CutMethod method) {
  switch (method) {
    case CutMethod::lsf: return "lsf";
    case CutMethod::svm: return "svm";
    case CutMethod::exact: return "exact";
    case CutMethod::full: return "full";
  }
  return "?";
}

namespace {

CutResult evaluate(CutObjective& obj, const CutProblem& pb, CutPlane plane) {
  if (plane.normal.squaredNorm() != 1.0) {
    plane.offset /= plane.normal.norm();
    plane.normal.normalize();
  }
  // Every method's plane must pass through the overlap: clamp into the range.
  const auto [lo, hi] = obj.range(plane.normal);
  plane.offset = std::clamp(plane.offset, lo, hi);
  CutResult r;
  r.plane = plane;
  r.objective = obj.value(plane);
  r.lost_volume = std::max(0.0, obj.separated_volume(plane) - volume(*pb.current_overlap));
  return r;
}

}  // namespace

const CutProblem& with_current_overlap(const CutProblem& problem, std::optional<CutProblem>& storage) {
  if (problem.current_overlap) return problem;
  storage.emplace(problem);
  storage->current_overlap = tagged_intersection(problem.a, problem.b);
  return *storage;
}

CutResult evaluate_cut_plane(const CutProblem& problem_in, const CutPlane& plane, double lambda) {
  std::optional<CutProblem> storage;
  const CutProblem& problem = with_current_overlap(problem_in, storage);
  CutObjective obj(problem, lambda);
  return evaluate(obj, problem, plane);
}

CutResult fit_cut_plane(const CutProblem& problem_in, const CutOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  std::optional<CutProblem> storage;
  const CutProblem& problem = with_current_overlap(problem_in, storage);
  CutPlane plane;
  switch (options.method) {
    case CutMethod::lsf: plane = lsf_cut_plane(problem.a, problem.b, *problem.current_overlap); break;
    case CutMethod::svm:
      plane = svm_cut_plane(problem.a, problem.b, options.svm_c, options.svm_samples, options.seed,
                            volume(*problem.current_overlap));
      break;
    case CutMethod::exact: plane = exact_cut_plane(problem, options); break;
    case CutMethod::full: plane = full_cut_plane(problem, options); break;
  }
  CutObjective obj(problem, options.lambda);
  CutResult r = evaluate(obj, problem, plane);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace dcshell
