// Exact volume of a union of convex polytopes: the denominator of the volume-loss metric.
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

#include "dcshell/exact_polytope.h"
#include "dcshell/overlaps.h"

namespace dcshell {

/// How the union was summed.
enum class UnionMethod {
  automatic,     ///< nerve while its cost stays within a few times the pairwise level, else decomposition
  nerve,         ///< inclusion–exclusion over the nerve only (exponential in the deepest overlap)
  decomposition  ///< interior-disjoint convex pieces only
};

/// "automatic", "nerve", "decomposition" (as in the volume-loss report).
const char* to_string(UnionMethod method);

struct UnionVolume {
  double value = 0.0;         ///< the volume, within `error_bound`
  double error_bound = 0.0;   ///< certified bound on |value - true volume|
  bool exact_fallback = false;///< the interval filter was too loose; value is the exact rational rounded
  bool fixed_point = false;   ///< summed on a fixed-point grid of exact vertices (about 30 digits)
  UnionMethod method = UnionMethod::nerve;  ///< the one that produced `value` (never automatic)
  std::size_t terms = 0;      ///< terms summed: inclusion–exclusion terms with a common interior
                              ///< (nerve), convex pieces and the intersections subtracted from
                              ///< them (decomposition)
  std::size_t nerve_polytopes = 0;  ///< polytopes whose share the nerve walk summed (all of them
                                    ///< for nerve; the decomposition took the others)
  std::size_t max_clique = 0; ///< largest set of polytopes sharing interior that the nerve walk met
                              ///< (a lower bound when it gave way to the decomposition)
};

/// vol(∪ P_i), exactly. Two ways to the same number:
/// - inclusion–exclusion over the nerve: only subsets whose intersection has an interior
///   contribute, each intersection is convex and computed exactly, so the sum is exact. Subsets
///   are enumerated depth-first, pruning as soon as the running intersection is empty. Cheapest
///   when few polytopes share a point, but a region covered by k polytopes costs 2^k terms;
/// - a decomposition of the union into interior-disjoint convex pieces (each polytope minus
///   the larger ones it overlaps, split along their faces; against the last one a piece meets,
///   the piece minus their intersection): polynomial whatever the depth.
/// Both give each polytope the same share (itself minus the larger polytopes it overlaps; the
/// walk visits the polytopes smallest first). `automatic` walks the nerve and hands the
/// polytopes it has not finished to the decomposition once the walk holds more than
/// 2·(polytopes + candidate pairs) + 256 terms, or once its intersections of three or more
/// polytopes have cost more than twice the pairwise ones (counted as vertices × planes
/// tested): a deterministic rule, and the walk's finished shares are kept. Terms are summed in
/// interval arithmetic, then with every vertex evaluated exactly, then on a fixed-point grid
/// (below); only when the enclosure is still wider than `max_relative_error` of the value are
/// exact rationals used.
UnionVolume union_volume(const std::vector<ExactPolytope>& polytopes, double max_relative_error = 1e-12,
                         UnionMethod method = UnionMethod::automatic);

/// The same, reusing the pairwise intersections `find_overlaps(polytopes)` already computed
/// (every pair with a common interior, i < j): same value, fewer exact intersections.
UnionVolume union_volume(const std::vector<ExactPolytope>& polytopes, const std::vector<Overlap>& overlaps,
                         double max_relative_error = 1e-12, UnionMethod method = UnionMethod::automatic);

/// Whether a union volume known to be `value` ± `error_bound` is known well enough.
using UnionEnough = std::function<bool(const ExactRational& value, double error_bound)>;

/// The same, refined until `enough` holds, for callers whose precision depends on the value
/// (the volume loss needs the union to a fraction of union − shells). Four levels on the same
/// terms, each tried only when the one before is not enough: the coordinates' intervals; those
/// intervals with every vertex evaluated exactly; a fixed-point sum (every exact vertex rounded
/// to a multiple of 2^-k, about 120 bits below the largest coordinate, the determinants summed
/// exactly in integers, and the rounding's effect bounded triangle by triangle); exact
/// rationals (error 0). `value`, when given, receives the centre as an exact rational.
/// `overlaps`, when given, is `find_overlaps(polytopes)`, reused as above.
UnionVolume union_volume(const std::vector<ExactPolytope>& polytopes, const std::vector<Overlap>* overlaps,
                         const UnionEnough& enough, UnionMethod method = UnionMethod::automatic,
                         ExactRational* value = nullptr);

/// The same sum in exact rationals only (no interval filter): for callers that must decide the
/// sign of a difference the enclosure cannot. `overlaps`, when given, is
/// `find_overlaps(polytopes)`, reused as above.
ExactRational exact_union_volume(const std::vector<ExactPolytope>& polytopes,
                                 const std::vector<Overlap>* overlaps = nullptr,
                                 UnionMethod method = UnionMethod::automatic);

}  // namespace dcshell
