// Stage "unfold": a convex triangle shell cut along a spanning tree of its dual graph and laid
// flat as a one-piece net (Net, net.h). Cut trees come from Schlickenrieder's heuristics
// ("Nets of polyhedra", 1997) with retries, or from a genetic search (unfold_ga.h).
//
// Coplanar faces are never cut apart: a fold of angle 0 is free and invisible, so the cut tree
// is built on "facets" (maximal regions joined by flat edges) and every flat edge stays a fold.
// That is what makes a triangulated cube cut along 7 cube edges instead of 18 triangle edges.
#pragma once
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "dcshell/fold_check.h"
#include "dcshell/kernel.h"
#include "dcshell/net.h"

namespace dcshell {

/// How the cut tree is chosen. `best`: every heuristic with retries, the best overlap-free net
/// by the objective. `ga`: `best`, then the genetic search of unfold_ga.h seeded with its nets.
/// `greedy`: overlap-aware Kruskal (longest fold first, a join that would overlap is refused),
/// which `best` and `ga` also try (its variants; see doc/unfold.md, "Cut tree").
enum class UnfoldHeuristic { best, steepest, flat, min_perimeter, random, ga, greedy };
/// What "best" means among overlap-free nets (the other feature breaks ties, weight 1/100).
enum class UnfoldObjective { hull_area, cut_length };

/// "steepest|flat|min-perimeter|random|greedy|ga|best" <-> enum. Parsing throws std::invalid_argument
/// naming the string and the accepted values.
UnfoldHeuristic parse_unfold_heuristic(const std::string&);
UnfoldObjective parse_unfold_objective(const std::string&);
std::string to_string(UnfoldHeuristic);
std::string to_string(UnfoldObjective);

struct UnfoldOptions {
  UnfoldHeuristic heuristic = UnfoldHeuristic::best;
  UnfoldObjective objective = UnfoldObjective::hull_area;
  std::uint64_t seed = 1;
  /// Cut trees tried per heuristic; 0 = automatic: a small budget (up to 12 for the smallest
  /// shells, 1 from 100 faces on; retries go on while no net is overlap-free). A count, not a
  /// time, so results do not depend on the machine.
  int tries = 0;
  /// |fold angle| (radians) at or below which an edge counts as flat: never cut, and not a
  /// reflex edge either. Files round coordinates (the shared convex models are up to 1.5e-5 rad
  /// off-convex); a fold of 0.006 degrees is invisible on paper.
  double flat_angle = 1e-4;
  /// The straight-line folding path of a net may collide. Overlap-free nets are checked
  /// (fold_check.h) in turn and the first one that folds without collision is returned: first the
  /// search's nets in score order, then further distinct trees of the heuristics (more directions,
  /// jitters, random trees). At most this many nets are checked (none for shells over 5,000
  /// faces: the check is then the caller's; 0 = no check).
  int fold_candidates = 64;
  /// Work budget of that selection, in units of one piece placed by the check (a step places
  /// every rigid piece) or one face of a tree decoded. Each net is first checked with a small
  /// share (`fold_first_work`); a net that runs out of it undecided is re-checked with the rest
  /// when no net verifies, or when a worse-scored one does (fold_recheck_work). A count, not a
  /// time: the result is the same on every machine.
  /// Both are per 200 faces of the shell, scaled by scaled_fold_work: a step of a larger net
  /// places more pieces, and its nets need about as many steps.
  long long fold_work = 500000;
  long long fold_first_work = 40000;
  /// Only nets whose objective is within this fraction of the best overlap-free net's are
  /// checked: a verified fold is worth that much longer cuts (or larger hull), no more.
  double fold_slack = 0.25;
  /// When no net within fold_slack verifies, the nets within this wider slack are checked too,
  /// with what the first pass left of its budget (it may have stopped at fold_candidates) plus
  /// fold_fallback_work (scaled like fold_work), and fold_candidates more checks: a net that
  /// folds is worth a longer cut then. At or below fold_slack: no fallback. The extra budget is
  /// a tenth of fold_work: on the shared sets that recovers the nets that fold (doc/unfold.md)
  /// without doubling the time of shells whose nets never do.
  double fold_fallback_slack = 3.0;
  long long fold_fallback_work = 50000;
  /// Each net's check starts with the end of its path, t in [1 - fold_screen, 1], where
  /// straight-line folds mostly fail (FoldCheckOptions::end_first): a conclusive failure there
  /// refutes the net in a few steps, where the whole check would first step through the path
  /// before it; an inconclusive one sets the net aside with the undecided ones (checked in full
  /// only when no net verifies; FoldCheckOptions::end_first_defers); otherwise the path is
  /// checked up to where the proved end begins (FoldCheckOptions::end_proof, this window for
  /// every check of the selection). 0: no screen, and every check steps from 0 to 1.
  double fold_screen = 1e-3;
  /// Once a net verifies, the nets scored better than it that ran out of their first share
  /// undecided (they came first: search nets in score order) are re-checked, best first, each
  /// with this much of what is left of fold_work (scaled like it); the first that verifies is
  /// returned instead. 0: the first net that verifies is returned. On the shared sets the
  /// re-checks that verified needed 40,000-166,000 units; one that never does would otherwise
  /// take all that is left (a 32-face Cow hull: 0.1 s).
  long long fold_recheck_work = 200000;
  /// Once a net verifies but scores worse than the best overlap-free net, fresh trees of this
  /// many more attempt numbers (every heuristic) are made; as many of those scored better than
  /// the verified net are checked, best first, and the first that verifies replaces it. 0: none;
  /// negative: 8 with the cut-length objective, 0 with hull area (there it made 52 of the shared sets'
  /// 629 nets 5.5% smaller, median, for 17% more selection time, past the 0.1 s per model of
  /// Bulbasaur's and Cow's DC-shells; doc/fold_check.md).
  int fold_improve_attempts = -1;
  /// Then, with the cut-length objective, a net still longer than the best overlap-free one is
  /// shortened by edge swaps (fold a cut edge, cut the shortest folded edge of the cycle it
  /// closes), kept while the net stays overlap-free and its folding verifies (each check only of
  /// the pairs of pieces the swaps moved apart, the net returned checked in full); the descent
  /// gets this much work of its own (scaled like fold_work) and up to 4 x fold_candidates checks;
  /// budget left at a local optimum goes to a second descent from the same net, one swap at a time.
  /// 0: none; negative: 2 x fold_work with cut length, 0 with hull area (the swaps are by
  /// length). On the 69 inputs of doc/unfold_blender.md it made 15 returned nets shorter (median
  /// 5.7%, up to 23%) for 26% more time over the 69 (medians of 3), most of it on the shells
  /// that gained (up to 3.6 s for 598 faces; doc/fold_check.md).
  long long fold_descent_work = -1;
  /// When no net of this objective verifies (`heuristic` best or ga), the selection of the other
  /// objective (heuristic best) runs too, and its net is returned if it verifies, or is
  /// overlap-free where this one is not (UnfoldStats::objective says which ranked it).
  bool fold_other_objective = true;
};

/// Features of a net, each in model units.
struct NetMetrics {
  double cut_length = 0;  ///< total length of the cut shell edges (each counted once)
  double hull_area = 0;   ///< area of the convex hull of the net
  int overlapping_pairs = 0;  ///< pairs of net faces whose interiors overlap (0 = overlap-free)
};

struct UnfoldStats {
  int faces = 0, facets = 0;  ///< triangles; maximal coplanar regions (at flat_angle)
  /// The flat angle used: options.flat_angle, or 10x / 100x it (at most 0.01 rad) when no
  /// overlap-free net exists until nearly flat folds are merged too (net lengths then match the
  /// shell's to about flat_angle^2 relative, not to rounding).
  double flat_angle = 0;
  bool convex = true;         ///< no reflex edge beyond flat_angle (closed genus 0 is required)
  int reflex_edges = 0;
  double max_reflex_angle = 0;  ///< radians
  std::string heuristic;        ///< the heuristic that produced the returned net
  int attempts = 0;             ///< distinct cut trees evaluated
  NetMetrics first;             ///< the first net tried (steepest edge, first direction)
  NetMetrics result;            ///< the returned net
  FoldCheckResult fold;         ///< folding check of the returned net (not run: verified=false, steps=0)
  int fold_checks = 0;          ///< nets whose folding was checked
  bool fold_fallback = false;   ///< the returned net verified only within fold_fallback_slack
  /// The objective whose selection gave the returned net: options.objective, or the other one
  /// when only that one's net verified (UnfoldOptions::fold_other_objective).
  UnfoldObjective objective = UnfoldObjective::hull_area;
  double seconds = 0;
};

/// Unfolds a closed triangle (or convex-polygon) mesh. Polygons are fan-triangulated from their
/// first corner, in face order; the net's faces are those triangles in that order.
/// Returns the best net found; it may overlap (stats->result.overlapping_pairs > 0) when no
/// overlap-free one was found (possible only for non-convex input in practice).
/// Throws InputError when the mesh is not a closed oriented 2-manifold of genus 0, has fewer
/// than 4 faces, or has a degenerate (zero-area) face.
Net unfold_convex_mesh(const Mesh& mesh, const UnfoldOptions& options = {}, UnfoldStats* stats = nullptr);

/// The share of a folding-check budget (UnfoldOptions::fold_work, fold_first_work) a shell of
/// `faces` faces gets: work x faces / 200, between 1x and 3x (Pikachu's 1,290-face shell
/// verifies within 3x, not within 2x; above it the budget mostly goes to nets that never
/// verify), saturating instead of overflowing.
long long scaled_fold_work(long long work, std::size_t faces);

/// Cut length, hull area and overlap count of a net.
NetMetrics net_metrics(const Net& net);

/// The net as OBJ: `v x y 0` per net corner (round-trip precision), then one `f` per shell
/// triangle in shell order, corners in the shell's order. Corners shared by faces joined along a
/// fold are written once, so a checker sees the folds as shared edges.
void write_net_obj(const Net& net, std::ostream& out);

}  // namespace dcshell
