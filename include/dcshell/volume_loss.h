// The volume-loss metric: (vol(∪ C_i) − Σ vol(shell_k)) / vol(∪ C_i), certified.
#pragma once
#include <vector>

#include "dcshell/exact_polytope.h"
#include "dcshell/kernel.h"
#include "dcshell/union_volume.h"

namespace dcshell {

struct VolumeLoss {
  double value = 0.0;          ///< the loss; its sign is always the true one (0 only when exactly 0)
  double error_bound = 0.0;    ///< certified bound on |value − true loss|
  bool exact = false;          ///< decided in exact rationals (no enclosure could fix the sign)
  double union_volume = 0.0;   ///< vol(∪ C_i), within union.error_bound
  double shells_volume = 0.0;  ///< Σ vol(shell_k), exact on the shells' doubles, rounded
  UnionVolume union_stats;     ///< how the union was computed (terms, depth, filter)
};

/// Loss of closed, outward-oriented `shells` against the union of `hulls`. The shells' volume
/// is exact on their coordinates; the union's comes from `union_volume`, refined only as far as
/// the loss needs. Remeshed shells may grow past the hulls, so a negative loss is meaningful, and
/// shells that meet exactly give a loss of exactly 0 — a difference of two nearly equal doubles
/// would give either sign. So the union is refined (intervals, then the fixed-point sum, then
/// exact rationals) until the loss's enclosure excludes 0 and is within `max_relative_error` of
/// it; a loss of exactly 0 is decided in exact rationals.
/// `overlaps`, when given, are `find_overlaps(hulls)` (reused by the union's filter).
VolumeLoss volume_loss(const std::vector<ExactPolytope>& hulls, const std::vector<Mesh>& shells,
                       const std::vector<Overlap>* overlaps = nullptr, double max_relative_error = 1e-9);

}  // namespace dcshell
