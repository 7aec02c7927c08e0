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
#include "dcshell/refine_cut_planes.h"
#include "dcshell/remesh.h"
#include "dcshell/trim.h"

namespace dcshell {

struct ShellOptions {
  CutOptions cut;  ///< method (default full), lambda, svm_c, seed
  /// Refinement sweeps of the cut planes and their starts (refine_cut_planes.h).
  SweepOptions sweep;
  /// A hull with at least this fraction of its volume inside one other hull is absorbed by it
  /// (no shell of its own; reported). Exactly nested and duplicated parts are absorbed too.
  double absorb_fraction = 0.99;
  /// Simplify + regularise hulls before cutting and shells after (0 = off), paper: 10 and 5%.
  /// The volume bound covers both stages: a hull may grow by sqrt(1 + R) - 1, and each shell
  /// is remeshed within (1 + R) x the volume of its part's original hull cut by its planes.
  int simplify_iterations = 0;
  double max_volume_increase = 0.05;
  /// Remeshing ends by giving flat facets (cut faces) their fattest triangulation (remesh.h).
  bool fatten_flat_facets = true;
  /// ... and splits edges with lifted points where that makes the shells fatter (remesh.h).
  bool edge_splits = true;
  /// ... and flips edges by lifting a vertex where that makes them fatter (remesh.h).
  bool edge_flips = true;
  /// Called with (stage, done, total) as work proceeds.
  StageProgress progress;
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
  SweepReport sweep;                   ///< what the refinement sweeps did
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
