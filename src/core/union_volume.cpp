// Exact union volume by inclusion–exclusion over the nerve of the polytopes.
#include "dcshell/union_volume.h"

#include "dcshell/overlaps.h"

#include <algorithm>
#include <cmath>

namespace dcshell {

namespace {

struct NerveWalk {
  const std::vector<ExactPolytope>& polys;
  const std::vector<std::vector<std::size_t>>& later;  // overlapping neighbours with larger index
  // Known pairwise intersections, parallel to `later` (null: compute them).
  const std::vector<std::vector<const ExactPolytope*>>* pair_region;
  bool exact;
  UnionVolume& out;
  CGAL::Interval_nt<true> sum_interval{0};  // protected: sets the rounding mode itself
  ExactRational sum_exact{0};

  // `cur` = intersection of the chosen set (size `depth`), `cands` = indices that overlap every
  // member and come after the last one.
  void walk(const ExactPolytope& cur, std::size_t depth, const std::vector<std::size_t>& cands, std::size_t first) {
    for (std::size_t c = 0; c < cands.size(); ++c) {
      std::size_t k = cands[c];
      ExactPolytope next;
      if (depth == 1 && pair_region) {
        const auto& l = later[first];
        next = *(*pair_region)[first][std::size_t(std::lower_bound(l.begin(), l.end(), k) - l.begin())];
      } else {
        next = intersect(cur, polys[k]);
      }
      if (next.empty()) continue;
      add(next, depth + 1);
      std::vector<std::size_t> rest;
      for (std::size_t d = c + 1; d < cands.size(); ++d)
        if (std::binary_search(later[k].begin(), later[k].end(), cands[d])) rest.push_back(cands[d]);
      if (!rest.empty()) walk(next, depth + 1, rest, first);
    }
  }
  void add(const ExactPolytope& p, std::size_t depth) {
    const bool plus = depth % 2 == 1;
    if (exact) {
      ExactRational v = exact_volume(p);
      if (plus) sum_exact += v; else sum_exact -= v;
    } else {
      auto v = volume_interval(p);
      CGAL::Interval_nt<true> w(v.inf(), v.sup());
      if (plus) sum_interval += w; else sum_interval -= w;
    }
    ++out.terms;
    out.max_clique = std::max(out.max_clique, depth);
  }
};

UnionVolume sum_over_nerve(const std::vector<ExactPolytope>& polys, const std::vector<std::vector<std::size_t>>& later,
                           const std::vector<std::vector<const ExactPolytope*>>* pair_region,
                           double max_relative_error, ExactRational* exact_sum) {
  UnionVolume out;
  const std::size_t n = polys.size();
  for (bool exact : {false, true}) {
    if (!exact && exact_sum) continue;
    out.terms = out.max_clique = 0;
    NerveWalk w{polys, later, pair_region, exact, out};
    for (std::size_t i = 0; i < n; ++i) {
      if (polys[i].empty()) continue;
      w.add(polys[i], 1);
      if (!later[i].empty()) w.walk(polys[i], 1, later[i], i);
    }
    if (!exact) {
      double lo = w.sum_interval.inf(), hi = w.sum_interval.sup();
      out.value = 0.5 * (lo + hi);
      out.error_bound = 0.5 * (hi - lo);
      if (hi - lo <= max_relative_error * std::fabs(out.value)) return out;
    } else {
      out.value = CGAL::to_double(w.sum_exact);
      out.error_bound = std::fabs(out.value) * 1e-16;  // rounding of the exact rational
      out.exact_fallback = true;
      if (exact_sum) *exact_sum = w.sum_exact;
    }
  }
  return out;
}

// Box-overlapping neighbours with larger index: the candidates of the nerve walk.
std::vector<std::vector<std::size_t>> later_neighbours(const std::vector<ExactPolytope>& polys) {
  const std::size_t n = polys.size();
  std::vector<CGAL::Bbox_3> boxes(n);
  for (std::size_t i = 0; i < n; ++i) boxes[i] = bbox(polys[i]);
  std::vector<std::vector<std::size_t>> later(n);
  for (auto [i, j] : box_overlap_pairs(boxes))
    if (!polys[i].empty() && !polys[j].empty()) later[i].push_back(j);
  for (auto& l : later) std::sort(l.begin(), l.end());
  return later;
}

// The walk's start from the pairs with a common interior, whose intersections `overlaps`
// already holds: `later` and `region` in parallel, sorted by the second index.
struct KnownPairs {
  std::vector<std::vector<std::size_t>> later;
  std::vector<std::vector<const ExactPolytope*>> region;
};

KnownPairs known_pairs(std::size_t n, const std::vector<Overlap>& overlaps) {
  std::vector<std::vector<std::pair<std::size_t, const ExactPolytope*>>> by_first(n);
  for (const auto& o : overlaps) by_first[o.i].push_back({o.j, &o.region});
  KnownPairs k{std::vector<std::vector<std::size_t>>(n), std::vector<std::vector<const ExactPolytope*>>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    std::sort(by_first[i].begin(), by_first[i].end());
    for (const auto& [j, r] : by_first[i]) k.later[i].push_back(j), k.region[i].push_back(r);
  }
  return k;
}

}  // namespace

UnionVolume union_volume(const std::vector<ExactPolytope>& polys, double max_relative_error) {
  return sum_over_nerve(polys, later_neighbours(polys), nullptr, max_relative_error, nullptr);
}

ExactRational exact_union_volume(const std::vector<ExactPolytope>& polys, const std::vector<Overlap>* overlaps) {
  ExactRational v(0);
  if (overlaps) {
    const KnownPairs k = known_pairs(polys.size(), *overlaps);
    sum_over_nerve(polys, k.later, &k.region, 0.0, &v);
  } else {
    sum_over_nerve(polys, later_neighbours(polys), nullptr, 0.0, &v);
  }
  return v;
}

UnionVolume union_volume(const std::vector<ExactPolytope>& polys, const std::vector<Overlap>& overlaps,
                         double max_relative_error) {
  // Only pairs with a common interior can start a non-empty term, and their intersections are
  // already known: the walk starts from them.
  const KnownPairs k = known_pairs(polys.size(), overlaps);
  return sum_over_nerve(polys, k.later, &k.region, max_relative_error, nullptr);
}

}  // namespace dcshell
