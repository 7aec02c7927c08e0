// Exact volume of a union of convex polytopes: the denominator of the volume-loss metric.
#pragma once
#include <cstddef>
#include <vector>

#include "dcshell/exact_polytope.h"
#include "dcshell/overlaps.h"

namespace dcshell {

struct UnionVolume {
  double value = 0.0;         ///< the volume, within `error_bound`
  double error_bound = 0.0;   ///< certified bound on |value - true volume|
  bool exact_fallback = false;///< the interval filter was too loose; value is the exact rational rounded
  std::size_t terms = 0;      ///< inclusion-exclusion terms with a common interior
  std::size_t max_clique = 0; ///< largest set of polytopes sharing interior
};

/// vol(∪ P_i) by inclusion–exclusion over the nerve: only subsets whose intersection has an
/// interior contribute, each intersection is convex and computed exactly, so the sum is exact.
/// Subsets are enumerated depth-first, pruning as soon as the running intersection is empty.
/// Terms are summed in interval arithmetic; only when the enclosure is wider than
/// `max_relative_error` of the value is the sum redone with exact rationals.
UnionVolume union_volume(const std::vector<ExactPolytope>& polytopes, double max_relative_error = 1e-12);

/// The same, reusing the pairwise intersections `find_overlaps(polytopes)` already computed
/// (every pair with a common interior, i < j): same terms, same sum, fewer exact intersections.
UnionVolume union_volume(const std::vector<ExactPolytope>& polytopes, const std::vector<Overlap>& overlaps,
                         double max_relative_error = 1e-12);

/// The same sum in exact rationals only (no interval filter): for callers that must decide the
/// sign of a difference the enclosure cannot. `overlaps`, when given, is
/// `find_overlaps(polytopes)`, reused as above.
ExactRational exact_union_volume(const std::vector<ExactPolytope>& polytopes,
                                 const std::vector<Overlap>* overlaps = nullptr);

}  // namespace dcshell
