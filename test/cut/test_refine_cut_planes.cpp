// The cut-plane stage of a composite on its own: pairwise fits, then refinement sweeps.
#include <boost/test/unit_test.hpp>

#include "dcshell/convex_hull.h"
#include "dcshell/polytope_clip.h"
#include "dcshell/refine_cut_planes.h"
#include "synthetic_parts.h"

using namespace dcshell;

namespace {

struct Composite {
  std::vector<ConvexPolytope> hulls;
  std::vector<HullPair> pairs;
};

Composite composite(const std::vector<Part>& parts) {
  Composite c;
  for (const auto& p : parts) c.hulls.push_back(polytope_from_mesh(convex_hull_mesh(p.points)));
  for (std::size_t i = 0; i < c.hulls.size(); ++i)
    for (std::size_t j = i + 1; j < c.hulls.size(); ++j) {
      ConvexPolytope r = intersect(c.hulls[i], c.hulls[j]);
      if (volume(r) > 0) c.pairs.push_back({i, j, std::move(r)});
    }
  return c;
}

// What the hulls keep, each clipped by all its planes (part i of a pair keeps the negative side).
double kept_volume(const Composite& c, const std::vector<CutPlane>& planes) {
  double v = 0;
  for (std::size_t k = 0; k < c.hulls.size(); ++k) {
    ConvexPolytope h = c.hulls[k];
    for (std::size_t p = 0; p < c.pairs.size() && !h.empty(); ++p)
      if (c.pairs[p].i == k) h = clip(h, planes[p], -1);
      else if (c.pairs[p].j == k) h = clip(h, planes[p].flipped(), -1);
    v += volume(h);
  }
  return v;
}

// Every plane passes through its pair's region: trimming opens no gap between the two parts.
void check_planes_cross_regions(const Composite& c, const std::vector<CutPlane>& planes) {
  BOOST_REQUIRE(planes.size() == c.pairs.size());
  for (std::size_t p = 0; p < planes.size(); ++p) {
    const auto [lo, hi] = height_range(c.pairs[p].region, planes[p].normal);
    const double slack = 1e-9 * (1 + std::abs(lo) + std::abs(hi));
    BOOST_TEST(planes[p].offset >= lo - slack, "pair " << p);
    BOOST_TEST(planes[p].offset <= hi + slack, "pair " << p);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(refine_cut_planes_suite)

BOOST_AUTO_TEST_CASE(sweeps_recover_what_pairwise_planes_over_trim) {
  // Eight planks through one axis: every pair overlaps in the same central region, so pairwise
  // planes each cut a plank in half, on sides that disagree.
  const Composite c = composite(synthetic::plank_star(8, 0.01));
  BOOST_REQUIRE(c.pairs.size() == 28u);
  CutOptions cut;
  const std::vector<CutPlane> pairwise = fit_pair_planes(c.hulls, c.pairs, cut);
  check_planes_cross_regions(c, pairwise);
  SweepReport report;
  const std::vector<CutPlane> refined = refine_cut_planes(c.hulls, c.pairs, pairwise, cut, SweepOptions{}, &report);
  check_planes_cross_regions(c, refined);
  double total = 0;
  for (const auto& h : c.hulls) total += volume(h);
  const double before = kept_volume(c, pairwise), after = kept_volume(c, refined);
  BOOST_TEST_MESSAGE("kept " << before / total << " -> " << after / total << ", start " << to_string(report.start));
  BOOST_TEST(after > 1.5 * before);
  BOOST_TEST(report.sweeps >= 1);
  BOOST_TEST(report.gains.size() == std::size_t(report.sweeps));
  BOOST_TEST((report.start == SweepStart::constructive));
  BOOST_TEST(report.refits > 0u);

  // One start only: still never worse than the pairwise planes, and not better than three.
  SweepOptions one;
  one.second_start = false;
  SweepReport one_report;
  const std::vector<CutPlane> polished = refine_cut_planes(c.hulls, c.pairs, pairwise, cut, one, &one_report);
  BOOST_TEST((one_report.start == SweepStart::pairwise));
  BOOST_TEST(one_report.refits == 0u);
  BOOST_TEST(kept_volume(c, polished) >= before);
  BOOST_TEST(kept_volume(c, polished) <= after);
}

BOOST_AUTO_TEST_CASE(single_pass_methods_and_idle_hulls_change_nothing) {
  std::mt19937_64 rng(7);
  Composite c = composite(synthetic::random_boxes(rng, 6, 1.0, 0.3, 0.6));
  BOOST_REQUIRE(!c.pairs.empty());
  CutOptions lsf;
  lsf.method = CutMethod::lsf;
  const std::vector<CutPlane> planes = fit_pair_planes(c.hulls, c.pairs, lsf);
  SweepReport report;
  report.sweeps = 99;
  const std::vector<CutPlane> same = refine_cut_planes(c.hulls, c.pairs, planes, lsf, SweepOptions{}, &report);
  BOOST_TEST(report.sweeps == 0);
  for (std::size_t p = 0; p < planes.size(); ++p) {
    BOOST_TEST((same[p].normal == planes[p].normal));
    BOOST_TEST(same[p].offset == planes[p].offset);
  }

  // A hull in no pair (an absorbed part, passed empty) changes neither the fits nor the sweeps.
  CutOptions full;
  const std::vector<CutPlane> a = refine_cut_planes(c.hulls, c.pairs, fit_pair_planes(c.hulls, c.pairs, full), full, {});
  c.hulls.emplace_back();
  const std::vector<CutPlane> b = refine_cut_planes(c.hulls, c.pairs, fit_pair_planes(c.hulls, c.pairs, full), full, {});
  BOOST_REQUIRE(a.size() == b.size());
  for (std::size_t p = 0; p < a.size(); ++p) {
    BOOST_TEST((a[p].normal == b[p].normal));
    BOOST_TEST(a[p].offset == b[p].offset);
  }
}

BOOST_AUTO_TEST_SUITE_END()
