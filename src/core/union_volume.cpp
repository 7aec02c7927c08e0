// Exact union volume: inclusion–exclusion over the nerve of the polytopes while the overlaps
// are shallow, a disjoint convex decomposition of the union when they are deep.
#include "dcshell/union_volume.h"

#include "dcshell/overlaps.h"

#include <CGAL/Mpzf.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dcshell {

namespace {

// A term of the sum: a convex polytope whose volume is added (plus) or subtracted.
struct Term {
  ExactPolytope polytope;
  bool plus = true;
};

// Depth-first walk over the subsets with a common interior, collecting their intersections
// with the inclusion–exclusion sign. Stops (`abandoned`) once it holds `budget` terms or its
// deep intersections pass `work_budget`: deep overlaps make the nerve exponential, and the
// decomposition below then takes over.
struct NerveWalk {
  const std::vector<ExactPolytope>& polys;
  const std::vector<std::vector<std::size_t>>& later;  // overlapping neighbours with larger index
  // Known pairwise intersections, parallel to `later` (null: compute them).
  const std::vector<std::vector<const ExactPolytope*>>* pair_region;
  std::size_t budget;       // most terms held
  double work_budget;       // most vertex-plane tests spent on intersections of three or more
  double work = 0;
  std::vector<Term> terms;
  std::size_t max_clique = 0;
  bool abandoned = false;

  // `cur` = intersection of the chosen set (size `depth`), `cands` = indices that overlap every
  // member and come after the last one.
  void walk(const ExactPolytope& cur, std::size_t depth, const std::vector<std::size_t>& cands, std::size_t first) {
    for (std::size_t c = 0; c < cands.size() && !abandoned; ++c) {
      std::size_t k = cands[c];
      ExactPolytope next;
      if (depth == 1 && pair_region) {
        const auto& l = later[first];
        next = *(*pair_region)[first][std::size_t(std::lower_bound(l.begin(), l.end(), k) - l.begin())];
      } else {
        // An intersection tests the vertices of `cur` against the faces of the next polytope.
        work += double(cur.vertices.size()) * double(polys[k].faces.size());
        if (work > work_budget) {
          abandoned = true;
          return;
        }
        next = intersect(cur, polys[k]);
      }
      if (next.empty()) continue;
      std::vector<std::size_t> rest;
      for (std::size_t d = c + 1; d < cands.size(); ++d)
        if (std::binary_search(later[k].begin(), later[k].end(), cands[d])) rest.push_back(cands[d]);
      if (rest.empty()) {
        add(std::move(next), depth + 1);
      } else {
        add(next, depth + 1);  // a copy: `terms` may reallocate during the walk below
        walk(next, depth + 1, rest, first);
      }
    }
  }
  void add(ExactPolytope p, std::size_t depth) {
    if (terms.size() >= budget) {
      abandoned = true;
      return;
    }
    terms.push_back({std::move(p), depth % 2 == 1});
    max_clique = std::max(max_clique, depth);
  }
};

// Interior-disjoint convex pieces whose union is the union of the polytopes: each polytope
// minus the ones before it in decreasing volume (a part nested in a larger one then leaves no
// piece at all). Q \ C is split along the faces of Q ∩ C that come from C, so every piece is
// a convex polytope whose vertices meet three input planes, and all terms are positive: the
// interval sum stays tight however deep the overlaps are.
std::vector<ExactPolytope> disjoint_pieces(const std::vector<ExactPolytope>& polys,
                                           const std::vector<std::vector<std::size_t>>& neighbours) {
  constexpr int kOwn = 0, kCutter = 1;
  auto retag = [](ExactPolytope p, int tag) {
    for (auto& f : p.faces) f.tag = tag;
    return p;
  };
  const std::size_t n = polys.size();
  std::vector<double> vol(n);
  for (std::size_t i = 0; i < n; ++i) vol[i] = approximate_volume(polys[i]);
  std::vector<std::size_t> order(n), rank(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return vol[a] > vol[b]; });
  for (std::size_t r = 0; r < n; ++r) rank[order[r]] = r;

  std::vector<ExactPolytope> pieces;
  for (std::size_t i : order) {
    if (polys[i].empty()) continue;
    std::vector<std::size_t> before;
    for (std::size_t j : neighbours[i])
      if (rank[j] < rank[i] && !polys[j].empty()) before.push_back(j);
    std::sort(before.begin(), before.end(), [&](std::size_t a, std::size_t b) { return rank[a] < rank[b]; });
    std::vector<ExactPolytope> mine{retag(polys[i], kOwn)};
    for (std::size_t j : before) {
      const ExactPolytope cutter = retag(polys[j], kCutter);
      const CGAL::Bbox_3 cbox = bbox(cutter);
      std::vector<ExactPolytope> next;
      for (auto& q : mine) {
        ExactPolytope r = CGAL::do_overlap(bbox(q), cbox) ? intersect(q, cutter) : ExactPolytope{};
        if (r.empty()) {
          next.push_back(std::move(q));
          continue;
        }
        // R's faces tagged kCutter are C's planes bounding Q ∩ C inside Q: Q \ C is the
        // union of Q ∩ {f_1..f_{k-1} <= 0} ∩ {f_k >= 0} over them, pairwise interior-disjoint.
        ExactPolytope rest = std::move(q);
        for (const auto& f : r.faces) {
          if (f.tag != kCutter) continue;
          ExactPolytope outside = clip(rest, f.plane.opposite(), kOwn);
          if (!outside.empty()) next.push_back(std::move(outside));
          rest = clip(rest, f.plane, kOwn);
          if (rest.empty()) break;
        }
      }
      mine = std::move(next);
      if (mine.empty()) break;
    }
    for (auto& q : mine) pieces.push_back(std::move(q));
  }
  return pieces;
}

// Σ ±vol(term) in intervals, from the coordinates' current approximations, then (when that is
// wider than `max_relative_error` of the value) after evaluating every vertex exactly (each
// coordinate then within an ulp). False when both are too wide.
bool interval_sum(const std::vector<Term>& terms, double max_relative_error, UnionVolume& out) {
  for (bool tight : {false, true}) {
    // The ends are summed exactly (doubles added into an Mpzf): rounding each of thousands of
    // additions outward would widen the sum by an ulp of the total per term.
    CGAL::Mpzf lo(0), hi(0);
    for (const auto& t : terms) {
      const auto v = volume_interval(t.polytope, tight);
      if (t.plus) {
        lo += CGAL::Mpzf(v.inf());
        hi += CGAL::Mpzf(v.sup());
      } else {
        lo -= CGAL::Mpzf(v.sup());
        hi -= CGAL::Mpzf(v.inf());
      }
    }
    const double l = lo.to_interval().first, h = hi.to_interval().second;
    out.value = 0.5 * (l + h);
    out.error_bound = 0.5 * (h - l);
    if (h - l <= max_relative_error * std::fabs(out.value)) return true;
  }
  return false;
}

// Σ ±vol(term) in exact rationals, whose denominators grow with every term: the expensive way.
void exact_sum_of(const std::vector<Term>& terms, UnionVolume& out, ExactRational* exact_sum) {
  ExactRational total(0);
  for (const auto& t : terms) {
    if (t.plus) total += exact_volume(t.polytope); else total -= exact_volume(t.polytope);
  }
  out.value = CGAL::to_double(total);
  out.error_bound = std::fabs(out.value) * 1e-16;  // rounding of the exact rational
  out.exact_fallback = true;
  if (exact_sum) *exact_sum = total;
}

std::vector<Term> decomposition_terms(const std::vector<ExactPolytope>& polys,
                                      const std::vector<std::vector<std::size_t>>& later) {
  // Symmetric neighbour lists: the decomposition visits the polytopes by volume.
  std::vector<std::vector<std::size_t>> neighbours(polys.size());
  for (std::size_t i = 0; i < polys.size(); ++i)
    for (std::size_t j : later[i]) neighbours[i].push_back(j), neighbours[j].push_back(i);
  std::vector<Term> terms;
  for (auto& p : disjoint_pieces(polys, neighbours)) terms.push_back({std::move(p), true});
  return terms;
}

// Nerve walk while it stays within budget (shallow overlaps: fewest exact constructions), else
// the disjoint decomposition; then the sum. With `automatic`, a nerve sum whose cancellation
// leaves the intervals too wide is also redone on the decomposition (positive terms) before
// anything is summed in rationals. `exact_sum` asks for the rational sum.
UnionVolume sum_union(const std::vector<ExactPolytope>& polys, const std::vector<std::vector<std::size_t>>& later,
                      const std::vector<std::vector<const ExactPolytope*>>* pair_region, double max_relative_error,
                      UnionMethod method, ExactRational* exact_sum) {
  UnionVolume out;
  const std::size_t n = polys.size();
  std::size_t pairs = 0;
  for (const auto& l : later) pairs += l.size();
  // The nerve has at least n + pairs terms; many more means deep cliques, whose term count
  // grows exponentially with their size. Deep intersections of large polytopes are costly even
  // when few: their work is held to twice that of the pairwise intersections.
  const std::size_t budget = method == UnionMethod::nerve           ? SIZE_MAX
                             : method == UnionMethod::decomposition ? 0
                                                                    : 2 * (n + pairs) + 256;
  double pair_work = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j : later[i]) pair_work += double(polys[i].vertices.size()) * double(polys[j].faces.size());
  const double work_budget = method == UnionMethod::nerve ? HUGE_VAL : 2 * pair_work + 1e5;
  if (budget > 0) {
    NerveWalk w{polys, later, pair_region, budget, work_budget, 0.0, {}};
    for (std::size_t i = 0; i < n && !w.abandoned; ++i) {
      if (polys[i].empty()) continue;
      w.add(polys[i], 1);
      if (!later[i].empty()) w.walk(polys[i], 1, later[i], i);
    }
    out.max_clique = w.max_clique;
    if (!w.abandoned) {
      out.method = UnionMethod::nerve;
      out.terms = w.terms.size();
      if (!exact_sum && interval_sum(w.terms, max_relative_error, out)) return out;
      if (exact_sum || method == UnionMethod::nerve) {
        exact_sum_of(w.terms, out, exact_sum);
        return out;
      }
    }
  }
  const std::vector<Term> terms = decomposition_terms(polys, later);
  out.method = UnionMethod::decomposition;
  out.terms = terms.size();
  if (exact_sum || !interval_sum(terms, max_relative_error, out)) exact_sum_of(terms, out, exact_sum);
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

const char* to_string(UnionMethod method) {
  switch (method) {
    case UnionMethod::automatic: break;
    case UnionMethod::nerve: return "nerve";
    case UnionMethod::decomposition: return "decomposition";
  }
  return "automatic";
}

UnionVolume union_volume(const std::vector<ExactPolytope>& polys, double max_relative_error, UnionMethod method) {
  return sum_union(polys, later_neighbours(polys), nullptr, max_relative_error, method, nullptr);
}

ExactRational exact_union_volume(const std::vector<ExactPolytope>& polys, const std::vector<Overlap>* overlaps,
                                 UnionMethod method) {
  ExactRational v(0);
  if (overlaps) {
    const KnownPairs k = known_pairs(polys.size(), *overlaps);
    sum_union(polys, k.later, &k.region, 0.0, method, &v);
  } else {
    sum_union(polys, later_neighbours(polys), nullptr, 0.0, method, &v);
  }
  return v;
}

UnionVolume union_volume(const std::vector<ExactPolytope>& polys, const std::vector<Overlap>& overlaps,
                         double max_relative_error, UnionMethod method) {
  // Only pairs with a common interior can start a non-empty term, and their intersections are
  // already known: the walk starts from them.
  const KnownPairs k = known_pairs(polys.size(), overlaps);
  return sum_union(polys, k.later, &k.region, max_relative_error, method, nullptr);
}

}  // namespace dcshell
