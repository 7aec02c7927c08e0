// Genetic search over cut trees (Xi & Lien): genomes are group weights in [0, 1], decoded by
// Kruskal, so crossover and mutation always give valid spanning trees.
#include "dcshell/unfold_ga.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>

#include "unfold/unfold_internal.h"

namespace dcshell::unfold_detail {

namespace {

// Kruskal only sees the order of the weights; ranks put genomes from different heuristics on
// one scale, so crossover mixes orders rather than units.
Genome to_ranks(const Genome& w) {
  std::vector<int> order(w.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return w[a] < w[b]; });
  Genome r(w.size());
  double scale = w.size() > 1 ? 1.0 / static_cast<double>(w.size() - 1) : 0.0;
  for (std::size_t i = 0; i < order.size(); ++i) r[order[i]] = static_cast<double>(i) * scale;
  return r;
}

struct Individual {
  Genome genome;
  NetMetrics metrics;
  double score = 0;
  std::string heuristic;
};

}  // namespace

GaRun run_ga(const ShellGraph& g, const SearchGraph& sg, const UnfoldOptions& options, int evaluations,
             int population, const SearchResult& seeds) {
  GaRun run;
  const NetMetrics ref = seeds.evaluated.front().metrics;
  const int n = g.num_groups();
  Rng rng(mix_seed(options.seed, 0x6761ULL));
  std::unordered_map<std::uint64_t, NetMetrics> cache;
  for (const auto& c : seeds.evaluated) cache.emplace(tree_hash(folded_groups(g, c.genome)), c.metrics);

  auto evaluate = [&](Individual& ind) {
    auto folded = folded_groups(g, ind.genome);
    auto h = tree_hash(folded);
    auto it = cache.find(h);
    if (it == cache.end()) {
      it = cache.emplace(h, sg.evaluate(folded)).first;
      ++run.evaluations;
    }
    ind.metrics = it->second;
    ind.score = objective_score(ind.metrics, ref, options.objective);
  };
  auto by_score = [](const Individual& a, const Individual& b) { return a.score < b.score; };

  // Initial population: the heuristics' best nets, then random genomes.
  std::vector<Individual> pop;
  {
    std::vector<int> idx(seeds.evaluated.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::vector<double> score(idx.size());
    for (std::size_t i = 0; i < idx.size(); ++i)
      score[i] = objective_score(seeds.evaluated[i].metrics, ref, options.objective);
    std::stable_sort(idx.begin(), idx.end(), [&](int a, int b) { return score[a] < score[b]; });
    for (int i : idx) {
      if (static_cast<int>(pop.size()) >= population / 2) break;
      const auto& c = seeds.evaluated[i];
      pop.push_back({to_ranks(c.genome), c.metrics, score[i], c.heuristic});
    }
  }
  while (static_cast<int>(pop.size()) < population) {
    Individual ind;
    ind.genome.resize(n);
    for (auto& x : ind.genome) x = rng.uniform();
    ind.heuristic = "ga";
    evaluate(ind);
    pop.push_back(std::move(ind));
  }
  std::stable_sort(pop.begin(), pop.end(), by_score);
  run.best_score_per_generation.push_back(pop.front().score);

  auto tournament = [&]() -> const Individual& {
    const Individual* best = &pop[rng.below(static_cast<int>(pop.size()))];
    for (int k = 0; k < 2; ++k) {
      const Individual& c = pop[rng.below(static_cast<int>(pop.size()))];
      if (c.score < best->score) best = &c;
    }
    return *best;
  };
  const double gene_mutation = std::min(0.5, 2.0 / std::max(n, 1));
  // Generations end when the evaluation budget is spent, or after many generations without a
  // new tree (small shells have few distinct trees).
  int stale = 0;
  while (run.evaluations < evaluations && stale < 50) {
    int before = run.evaluations;
    std::vector<Individual> next(pop.begin(), pop.begin() + 2);  // elitism
    while (static_cast<int>(next.size()) < population) {
      const Individual &a = tournament(), &b = tournament();
      Individual child;
      child.genome = a.genome;
      if (rng.uniform() < 0.9)
        for (int i = 0; i < n; ++i)
          if (rng.uniform() < 0.5) child.genome[i] = b.genome[i];
      bool mutated = false;
      for (int i = 0; i < n; ++i)
        if (rng.uniform() < gene_mutation) child.genome[i] = rng.uniform(), mutated = true;
      if (!mutated && n > 0) child.genome[rng.below(n)] = rng.uniform();
      child.heuristic = "ga";
      evaluate(child);
      next.push_back(std::move(child));
    }
    std::stable_sort(next.begin(), next.end(), by_score);
    pop = std::move(next);
    run.best_score_per_generation.push_back(pop.front().score);
    stale = run.evaluations == before ? stale + 1 : 0;
  }
  run.best = {pop.front().genome, pop.front().metrics, pop.front().heuristic};
  return run;
}

}  // namespace dcshell::unfold_detail
