// Stage "cut planes" of a whole composite: one plane per overlapping pair of hulls, first fitted
// pair by pair (fit_pair_planes), then refined in sweeps against the hulls as trimmed by all the
// other planes (refine_cut_planes). Independently optimal planes over-trim where three or more
// hulls meet; the sweeps and their starts are what recovers that volume (doc/shell.md).
//
// Double precision throughout (the fast path): the pipeline trims and certifies exactly
// afterwards (trim.h, certify.h).
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "dcshell/convex_polytope.h"
#include "dcshell/cut_plane.h"
#include "dcshell/fit_cut_plane.h"

namespace dcshell {

/// Two overlapping hulls, i < j (indices into the hulls), and the region they share.
struct HullPair {
  std::size_t i = 0, j = 0;
  ConvexPolytope region;  ///< C_i ∩ C_j of the hulls: every plane of the pair passes through it
};

/// The sweep starts of `full` (doc/shell.md, "Two starts", "Three starts").
enum class SweepStart {
  pairwise,        ///< the pairwise planes, polished
  refit_reshaped,  ///< pairs whose hulls the other planes reshaped re-fitted from scratch first
  constructive     ///< planes placed pair by pair against the hulls trimmed so far
};
/// "pairwise", "refit-reshaped", "constructive" (as in report.json).
const char* to_string(SweepStart start);

struct SweepOptions {
  /// Maximum refinement sweeps: each re-optimises every pair's plane against the two hulls as
  /// already trimmed by all their other planes, keeping a new plane only when it loses less.
  /// Used by the volume-minimising methods (exact, full); lsf and svm are single-pass.
  int max_sweeps = 6;
  /// Sweeps re-fit a pair from scratch (true) or, for `full`, from its current plane with a
  /// short scan (false, the default: several times faster; see doc/results.md for the losses).
  bool global_sweeps = false;
  /// With warm-started sweeps, where the other planes cut 30% or more off a pair's hulls, `full`
  /// also runs a second start that re-fits those pairs from scratch in its first sweep, and keeps
  /// whichever start leaves the shells more volume (doc/shell.md, "Two starts").
  bool second_start = true;
  /// Where the second start runs and the pairwise planes together cut a fifth or more off the
  /// hulls, a third start places the planes pair by pair (larger hulls first), each fitted from
  /// scratch against its hulls trimmed by the planes placed before it (doc/shell.md, "Three
  /// starts"). Off: two starts at most.
  bool constructive_start = true;
  /// Sweeps stop once one gains less than this fraction of the hulls' total volume (each sweep
  /// gains less than the one before, typically by a factor of 2 to 10).
  double tolerance = 2e-6;
};

/// What the sweeps did, for the report.
struct SweepReport {
  int sweeps = 0;               ///< sweeps run by the winning start
  std::vector<double> gains;    ///< objective decrease of each, as a fraction of the hulls' volume
  std::size_t refits = 0;       ///< pairs the winning start re-fitted from scratch (0: the first won)
  SweepStart start = SweepStart::pairwise;  ///< the start whose planes were kept
};

/// Called with (stage, done, total) as work proceeds.
using StageProgress = std::function<void(const std::string&, std::size_t, std::size_t)>;

/// The plane of each pair, fitted to the two whole hulls (part i keeps normal·x <= offset), with
/// the interference (paper Eq. 7) of the regions each part shares with its other pairs. Pair p
/// uses the seed `cut.seed * 1000003 + p`; pairs run side by side with the same result as one
/// after the other.
std::vector<CutPlane> fit_pair_planes(const std::vector<ConvexPolytope>& hulls, const std::vector<HullPair>& pairs,
                                      const CutOptions& cut, const StageProgress& progress = {});

/// Refinement sweeps from the pairwise `planes` (exact and full; other methods return them
/// unchanged). A hull that takes part in no pair (e.g. absorbed by another) may be passed empty.
/// Deterministic; the result does not depend on the number of threads.
std::vector<CutPlane> refine_cut_planes(const std::vector<ConvexPolytope>& hulls, const std::vector<HullPair>& pairs,
                                        std::vector<CutPlane> planes, const CutOptions& cut,
                                        const SweepOptions& options, SweepReport* report = nullptr,
                                        const StageProgress& progress = {});

}  // namespace dcshell
