// Stage "cut": choosing the plane that separates two overlapping convex shells.
//
// A pair (a, b) of shells whose original hulls overlap is split by a plane H: a keeps
// H- = {normal·x <= offset}, b keeps H+. The plane must pass through the overlap of the original
// hulls, so no gap opens between the pieces. Its quality is the volume it loses,
//   lost = vol(a ∩ H+) + vol(b ∩ H-) - vol(a ∩ b),
// i.e. the objective g(n, d) = vol(a ∩ H+) + vol(b ∩ H-) up to a constant.
//
// Methods (each in its own header):
//  - lsf:   least-squares plane through the intersection curve ∂a ∩ ∂b (cut_plane_lsf.h);
//  - svm:   soft-margin linear SVM separating points sampled in a and b (cut_plane_svm.h);
//  - exact: the paper's method: SVM normal, offset minimising g exactly (cut_plane_exact.h);
//  - full:  normal and offset optimised together, never worse than exact (cut_plane_full.h).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dcshell/convex_polytope.h"
#include "dcshell/cut_plane.h"

namespace dcshell {

enum class CutMethod { lsf, svm, exact, full };

/// "lsf", "svm", "exact", "full" (case-sensitive). Throws InputError for anything else.
CutMethod parse_cut_method(const std::string& name);
const char* to_string(CutMethod method);

struct CutProblem {
  ConvexPolytope a;  ///< current shell of the first part: keeps normal·x <= offset
  ConvexPolytope b;  ///< current shell of the second part: keeps normal·x >= offset
  /// C_i ∩ C_j of the ORIGINAL hulls; the plane's offset is kept within the range of its
  /// vertices along the normal. When empty, a ∩ b is used; when that is empty too, a ∪ b.
  ConvexPolytope overlap;
  /// Interference (paper Eq. 7): regions C_i ∩ C_k (k another part) that a should not lose;
  /// the objective adds lambda * vol(X ∩ H+) for each.
  std::vector<ConvexPolytope> interference_a;
  /// Regions C_j ∩ C_k that b should not lose: adds lambda * vol(Y ∩ H-) for each.
  std::vector<ConvexPolytope> interference_b;
  /// a ∩ b as `tagged_intersection(a, b)` gives it, when the caller has it already. Every
  /// method needs it (the LSF curve, the SVM's class volumes, the lost volume) and it is the
  /// costly part of a fit when the hulls are large: fit_cut_plane and evaluate_cut_plane
  /// compute it once when it is unset.
  std::optional<ConvexPolytope> current_overlap;
};

/// `problem` itself when it carries its current overlap, else a copy in `storage` that does:
/// what every entry point below starts with, so the overlap is computed once per call.
const CutProblem& with_current_overlap(const CutProblem& problem, std::optional<CutProblem>& storage);

struct CutOptions {
  CutMethod method = CutMethod::full;
  double lambda = 0.01;               ///< weight of the interference terms
  double svm_c = 1.0;                 ///< SVM soft-margin penalty (features are normalised)
  std::uint64_t seed = 1;             ///< seeds the point sampling of svm / exact / full
  std::size_t svm_samples = 600;      ///< points sampled in a and b together (by volume)
  std::size_t full_directions = 32;   ///< Fibonacci-sphere directions scanned by full
  std::size_t full_starts = 2;        ///< best distinct directions refined locally by full
  /// full only: a good plane for a nearby problem (the pair's plane before a refinement sweep
  /// re-fits it against hulls trimmed by their other planes). The search then polishes from
  /// it (and from the best of `warm_directions` scanned directions), skipping the SVM start:
  /// the landscape changed little, and a sweep keeps the new plane only if it loses less.
  std::optional<CutPlane> warm_start;
  std::size_t warm_directions = 0;
};

struct CutResult {
  CutPlane plane;            ///< unit normal, pointing from a toward b
  double lost_volume = 0.0;  ///< vol(a ∩ H+) + vol(b ∩ H-) - vol(a ∩ b)
  double objective = 0.0;    ///< vol(a ∩ H+) + vol(b ∩ H-) + lambda * interference
  double seconds = 0.0;      ///< wall time of the fit
};

/// Fits the plane of one pair with options.method. Deterministic for a given seed.
CutResult fit_cut_plane(const CutProblem& problem, const CutOptions& options = {});

/// Objective and lost volume of a given plane for the problem (e.g. to compare methods).
CutResult evaluate_cut_plane(const CutProblem& problem, const CutPlane& plane, double lambda = 0.01);

}  // namespace dcshell
