// Edge-swap descent from a verified net (cut length; fold_selection.h, stage 6): a verified net
// still longer than the best overlap-free one is shortened swap by swap (fold a cut group, cut
// the shortest folded group on the cycle it closes), each batch kept only when the net stays
// overlap-free and its folding still verifies. A swap moves one branch of the net, so the
// verified motion mostly survives it, where the short nets the search made fold into collisions
// (doc/fold_check.md, *Descent by edge swaps*).
#include <utility>

#include "unfold/fold_selection.h"

namespace dcshell::unfold_detail {

std::optional<LengthSwap> best_length_swap(const ShellGraph& g, const std::vector<char>& folded,
                                           const std::set<std::pair<int, int>>& tabu) {
  // The tree's cycles come from a rooted copy of it (parent and depth per facet), walked up from
  // both ends of each cut group: O(groups x depth).
  std::vector<std::vector<std::pair<int, int>>> adj(g.num_facets);
  for (int gi = 0; gi < g.num_groups(); ++gi)
    if (folded[gi]) {
      const auto ab = g.group_facets(gi);
      adj[ab[0]].push_back({ab[1], gi}), adj[ab[1]].push_back({ab[0], gi});
    }
  std::vector<int> parent(g.num_facets, -1), up_group(g.num_facets, -1), depth(g.num_facets, 0), queue{0};
  parent[0] = 0;
  for (std::size_t q = 0; q < queue.size(); ++q)
    for (const auto& [b, gi] : adj[queue[q]])
      if (parent[b] < 0) parent[b] = queue[q], up_group[b] = gi, depth[b] = depth[queue[q]] + 1, queue.push_back(b);
  std::optional<LengthSwap> best;
  for (int gi = 0; gi < g.num_groups(); ++gi) {
    if (folded[gi]) continue;
    auto [a, b] = g.group_facets(gi);
    while (a != b) {
      if (depth[a] < depth[b]) std::swap(a, b);
      const int f = up_group[a];
      const double gain = g.group_length[gi] - g.group_length[f];
      if (gain > 1e-9 * g.group_length[gi] && (!best || gain > best->gain) && !tabu.count({gi, f}))
        best = LengthSwap{gi, f, gain};
      a = parent[a];
    }
  }
  return best;
}

std::vector<int> shared_parts(const ShellGraph& g, const std::vector<char>& a, const std::vector<char>& b) {
  UnionFind parts(g.num_facets);
  for (int gi = 0; gi < g.num_groups(); ++gi)
    if (a[gi] && b[gi]) {
      const auto ab = g.group_facets(gi);
      parts.unite(ab[0], ab[1]);
    }
  std::vector<int> part(g.F.size());
  for (std::size_t f = 0; f < g.F.size(); ++f) part[f] = parts.find(g.facet[f]);
  return part;
}

bool FoldSelection::descend(bool single, int max_checks) {
  // Batches double after a verified one and halve after a refuted one; a single swap refuted
  // (fold) or overlapping is not tried again. `single`: one swap per check, and the refused
  // swaps are tried again after each accepted one.
  max_score_ = returned_score();
  std::vector<char> tree = folded_groups(g_, verified_genome_);
  std::set<std::pair<int, int>> tabu;
  bool moved = false;
  int batch = single ? 1 : 4;
  while (st_.fold_checks < max_checks && work_ > 0) {
    auto next = tree;
    std::vector<std::pair<int, int>> applied;
    while (static_cast<int>(applied.size()) < batch && work_ > 0) {
      const auto sw = best_length_swap(g_, next, tabu);
      if (!sw) break;
      next[sw->cut] = 1, next[sw->fold] = 0;
      work_ -= 8 + sg_.faces();
      if (sg_.evaluate(next).overlapping_pairs != 0) {
        next[sw->cut] = 0, next[sw->fold] = 1;
        tabu.insert({sw->cut, sw->fold});
        continue;
      }
      applied.push_back({sw->cut, sw->fold});
    }
    if (applied.empty()) break;
    Genome w(next.size());  // 0 = folded, 1 = cut: Kruskal gives back exactly this tree
    for (std::size_t i = 0; i < next.size(); ++i) w[i] = next[i] ? 0 : 1;
    // Every pair of the current net is proved; within a part both trees share, the hinges
    // between two faces, so their relative motion, are unchanged: only pairs across parts are
    // checked.
    const std::vector<int> part = shared_parts(g_, tree, next);
    if (check(w, "descent", first_budget(), true, &part)) {
      tree = std::move(next);
      moved = true;
      if (single) tabu.clear();
      batch = single ? 1 : std::min(2 * batch, 16);
      max_score_ = returned_score();  // never back up (the score weighs hull area too)
    } else if (applied.size() == 1) {
      tabu.insert(applied[0]);
      batch = 1;
    } else {
      batch = static_cast<int>(applied.size()) / 2;
    }
  }
  return moved;
}

void FoldSelection::descend_by_length() {
  // Its own budget, fold_descent_work, is added to what is left.
  const long long descent_work = options_.fold_descent_work >= 0 ? options_.fold_descent_work
                                 : options_.objective == UnfoldObjective::cut_length
                                     ? add_work(options_.fold_work, options_.fold_work)
                                     : 0;
  if (!done_ || descent_work <= 0 || options_.objective != UnfoldObjective::cut_length ||
      returned_score() <= best_score_ * (1 + 1e-9))
    return;
  work_ = add_work(work_, scaled_fold_work(descent_work, g_.F.size()));
  const Kept start = keep();
  const int max_checks = st_.fold_checks + 4 * checks_;
  // The net returned is proved in full, not by the chain of partial proofs (which is sound, but
  // this keeps every verdict the check's own).
  auto full_check = [&] { return check(verified_genome_, "descent", add_work(work_, first_work_), false); };
  if (descend(false, max_checks) && !full_check()) restore(start);
  // Budget left (the descent stopped at a local optimum): once more from the start net with
  // single swaps, the refused ones retried after each accepted one; the shorter end is kept. On
  // ellip (48 faces) that reaches Blender's 15.996 where the batches stop at 16.22.
  if (st_.fold_checks < max_checks && work_ > 0) {
    const Kept first = keep();
    restore(start);
    if (!(descend(true, max_checks) && returned_score() < score(first.result) && full_check())) restore(first);
  }
}

}  // namespace dcshell::unfold_detail
