// Exact union volume: inclusion–exclusion over the nerve of the polytopes while the overlaps
// are shallow, a disjoint convex decomposition of the union when they are deep.
#include "dcshell/union_volume.h"

#include "dcshell/overlaps.h"

#include <CGAL/Mpzf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace dcshell {

namespace {

// A term of the sum: a convex polytope whose volume is added (plus) or subtracted.
struct Term {
  ExactPolytope polytope;
  bool plus = true;
};

// The polytopes by decreasing volume (stable: ties by index). Both methods give polytope i the
// share vol(P_i minus the larger polytopes it overlaps): the decomposition cuts the larger ones
// out of it, and the nerve walk, which visits the polytopes smallest first, collects the
// subsets whose first member is i, whose signed sum is that share. So the walk can hand over to
// the decomposition at any polytope without losing what it summed before.
struct VolumeOrder {
  std::vector<std::size_t> order, rank;  // order[rank[i]] = i
  // Per polytope, the overlapping neighbours larger than it, in walk order (decreasing rank).
  std::vector<std::vector<std::size_t>> larger;
};

VolumeOrder volume_order(const std::vector<ExactPolytope>& polys, const std::vector<std::vector<std::size_t>>& later) {
  const std::size_t n = polys.size();
  VolumeOrder v{std::vector<std::size_t>(n), std::vector<std::size_t>(n), std::vector<std::vector<std::size_t>>(n)};
  std::vector<double> vol(n);
  for (std::size_t i = 0; i < n; ++i) vol[i] = approximate_volume(polys[i]);
  std::iota(v.order.begin(), v.order.end(), std::size_t(0));
  std::stable_sort(v.order.begin(), v.order.end(), [&](std::size_t a, std::size_t b) { return vol[a] > vol[b]; });
  for (std::size_t r = 0; r < n; ++r) v.rank[v.order[r]] = r;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j : later[i]) {
      const auto [small, big] = v.rank[i] > v.rank[j] ? std::pair(i, j) : std::pair(j, i);
      v.larger[small].push_back(big);
    }
  for (auto& l : v.larger) std::sort(l.begin(), l.end(), [&](std::size_t a, std::size_t b) { return v.rank[a] > v.rank[b]; });
  return v;
}

// Depth-first walk over the subsets with a common interior, collecting their intersections
// with the inclusion–exclusion sign, polytope by polytope in walk order. Stops (`abandoned`)
// once it holds `budget` terms or its deep intersections pass `work_budget`: deep overlaps make
// the nerve exponential, and the decomposition below then takes the polytopes not finished.
struct NerveWalk {
  const std::vector<ExactPolytope>& polys;
  const VolumeOrder& vo;
  // Known pairwise intersections (null: compute them), found through `later`, the overlapping
  // neighbours with larger index, to which they are parallel.
  const std::vector<std::vector<std::size_t>>& later;
  const std::vector<std::vector<const ExactPolytope*>>* pair_region;
  std::size_t budget;       // most terms held
  double work_budget;       // most vertex-plane tests spent on intersections of three or more
  double work = 0;
  std::vector<Term> terms;
  std::size_t max_clique = 0;
  bool abandoned = false;

  // `cur` = intersection of the chosen set (size `depth`), `cands` = polytopes that overlap
  // every member and come after the last one in walk order (in that order).
  void walk(const ExactPolytope& cur, std::size_t depth, const std::vector<std::size_t>& cands, std::size_t first) {
    const auto after = [&](std::size_t a, std::size_t b) { return vo.rank[a] > vo.rank[b]; };
    for (std::size_t c = 0; c < cands.size() && !abandoned; ++c) {
      std::size_t k = cands[c];
      ExactPolytope next;
      if (depth == 1 && pair_region) {
        const std::size_t a = std::min(first, k), b = std::max(first, k);
        const auto& l = later[a];
        next = *(*pair_region)[a][std::size_t(std::lower_bound(l.begin(), l.end(), b) - l.begin())];
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
        if (std::binary_search(vo.larger[k].begin(), vo.larger[k].end(), cands[d], after)) rest.push_back(cands[d]);
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
  // Polytope i's share; false (and nothing of it kept) when the walk ran out of budget in it.
  bool share(std::size_t i) {
    const std::size_t mark = terms.size();
    add(polys[i], 1);
    if (!abandoned && !vo.larger[i].empty()) walk(polys[i], 1, vo.larger[i], i);
    if (abandoned) terms.erase(terms.begin() + std::ptrdiff_t(mark), terms.end());
    return !abandoned;
  }
};

// Terms whose signed sum is the share of every polytope `todo` marks, without the nerve: the
// polytope minus the larger ones it overlaps (a part nested in a larger one then leaves
// nothing). Q \ C is split along the faces of Q ∩ C that come from C, so every piece is a
// convex polytope whose vertices meet three input planes — except against the last polytope a
// piece meets (no later one's box reaches it): there Q \ C counts as +Q − (Q ∩ C), one
// subtraction instead of a split into as many pieces as Q ∩ C has faces from C (a round hull
// has a hundred). The sum stays one level deep, not an alternating sum over cliques.
std::vector<Term> decomposition_terms(const std::vector<ExactPolytope>& polys, const VolumeOrder& vo,
                                      const std::vector<char>& todo) {
  constexpr int kOwn = 0, kCutter = 1;
  auto retag = [](ExactPolytope p, int tag) {
    for (auto& f : p.faces) f.tag = tag;
    return p;
  };
  std::vector<Term> terms;
  for (std::size_t i : vo.order) {
    if (!todo[i] || polys[i].empty()) continue;
    // Largest first.
    const std::vector<std::size_t> before(vo.larger[i].rbegin(), vo.larger[i].rend());
    std::vector<CGAL::Bbox_3> boxes;
    for (std::size_t j : before) boxes.push_back(bbox(polys[j]));
    std::vector<ExactPolytope> mine{retag(polys[i], kOwn)};
    for (std::size_t c = 0; c < before.size(); ++c) {
      const ExactPolytope cutter = retag(polys[before[c]], kCutter);
      std::vector<ExactPolytope> next;
      for (auto& q : mine) {
        const CGAL::Bbox_3 qbox = bbox(q);
        ExactPolytope r = CGAL::do_overlap(qbox, boxes[c]) ? intersect(q, cutter) : ExactPolytope{};
        if (r.empty()) {
          next.push_back(std::move(q));
          continue;
        }
        // No face of C bounds Q ∩ C: Q lies inside C and leaves nothing.
        if (std::none_of(r.faces.begin(), r.faces.end(), [](const auto& f) { return f.tag == kCutter; })) continue;
        const bool last = std::none_of(boxes.begin() + std::ptrdiff_t(c) + 1, boxes.end(),
                                       [&](const CGAL::Bbox_3& b) { return CGAL::do_overlap(qbox, b); });
        if (last) {
          terms.push_back({std::move(r), false});
          terms.push_back({std::move(q), true});
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
    for (auto& q : mine) terms.push_back({std::move(q), true});
  }
  return terms;
}

// Σ ±vol(term) in intervals, from the coordinates' current approximations, then after
// evaluating every vertex exactly (each coordinate then within an ulp). False when neither is
// enough.
bool interval_sum(const std::vector<Term>& terms, const UnionEnough& enough, UnionVolume& out, ExactRational* value) {
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
    // Half the width, and the rounding of the midpoint and of that half.
    out.error_bound = 0.5 * (h - l) * (1 + 0x1p-50) + std::fabs(out.value) * 0x1p-52;
    const ExactRational centre(out.value);
    if (enough(centre, out.error_bound)) {
      if (value) *value = centre;
      return true;
    }
  }
  return false;
}

// Σ ±vol(term) on the grid 2^-k, k about 120 bits below the largest coordinate: every vertex
// (evaluated exactly) truncated to the grid, the fan determinants summed exactly in integers.
// Truncation moves a difference of two vertices by delta < 2·sqrt(3)·2^-k, which changes a
// determinant of three such differences of length <= D by at most 3 delta (D + delta)^2; that,
// over every triangle, bounds the error. About 30 digits without one rational operation (the
// rational sum's denominators grow with every term: minutes on 100 overlapping fine hulls).
bool fixed_point_sum(const std::vector<Term>& terms, const UnionEnough& enough, UnionVolume& out,
                     ExactRational* value) {
  double largest = 0;
  for (const auto& t : terms)
    for (const auto& v : t.polytope.vertices) {
      const auto a = CGAL::approx(v);
      for (const auto& c : {a.x(), a.y(), a.z()}) largest = std::max({largest, std::fabs(c.inf()), std::fabs(c.sup())});
    }
  if (!(largest > 0) || !std::isfinite(largest)) return false;
  const int k = 120 - std::ilogb(largest);
  const double delta = 2 * std::sqrt(3.0) * std::ldexp(1.0, -k) * (1 + 0x1p-40);
  auto grid = [k](const ExactRational& x) {  // x·2^k truncated: |x − result·2^-k| < 2^-k
    mpz_class n = x.get_num(), d = x.get_den();
    if (k >= 0) n <<= k; else d <<= -k;
    return mpz_class(n / d);
  };
  mpz_class total = 0;
  double error = 0;  // on 6 x the volume
  std::vector<std::array<mpz_class, 3>> q;
  for (const auto& t : terms) {
    const ExactPolytope& p = t.polytope;
    if (p.empty()) continue;
    q.resize(p.vertices.size());
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (std::size_t i = 0; i < p.vertices.size(); ++i) {
      const auto& e = CGAL::exact(p.vertices[i]);
      q[i] = {{grid(e.x()), grid(e.y()), grid(e.z())}};
      const auto a = CGAL::approx(p.vertices[i]);
      const CGAL::Interval_nt<false> c[3] = {a.x(), a.y(), a.z()};
      for (int j = 0; j < 3; ++j) lo[j] = std::min(lo[j], c[j].inf()), hi[j] = std::max(hi[j], c[j].sup());
    }
    // D bounds every difference of two vertices (the box's diagonal, rounded up).
    const double D = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                               (hi[2] - lo[2]) * (hi[2] - lo[2])) * (1 + 0x1p-40);
    const auto& o = q[p.faces.front().loop.front()];
    mpz_class six = 0;
    std::size_t triangles = 0;
    for (const auto& f : p.faces) {
      const auto& L = f.loop;
      for (std::size_t m = 1; m + 1 < L.size(); ++m, ++triangles) {
        const auto &A = q[L[0]], &B = q[L[m]], &C = q[L[m + 1]];
        const mpz_class ax = A[0] - o[0], ay = A[1] - o[1], az = A[2] - o[2];
        const mpz_class bx = B[0] - o[0], by = B[1] - o[1], bz = B[2] - o[2];
        const mpz_class cx = C[0] - o[0], cy = C[1] - o[1], cz = C[2] - o[2];
        six += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
      }
    }
    if (t.plus) total += six; else total -= six;
    error += double(triangles) * 3 * delta * (D + delta) * (D + delta);
  }
  // total·2^-3k is six times the sum on the grid.
  ExactRational centre = k >= 0 ? ExactRational(total, mpz_class(6) << (3 * k))
                                : ExactRational(mpz_class(total << (-3 * k)), 6);
  centre.canonicalize();
  out.value = CGAL::to_double(centre);
  out.error_bound = error / 6 * (1 + 1e-6);  // the rounding of summing millions of terms
  out.fixed_point = true;
  if (!enough(centre, out.error_bound)) return false;
  if (value) *value = centre;
  return true;
}

// Σ ±vol(term) in exact rationals, whose denominators grow with every term: the expensive way.
void exact_sum_of(const std::vector<Term>& terms, UnionVolume& out, ExactRational* value) {
  ExactRational total(0);
  for (const auto& t : terms) {
    if (t.plus) total += exact_volume(t.polytope); else total -= exact_volume(t.polytope);
  }
  out.value = CGAL::to_double(total);
  out.error_bound = std::fabs(out.value) * 1e-16;  // rounding of the exact rational
  out.exact_fallback = true;
  out.fixed_point = false;
  if (value) *value = total;
}

// The levels of union_volume(..., enough, ...) on one set of terms; `exact_only` skips to the last.
void sum_terms(const std::vector<Term>& terms, const UnionEnough& enough, bool exact_only, UnionVolume& out,
               ExactRational* value) {
  if (!exact_only && (interval_sum(terms, enough, out, value) || fixed_point_sum(terms, enough, out, value))) return;
  exact_sum_of(terms, out, value);
}

// Nerve walk while it stays within budget (shallow overlaps: fewest exact constructions), the
// decomposition for the polytopes it did not finish; then the sum, refined until `enough`
// (sum_terms).
UnionVolume sum_union(const std::vector<ExactPolytope>& polys, const std::vector<std::vector<std::size_t>>& later,
                      const std::vector<std::vector<const ExactPolytope*>>* pair_region, const UnionEnough& enough,
                      UnionMethod method, bool exact_only, ExactRational* value) {
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
  const VolumeOrder vo = volume_order(polys, later);
  NerveWalk w{polys, vo, later, pair_region, budget, work_budget, 0.0, {}};
  // Smallest first; from the first polytope the walk cannot finish, the decomposition.
  std::vector<char> todo(n, 0);
  for (std::size_t r = n; r-- > 0;) {
    const std::size_t i = vo.order[r];
    if (polys[i].empty()) continue;
    if (budget == 0 || w.abandoned || !w.share(i)) todo[i] = 1; else ++out.nerve_polytopes;
  }
  out.max_clique = w.max_clique;
  std::vector<Term> terms = std::move(w.terms);
  const bool handed_over = budget == 0 || w.abandoned;
  if (handed_over) {
    std::vector<Term> rest = decomposition_terms(polys, vo, todo);
    terms.insert(terms.end(), std::make_move_iterator(rest.begin()), std::make_move_iterator(rest.end()));
  }
  out.method = handed_over ? UnionMethod::decomposition : UnionMethod::nerve;
  out.terms = terms.size();
  sum_terms(terms, enough, exact_only, out, value);
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

// Enough when the enclosure's width is at most `max_relative_error` of the value.
UnionEnough relative_error(double max_relative_error) {
  return [max_relative_error](const ExactRational& v, double error_bound) {
    return 2 * error_bound <= max_relative_error * std::fabs(CGAL::to_double(v));
  };
}

// The walk from the pairs with a common interior (`overlaps`, whose intersections it reuses),
// or from the box-overlapping ones.
UnionVolume sum_union(const std::vector<ExactPolytope>& polys, const std::vector<Overlap>* overlaps,
                      const UnionEnough& enough, UnionMethod method, bool exact_only, ExactRational* value) {
  if (!overlaps) return sum_union(polys, later_neighbours(polys), nullptr, enough, method, exact_only, value);
  const KnownPairs k = known_pairs(polys.size(), *overlaps);
  return sum_union(polys, k.later, &k.region, enough, method, exact_only, value);
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

UnionVolume union_volume(const std::vector<ExactPolytope>& polys, const std::vector<Overlap>* overlaps,
                         const UnionEnough& enough, UnionMethod method, ExactRational* value) {
  return sum_union(polys, overlaps, enough, method, false, value);
}

UnionVolume union_volume(const std::vector<ExactPolytope>& polys, double max_relative_error, UnionMethod method) {
  return union_volume(polys, nullptr, relative_error(max_relative_error), method);
}

UnionVolume union_volume(const std::vector<ExactPolytope>& polys, const std::vector<Overlap>& overlaps,
                         double max_relative_error, UnionMethod method) {
  return union_volume(polys, &overlaps, relative_error(max_relative_error), method);
}

ExactRational exact_union_volume(const std::vector<ExactPolytope>& polys, const std::vector<Overlap>* overlaps,
                                 UnionMethod method) {
  ExactRational v(0);
  sum_union(polys, overlaps, [](const ExactRational&, double) { return false; }, method, true, &v);
  return v;
}

}  // namespace dcshell
