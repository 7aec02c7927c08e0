// Genetic search over cut trees (Xi & Lien) with a local search (memetic algorithm).
//
// Individuals are fold sets: the polytope edges (facet groups) that stay folded, always a
// spanning tree of the facet graph. Their genome for the rest of the unfolder is 0 for a folded
// group and 1 for a cut one (Kruskal reproduces exactly that tree).
//
// Operators:
// - crossover keeps every group folded in both parents, then prefers groups folded in one of
//   them (for the cut-length objective the longer ones first), and completes the tree with the
//   rest (never needed: the union of two spanning trees is connected);
// - mutation is an edge exchange: fold one cut group, cut a folded group on the cycle it closes;
// - local search (on the seeds and on the GA's best): best-first edge exchanges evaluated
//   analytically. Exchanging folded group f for cut group c moves the piece S that f held by a
//   rigid motion (the one that lands c's sides on each other), so the new hull is the hull of
//   hull(rest) and the moved hull(S), and the new cut length is cut + len(f) - len(c); only
//   exchanges that improve the objective are checked for overlaps (first between the moved piece
//   and the rest, then in full). For hull area an exchange can only help when both sides of f
//   hold hull vertices of the net. For cut length the exchange neighbourhood is the exact
//   minimum-spanning-tree neighbourhood (cut length = total length - folded length): without
//   overlaps it ends at the minimum-length cut tree.
#include "dcshell/unfold_ga.h"

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>

#include "dcshell/net_overlap.h"
#include "unfold/unfold_internal.h"

namespace dcshell::unfold_detail {

namespace {

using Vec2 = Eigen::Vector2d;

struct Individual {
  std::vector<char> folded;  ///< fine groups
  NetMetrics metrics;
  double score = 0;
  std::string heuristic;
};

Genome genome_of(const std::vector<char>& folded) {
  Genome w(folded.size());
  for (std::size_t i = 0; i < folded.size(); ++i) w[i] = folded[i] ? 0.0 : 1.0;
  return w;
}

std::vector<Epick::Point_2> hull_of(const std::vector<Epick::Point_2>& pts) {
  std::vector<Epick::Point_2> h;
  CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(h));
  return h;
}

struct StopSearch {};
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, int>;

// Shared by the GA and the local search: evaluations on the search graph, cached by tree.
struct Evaluator {
  const ShellGraph& g;  // fine
  const SearchGraph& sg;
  NetMetrics ref;
  UnfoldObjective obj;
  std::unordered_map<std::uint64_t, NetMetrics> cache;
  int evaluations = 0;

  NetMetrics metrics(const std::vector<char>& folded) {
    auto h = tree_hash(folded);
    auto it = cache.find(h);
    if (it == cache.end()) {
      it = cache.emplace(h, sg.evaluate(folded)).first;
      ++evaluations;
    }
    return it->second;
  }
  double score(const NetMetrics& m) const { return objective_score(m, ref, obj); }
  void evaluate(Individual& ind) {
    ind.metrics = metrics(ind.folded);
    ind.score = score(ind.metrics);
  }
};

// The facet tree of a fold set on a graph: parent facet and group, subtree intervals.
struct FacetTree {
  std::vector<int> parent, parent_group, depth, tin, tout, order;
  FacetTree(const ShellGraph& G, const std::vector<std::array<int, 2>>& ends, const std::vector<char>& folded) {
    const int n = G.num_facets;
    std::vector<std::vector<std::pair<int, int>>> adj(n);
    for (int gi = 0; gi < G.num_groups(); ++gi)
      if (folded[gi]) adj[ends[gi][0]].push_back({ends[gi][1], gi}), adj[ends[gi][1]].push_back({ends[gi][0], gi});
    parent.assign(n, -1), parent_group.assign(n, -1), depth.assign(n, 0), tin.assign(n, -1), tout.assign(n, -1);
    // Iterative DFS from facet 0: tin/tout intervals identify subtrees.
    std::vector<std::pair<int, std::size_t>> stack = {{0, 0}};
    int t = 0;
    tin[0] = t++;
    order.push_back(0);
    while (!stack.empty()) {
      auto& [v, i] = stack.back();
      if (i < adj[v].size()) {
        auto [u, gi] = adj[v][i++];
        if (u == parent[v] && gi == parent_group[v]) continue;
        if (tin[u] >= 0) continue;
        parent[u] = v, parent_group[u] = gi, depth[u] = depth[v] + 1, tin[u] = t++;
        order.push_back(u);
        stack.push_back({u, 0});
      } else {
        tout[v] = t;
        stack.pop_back();
      }
    }
  }
  bool in_subtree(int v, int root) const { return tin[v] >= tin[root] && tin[v] < tout[root]; }
  /// Folded groups on the tree path between facets a and b.
  std::vector<int> path(int a, int b) const {
    std::vector<int> out;
    while (a != b) {
      if (depth[a] >= depth[b]) out.push_back(parent_group[a]), a = parent[a];
      else out.push_back(parent_group[b]), b = parent[b];
    }
    return out;
  }
};

// Local search by edge exchanges (see the file comment), on the search graph.
class LocalSearch {
 public:
  LocalSearch(Evaluator& ev) : ev_(ev), G_(ev.sg.use_coarse ? ev.sg.coarse : *ev.sg.fine) {
    const int ng = G_.num_groups();
    to_fine_.resize(ng);
    for (int gi = 0; gi < ng; ++gi) to_fine_[ev.sg.use_coarse ? ev.sg.group_map[gi] : gi] = gi;
    ends_.resize(ng);
    for (int gi = 0; gi < ng; ++gi) {
      ends_[gi] = G_.group_facets(gi);
    }
  }

  /// Improves `ind` (overlap-free) in place; at most `max_evaluations` full evaluations and
  /// about `max_work` point operations of analytic evaluation. Returns true if it improved.
  bool improve(Individual& ind, int max_evaluations, double max_work) {
    if (ind.metrics.overlapping_pairs != 0) return false;
    const int start_evals = ev_.evaluations;
    double work = 0;
    bool improved = false;
    for (;;) {
      if (ev_.evaluations - start_evals >= max_evaluations || work >= max_work) break;
      std::vector<char> sf = to_search(ind.folded);
      Decoded d = decode(G_, sf, 0);
      FacetTree tree(G_, ends_, sf);
      const auto& P = d.net.corners;
      work += static_cast<double>(P.size());
      auto moves = candidate_moves(ind, sf, tree, P, work, max_work);
      bool accepted = false;
      for (auto& mv : moves) {
        if (ev_.evaluations - start_evals >= max_evaluations || work >= max_work) break;
        work += static_cast<double>(P.size()) * 4;
        if (piece_overlaps_rest(tree, mv, P)) continue;
        std::vector<char> cand = ind.folded;
        cand[to_fine_[mv.f]] = 0;
        cand[to_fine_[mv.c]] = 1;
        NetMetrics m = ev_.metrics(cand);
        double s = ev_.score(m);
        if (m.overlapping_pairs == 0 && s < ind.score - 1e-12) {
          ind.folded = std::move(cand), ind.metrics = m, ind.score = s;
          accepted = improved = true;
          break;
        }
      }
      if (!accepted) break;
    }
    return improved;
  }

  const ShellGraph& graph() const { return G_; }
  const std::vector<std::array<int, 2>>& ends() const { return ends_; }
  std::vector<char> to_search(const std::vector<char>& fine) const {
    std::vector<char> s(fine.size());
    for (std::size_t gi = 0; gi < s.size(); ++gi) s[gi] = fine[to_fine_[gi]];
    return s;
  }
  int to_fine(int sgi) const { return to_fine_[sgi]; }

 private:
  struct Move {
    int f = -1, c = -1;  // search-graph groups: f folded -> cut, c cut -> folded
    int piece = -1;      // root facet of the moved subtree (the child side of f)
    Eigen::Matrix2d R;
    Vec2 T;
    double estimate = 0;  // estimated score (lower is better)
  };

  // Rigid motion that lands the moved piece's side of group c onto the other side.
  bool motion(const FacetTree& tree, int piece, int c, const std::vector<std::array<Vec2, 3>>& P, Move& mv) const {
    const auto& e = G_.edges[G_.group_edges[c][0]];
    int fs = e.f0, fr = e.f1;
    if (!tree.in_subtree(G_.facet[fs], piece)) std::swap(fs, fr);
    auto at = [&](int f, int v) {
      for (int k = 0; k < 3; ++k)
        if (G_.F[f][k] == v) return P[f][k];
      return Vec2(0, 0);
    };
    Vec2 s0 = at(fs, e.v0), s1 = at(fs, e.v1), r0 = at(fr, e.v0), r1 = at(fr, e.v1);
    Vec2 ds = s1 - s0, dr = r1 - r0;
    double cs = ds.dot(dr), sn = ds.x() * dr.y() - ds.y() * dr.x(), n = std::hypot(cs, sn);
    if (!(n > 0)) return false;
    cs /= n, sn /= n;
    mv.R << cs, -sn, sn, cs;
    mv.T = r0 - mv.R * s0;
    return true;
  }

  std::vector<Move> candidate_moves(const Individual& ind, const std::vector<char>& sf, const FacetTree& tree,
                                    const std::vector<std::array<Vec2, 3>>& P, double& work, double max_work) const {
    std::vector<Move> moves;
    const int ng = G_.num_groups();
    const double cut = ind.metrics.cut_length, hull = ind.metrics.hull_area;
    auto est_score = [&](double cut_len, double hull_area) {
      NetMetrics m;
      m.cut_length = cut_len, m.hull_area = hull_area;
      return ev_.score(m);
    };
    // The net's distinct points (corners joined across folds coincide exactly): each facet's
    // points as indices into them, so the hulls below see each point once, not once per face.
    std::vector<Vec2> pts_u;
    std::vector<std::vector<int>> facet_pts(G_.num_facets);
    {
      std::vector<std::pair<std::pair<double, double>, int>> keyed;
      for (int f = 0; f < static_cast<int>(P.size()); ++f)
        for (auto& p : P[f]) keyed.push_back({{p.x(), p.y()}, G_.facet[f]});
      std::sort(keyed.begin(), keyed.end());
      for (std::size_t i = 0; i < keyed.size(); ++i) {
        if (i == 0 || keyed[i].first != keyed[i - 1].first) pts_u.emplace_back(keyed[i].first.first, keyed[i].first.second);
        auto& fp = facet_pts[keyed[i].second];
        const int id = static_cast<int>(pts_u.size()) - 1;
        if (fp.empty() || fp.back() != id) fp.push_back(id);
      }
    }
    // Facets holding a hull vertex of the net.
    std::vector<Epick::Point_2> all;
    std::vector<int> owner;
    for (int fc = 0; fc < G_.num_facets; ++fc)
      for (int id : facet_pts[fc]) all.emplace_back(pts_u[id].x(), pts_u[id].y()), owner.push_back(fc);
    auto H = hull_of(all);
    std::vector<char> on_hull(G_.num_facets, 0);
    {
      std::vector<std::pair<double, double>> hv;
      for (auto& h : H) hv.push_back({h.x(), h.y()});
      std::sort(hv.begin(), hv.end());
      for (std::size_t i = 0; i < all.size(); ++i)
        if (std::binary_search(hv.begin(), hv.end(), std::make_pair(all[i].x(), all[i].y()))) on_hull[owner[i]] = 1;
    }
    std::vector<int> hull_in_subtree(G_.num_facets, 0);
    for (auto it = tree.order.rbegin(); it != tree.order.rend(); ++it) {
      hull_in_subtree[*it] += on_hull[*it];
      if (tree.parent[*it] >= 0) hull_in_subtree[tree.parent[*it]] += hull_in_subtree[*it];
    }
    const int hull_total = hull_in_subtree[0];
    const bool by_cut = ev_.obj == UnfoldObjective::cut_length;

    // Exchanges: cut group c against a folded group f on its tree path. For cut length any
    // longer c may help; for hull area only an f with hull vertices on both sides (else the side
    // without them moves inside an unchanged hull).
    std::vector<std::vector<int>> crossing(ng);  // folded f -> cut groups c
    for (int c = 0; c < ng; ++c) {
      if (sf[c]) continue;
      auto path = tree.path(ends_[c][0], ends_[c][1]);
      work += static_cast<double>(path.size());
      for (int f : path) {
        if (by_cut && !(G_.group_length[c] > G_.group_length[f] * (1 + 1e-12))) continue;
        crossing[f].push_back(c);
      }
    }
    std::vector<int> mark_p(pts_u.size(), -1), mark_r(pts_u.size(), -1);  // point added for this piece
    for (int piece = 1; piece < G_.num_facets && work < max_work; ++piece) {
      int f = tree.parent_group[piece];
      if (f < 0 || crossing[f].empty()) continue;
      if (by_cut) {
        // The cut gain decides; the hull (1/100 weight) is left to the full evaluation.
        for (int c : crossing[f]) {
          Move mv;
          mv.f = f, mv.c = c, mv.piece = piece;
          if (!motion(tree, piece, c, P, mv)) continue;
          mv.estimate = est_score(cut + G_.group_length[f] - G_.group_length[c], hull);
          moves.push_back(mv);
        }
        continue;
      }
      if (!(hull_in_subtree[piece] > 0 && hull_in_subtree[piece] < hull_total)) continue;
      // Hulls of the piece and of the rest.
      std::vector<Epick::Point_2> ps, rs;
      for (int fc = 0; fc < G_.num_facets; ++fc) {
        const bool in = tree.in_subtree(fc, piece);
        auto& dst = in ? ps : rs;
        auto& mark = in ? mark_p : mark_r;
        for (int id : facet_pts[fc])
          if (mark[id] != piece) mark[id] = piece, dst.emplace_back(pts_u[id].x(), pts_u[id].y());
      }
      work += static_cast<double>(3 * P.size()) * 4;  // counted in face corners, whatever the dedup leaves
      auto hp = hull_of(ps), hr = hull_of(rs);
      for (int c : crossing[f]) {
        Move mv;
        mv.f = f, mv.c = c, mv.piece = piece;
        if (!motion(tree, piece, c, P, mv)) continue;
        std::vector<Epick::Point_2> pts = hr;
        for (auto& p : hp) {
          Vec2 q = mv.R * Vec2(p.x(), p.y()) + mv.T;
          pts.emplace_back(q.x(), q.y());
        }
        work += static_cast<double>(pts.size()) * 4;
        double new_hull = hull_area(pts);
        double new_cut = cut + G_.group_length[f] - G_.group_length[c];
        mv.estimate = est_score(new_cut, new_hull);
        if (mv.estimate < est_score(cut, hull) - 1e-12) moves.push_back(mv);
      }
    }
    std::stable_sort(moves.begin(), moves.end(), [](const Move& a, const Move& b) { return a.estimate < b.estimate; });
    return moves;
  }

  // Moved piece against the rest, triangles shrunk by 1e-7 relative so that faces touching
  // along the new fold (equal only up to the motion's rounding) do not count. A pre-filter:
  // the full check decides.
  bool piece_overlaps_rest(const FacetTree& tree, const Move& mv, const std::vector<std::array<Vec2, 3>>& P) const {
    const int nf = static_cast<int>(P.size());
    std::vector<Triangle2> tri(nf);
    std::vector<Box> a, b;
    for (int f = 0; f < nf; ++f) {
      bool moved = tree.in_subtree(G_.facet[f], mv.piece);
      Triangle2 t = P[f];
      if (moved)
        for (auto& p : t) p = mv.R * p + mv.T;
      Vec2 cen = (t[0] + t[1] + t[2]) / 3;
      for (auto& p : t) p = cen + (p - cen) * (1 - 1e-7);
      tri[f] = t;
      double lo[2] = {std::min({t[0].x(), t[1].x(), t[2].x()}), std::min({t[0].y(), t[1].y(), t[2].y()})};
      double hi[2] = {std::max({t[0].x(), t[1].x(), t[2].x()}), std::max({t[0].y(), t[1].y(), t[2].y()})};
      (moved ? a : b).emplace_back(lo, hi, f);
    }
    try {
      CGAL::box_intersection_d(a.begin(), a.end(), b.begin(), b.end(), [&](const Box& x, const Box& y) {
        if (triangle_interiors_overlap(tri[x.info()], tri[y.info()])) throw StopSearch{};
      });
    } catch (const StopSearch&) {
      return true;
    }
    return false;
  }

  Evaluator& ev_;
  const ShellGraph& G_;
  std::vector<int> to_fine_;  // search group -> fine group
  std::vector<std::array<int, 2>> ends_;
};

}  // namespace

GaRun run_ga(const ShellGraph& g, const SearchGraph& sg, const UnfoldOptions& options, int evaluations,
             int population, const SearchResult& seeds) {
  GaRun run;
  Evaluator ev{g, sg, seeds.evaluated.front().metrics, options.objective, {}, 0};
  const int n = g.num_groups();
  Rng rng(mix_seed(options.seed, 0x6761ULL));
  for (const auto& c : seeds.evaluated) ev.cache.emplace(tree_hash(folded_groups(g, c.genome)), c.metrics);
  LocalSearch ls(ev);
  const ShellGraph& G = ls.graph();
  // Analytic work allowed per local search: a few hundred neighbourhood scans.
  const double ls_work = population <= 0 ? 2e6 : 4e7;

  auto by_score = [](const Individual& a, const Individual& b) { return a.score < b.score; };
  auto finish = [&](const Individual& best) {
    run.best = {genome_of(best.folded), best.metrics, best.heuristic};
    run.evaluations = ev.evaluations;
  };

  // Seeds in score order (distinct trees).
  std::vector<Individual> seeded;
  for (const auto& c : seeds.evaluated) {
    Individual ind{folded_groups(g, c.genome), c.metrics, ev.score(c.metrics), c.heuristic};
    seeded.push_back(std::move(ind));
  }
  std::stable_sort(seeded.begin(), seeded.end(), by_score);
  if (seeded.empty()) return run;

  // Local search on the best seeds (population 0: local search on the best seed only).
  const int ls_starts = population <= 0 ? 1 : 3;
  int started = 0;
  for (auto& s : seeded) {
    if (started >= ls_starts || s.metrics.overlapping_pairs != 0) break;
    ++started;
    int budget = population <= 0 ? evaluations : std::max(1, (evaluations - ev.evaluations) / 4);
    if (ls.improve(s, budget, ls_work) && population > 0) s.heuristic = "ga";
  }
  std::stable_sort(seeded.begin(), seeded.end(), by_score);
  if (population <= 0) {
    finish(seeded.front());
    return run;
  }

  // Edge-exchange mutation on the search graph: fold a random cut group, cut a random folded
  // group on the cycle it closes.
  auto mutate = [&](std::vector<char>& fine_folded, int swaps) {
    std::vector<char> sf = ls.to_search(fine_folded);
    for (int k = 0; k < swaps; ++k) {
      FacetTree tree(G, ls.ends(), sf);
      std::vector<int> cut;
      for (int gi = 0; gi < G.num_groups(); ++gi)
        if (!sf[gi]) cut.push_back(gi);
      if (cut.empty()) return;
      int c = cut[rng.below(static_cast<int>(cut.size()))];
      auto path = tree.path(ls.ends()[c][0], ls.ends()[c][1]);
      if (path.empty()) return;
      int f = path[rng.below(static_cast<int>(path.size()))];
      sf[f] = 0, sf[c] = 1;
    }
    for (int gi = 0; gi < G.num_groups(); ++gi) fine_folded[ls.to_fine(gi)] = sf[gi];
  };

  // Initial population: the best seeds, mutated copies of the best, random trees.
  std::vector<Individual> pop;
  for (auto& s : seeded) {
    if (static_cast<int>(pop.size()) >= population / 2) break;
    pop.push_back(s);
  }
  const int copies = population / 4;
  for (int i = 0; i < copies && !pop.empty(); ++i) {
    Individual ind = pop[i % std::min<int>(3, static_cast<int>(pop.size()))];
    mutate(ind.folded, 1 + rng.below(3));
    ind.heuristic = "ga";
    ev.evaluate(ind);
    pop.push_back(std::move(ind));
  }
  while (static_cast<int>(pop.size()) < population) {
    Genome w(n);
    for (auto& x : w) x = rng.uniform();
    Individual ind{folded_groups(g, w), {}, 0, "ga"};
    ev.evaluate(ind);
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
  double max_len = 0;
  for (double l : g.group_length) max_len = std::max(max_len, l);
  const bool by_cut = options.objective == UnfoldObjective::cut_length;
  // Crossover keeping the common folds (see the file comment).
  auto crossover = [&](const Individual& a, const Individual& b) {
    Genome w(n);
    for (int i = 0; i < n; ++i) {
      double u = rng.uniform();
      int k = a.folded[i] + b.folded[i];
      double bias = by_cut ? 0.5 * u + 0.5 * (1 - g.group_length[i] / std::max(max_len, 1e-300)) : u;
      w[i] = k == 2 ? 0.3 * u : k == 1 ? 0.3 + 0.4 * bias : 0.7 + 0.3 * u;
    }
    return folded_groups(g, w);
  };

  // Generations end when the evaluation budget is spent, or after many generations without a
  // new tree (small shells have few distinct trees).
  int stale = 0;
  const int ls_reserve = std::max(1, evaluations / 5);  // kept for the final local search
  while (ev.evaluations < evaluations - ls_reserve && stale < 50) {
    int before = ev.evaluations;
    std::vector<Individual> next(pop.begin(), pop.begin() + 2);  // elitism
    while (static_cast<int>(next.size()) < population) {
      const Individual &a = tournament(), &b = tournament();
      Individual child;
      child.folded = rng.uniform() < 0.9 ? crossover(a, b) : a.folded;
      int swaps = 1;
      while (swaps < 4 && rng.uniform() < 0.4) ++swaps;
      if (rng.uniform() < 0.7 || child.folded == a.folded) mutate(child.folded, swaps);
      child.heuristic = "ga";
      ev.evaluate(child);
      next.push_back(std::move(child));
    }
    std::stable_sort(next.begin(), next.end(), by_score);
    // Memetic step: the best new child is polished by the local search (a short one).
    for (std::size_t i = 2; i < next.size(); ++i) {
      if (next[i].metrics.overlapping_pairs != 0) break;
      if (next[i].folded == next[0].folded || next[i].folded == next[1].folded) continue;
      ls.improve(next[i], std::max(1, (evaluations - ls_reserve - ev.evaluations) / 8), ls_work / 20);
      std::stable_sort(next.begin(), next.end(), by_score);
      break;
    }
    pop = std::move(next);
    run.best_score_per_generation.push_back(pop.front().score);
    stale = ev.evaluations == before ? stale + 1 : 0;
  }
  // Local search on the best individuals of the final population.
  int polished = 0;
  for (std::size_t i = 0; i < pop.size() && polished < 2; ++i) {
    if (pop[i].metrics.overlapping_pairs != 0) break;
    if (i > 0 && pop[i].folded == pop[0].folded) continue;
    ++polished;
    if (ls.improve(pop[i], std::max(1, evaluations - ev.evaluations), ls_work)) pop[i].heuristic = "ga";
  }
  std::stable_sort(pop.begin(), pop.end(), by_score);
  run.best_score_per_generation.push_back(pop.front().score);
  finish(pop.front());
  return run;
}

}  // namespace dcshell::unfold_detail
