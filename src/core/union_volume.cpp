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
  bool exact;
  UnionVolume& out;
  CGAL::Interval_nt<true> sum_interval{0};  // protected: sets the rounding mode itself
  ExactRational sum_exact{0};

  // `cur` = intersection of the chosen set (size `depth`), `cands` = indices that overlap every
  // member and come after the last one.
  void walk(const ExactPolytope& cur, std::size_t depth, const std::vector<std::size_t>& cands) {
    for (std::size_t c = 0; c < cands.size(); ++c) {
      std::size_t k = cands[c];
      ExactPolytope next = intersect(cur, polys[k]);
      if (next.empty()) continue;
      add(next, depth + 1);
      std::vector<std::size_t> rest;
      for (std::size_t d = c + 1; d < cands.size(); ++d)
        if (std::binary_search(later[k].begin(), later[k].end(), cands[d])) rest.push_back(cands[d]);
      if (!rest.empty()) walk(next, depth + 1, rest);
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

}  // namespace

UnionVolume union_volume(const std::vector<ExactPolytope>& polys, double max_relative_error) {
  UnionVolume out;
  const std::size_t n = polys.size();
  std::vector<CGAL::Bbox_3> boxes(n);
  for (std::size_t i = 0; i < n; ++i) boxes[i] = bbox(polys[i]);
  std::vector<std::vector<std::size_t>> later(n);  // box-overlapping neighbours with larger index
  for (auto [i, j] : box_overlap_pairs(boxes))
    if (!polys[i].empty() && !polys[j].empty()) later[i].push_back(j);
  for (auto& l : later) std::sort(l.begin(), l.end());
  for (bool exact : {false, true}) {
    out.terms = out.max_clique = 0;
    NerveWalk w{polys, later, exact, out};
    for (std::size_t i = 0; i < n; ++i) {
      if (polys[i].empty()) continue;
      w.add(polys[i], 1);
      if (!later[i].empty()) w.walk(polys[i], 1, later[i]);
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
    }
  }
  return out;
}

}  // namespace dcshell
