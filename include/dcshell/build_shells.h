// The DC-shell pipeline: parts -> hulls -> overlaps -> cut planes (+ refinement sweeps) ->
// exact trim -> certified rounding -> optional simplify/regularise -> certification.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "dcshell/certify.h"
#include "dcshell/cut_plane.h"
#include "dcshell/fit_cut_plane.h"
#include "dcshell/load_parts.h"
#include "dcshell/remesh.h"
#include "dcshell/trim.h"

namespace dcshell {

/// The sweep starts of `full` (doc/shell.md, "Two starts", "Three starts").
enum class SweepStart {
  pairwise,        ///< the pairwise planes, polished
  refit_reshaped,  ///< pairs whose hulls the other planes reshaped re-fitted from scratch first
  constructive     ///< planes placed pair by pair against the hulls trimmed so far
};
/// "pairwise", "refit-reshaped", "constructive" (as in report.json).
const char* to_string(SweepStart start);

struct ShellOptions {
  CutOptions cut;  ///< method (default full), lambda, svm_c, seed
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
  double sweep_tolerance = 2e-6;
  /// A hull with at least this fraction of its volume inside one other hull is absorbed by it
  /// (no shell of its own; reported). Exactly nested and duplicated parts are absorbed too.
  double absorb_fraction = 0.99;
  /// Simplify + regularise hulls before cutting and shells after (0 = off), paper: 10 and 5%.
  /// The volume bound is split between the two stages: each may grow its input (a hull, then
  /// a shell) by sqrt(1 + R) - 1, so that the two compound to R.
  int simplify_iterations = 0;
  double max_volume_increase = 0.05;
  /// Remeshing ends by giving flat facets (cut faces) their fattest triangulation (remesh.h).
  bool fatten_flat_facets = true;
  /// ... and splits edges with lifted points where that makes the shells fatter (remesh.h).
  bool edge_splits = true;
  /// Called with (stage, done, total) as work proceeds.
  std::function<void(const std::string&, std::size_t, std::size_t)> progress;
};

struct ShellCut {
  CutPlane plane;            ///< oriented so that this shell keeps normal·x <= offset
  std::size_t partner = 0;   ///< the part on the other side
};

struct Shell {
  std::size_t part = 0;                ///< source part
  std::vector<std::size_t> absorbed;   ///< parts absorbed into this shell
  std::vector<ShellCut> cuts;
  Mesh mesh;                           ///< the shell as written: double coordinates, certified
  double volume = 0.0;                 ///< exact volume of `mesh`, rounded
  TrimStats trim;
  bool remeshed = false;
  RemeshStats remesh;
};

struct AbsorbedPart {
  std::size_t part = 0, container = 0;
  double fraction_inside = 0.0;  ///< of the part's hull volume
};

struct StageTime {
  std::string stage;
  double seconds = 0.0;
};

struct ShellResult {
  std::vector<Shell> shells;
  std::vector<AbsorbedPart> absorbed;
  std::vector<std::size_t> vanished;   ///< parts whose shell was cut away entirely
  std::size_t overlapping_pairs = 0;
  int sweeps_run = 0;
  /// Objective decrease of each sweep, as a fraction of the hulls' total volume.
  std::vector<double> sweep_gains;
  /// Pairs the winning start re-fitted from scratch (0 when the first start won or none ran).
  std::size_t sweep_refits = 0;
  SweepStart sweep_start = SweepStart::pairwise;  ///< the start whose planes were kept
  double union_volume = 0.0;           ///< of the parts' original convex hulls (certified enclosure midpoint)
  double shells_volume = 0.0;
  double volume_loss = 0.0;            ///< (union - shells) / union, correctly signed (volume_loss.h)
  double volume_loss_error_bound = 0.0;///< certified bound on its error
  bool volume_loss_exact = false;      ///< decided in exact rationals
  CertificationReport certification;
  std::vector<StageTime> times;
};

/// Builds certified DC-shells for the parts. Deterministic for given options.
ShellResult build_shells(const std::vector<Part>& parts, const ShellOptions& options);

}  // namespace dcshell
