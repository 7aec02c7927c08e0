// Genetic net optimisation (after Xi & Lien): a genome is one weight per facet pair; decoding is
// Kruskal's spanning tree on those weights (flat edges always folded), so every genome is a
// valid cut tree. Fitness = weighted sum of the features normalised by the first net (hull area,
// cut length; weights set by the objective); only overlap-free nets are feasible, overlapping
// ones rank after all feasible ones (fewer overlaps first). Seeded with the heuristics' nets,
// reproducible for a given seed.
#pragma once
#include <vector>

#include "dcshell/unfold.h"

namespace dcshell {

struct GaOptions {
  int population = 24;
  /// Nets evaluated in total; 0 = automatic (about the same time for small and large shells).
  int evaluations = 0;
};

/// Runs the heuristics (as UnfoldHeuristic::best) and then the genetic search on their nets.
/// stats->first is the first heuristic net: the reference the improvement is measured against.
/// `best_score_per_generation` (optional) receives the best fitness after each generation
/// (1 = as good as the first net; lower is better).
Net unfold_ga(const Mesh& mesh, const UnfoldOptions& options, const GaOptions& ga,
              UnfoldStats* stats = nullptr, std::vector<double>* best_score_per_generation = nullptr);

}  // namespace dcshell
