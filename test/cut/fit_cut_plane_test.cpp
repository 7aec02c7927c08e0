#include <boost/test/unit_test.hpp>
#include <algorithm>
#include <cstring>

#include "cut/fixtures.h"
#include "dcshell/cut_plane_lsf.h"
#include "dcshell/cut_plane_svm.h"
#include "dcshell/error.h"
#include "dcshell/fit_cut_plane.h"
#include "dcshell/polytope_clip.h"

using namespace dcshell;
using namespace dcshell::test;

namespace {

CutProblem make_problem(ConvexPolytope a, ConvexPolytope b) {
  CutProblem pb;
  pb.overlap = intersect(a, b);
  pb.a = std::move(a);
  pb.b = std::move(b);
  return pb;
}

CutOptions with(CutMethod m) {
  CutOptions o;
  o.method = m;
  return o;
}

// Random overlapping pair of hulls (different sizes, 30-120 vertices).
CutProblem random_pair(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const Eigen::Vector3d off = 1.1 * random_unit(rng);
  return make_problem(random_hull(seed * 2 + 1, 30 + int(u01(rng) * 90), Eigen::Vector3d::Zero(), 1.0),
                      random_hull(seed * 2 + 2, 30 + int(u01(rng) * 90), off, 0.5 + u01(rng)));
}

bool same_bits(const CutPlane& x, const CutPlane& y) {
  return std::memcmp(x.normal.data(), y.normal.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(&x.offset, &y.offset, sizeof(double)) == 0;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(fit_cut_plane_suite)

BOOST_AUTO_TEST_CASE(parse_method_names) {
  BOOST_CHECK(parse_cut_method("lsf") == CutMethod::lsf);
  BOOST_CHECK(parse_cut_method("svm") == CutMethod::svm);
  BOOST_CHECK(parse_cut_method("exact") == CutMethod::exact);
  BOOST_CHECK(parse_cut_method("full") == CutMethod::full);
  BOOST_CHECK_THROW(parse_cut_method("Full"), InputError);
  BOOST_CHECK_THROW(parse_cut_method(""), InputError);
  for (CutMethod m : {CutMethod::lsf, CutMethod::svm, CutMethod::exact, CutMethod::full})
    BOOST_CHECK(parse_cut_method(to_string(m)) == m);
}

// Two unit cubes shifted by 1/2 along x: every plane inside the slab 1/2 <= x <= 1 (over the
// whole cube section) loses nothing, any other plane through the overlap loses volume.
BOOST_AUTO_TEST_CASE(shifted_cubes_lose_nothing) {
  const CutProblem pb = make_problem(unit_cube(), translated(unit_cube(), Eigen::Vector3d(0.5, 0, 0)));
  for (CutMethod m : {CutMethod::exact, CutMethod::full}) {
    const CutResult r = fit_cut_plane(pb, with(m));
    BOOST_TEST_CONTEXT(to_string(m)) {
      BOOST_CHECK_SMALL(r.lost_volume, 1e-9);
      BOOST_CHECK_GT(r.plane.normal.x(), 0.9);
      BOOST_CHECK_CLOSE(r.objective, 0.5, 1e-7);
      for (double y : {0.0, 1.0})
        for (double z : {0.0, 1.0}) {  // the plane stays inside the slab
          const Eigen::Vector3d& n = r.plane.normal;
          const double x = (r.plane.offset - n.y() * y - n.z() * z) / n.x();
          // A corner overshooting by e loses a sliver of volume ~e^3: lost < 1e-9 allows ~1e-3.
          BOOST_CHECK(x >= 0.5 - 2e-3 && x <= 1 + 2e-3);
        }
    }
  }
  // A tilted plane through the overlap does lose volume (the test above can fail).
  const CutResult tilted = evaluate_cut_plane(pb, {Eigen::Vector3d(1, 0.8, 0).normalized(), 0.7});
  BOOST_CHECK_GT(tilted.lost_volume, 1e-3);
}

// Cubes shifted along the diagonal: the curve ∂a ∩ ∂b is a skew hexagon symmetric about the
// plane x+y+z = 9/4, which is the least-squares plane.
BOOST_AUTO_TEST_CASE(lsf_symmetric_boxes) {
  const ConvexPolytope a = unit_cube(), b = translated(unit_cube(), Eigen::Vector3d(0.5, 0.5, 0.5));
  const CutPlane h = lsf_cut_plane(a, b);
  const Eigen::Vector3d expect = Eigen::Vector3d::Ones().normalized();
  BOOST_CHECK_SMALL((h.normal - expect).norm(), 1e-9);
  BOOST_CHECK_CLOSE(h.offset, 2.25 / std::sqrt(3.0), 1e-9);
  // Swapping the shells flips the plane (normal from a toward b).
  const CutPlane f = lsf_cut_plane(b, a);
  BOOST_CHECK_SMALL((f.normal + expect).norm(), 1e-9);
}

BOOST_AUTO_TEST_CASE(svm_separates_disjoint_boxes) {
  const ConvexPolytope a = unit_cube(), b = translated(unit_cube(), Eigen::Vector3d(2, 0, 0));
  const CutPlane h = svm_cut_plane(a, b, 10.0, 800, 5);
  BOOST_CHECK_GT(h.normal.x(), 0.99);
  BOOST_CHECK_CLOSE(h.offset / h.normal.x(), 1.5, 5.0);  // maximal margin: about halfway (samples)
  std::mt19937_64 rng(1);
  for (const auto& x : sample_polytope(a, 200, rng)) BOOST_CHECK_LT(h.eval(x), 0.0);
}

BOOST_AUTO_TEST_CASE(sampling_is_uniform) {
  std::mt19937_64 rng(77);
  const ConvexPolytope t = tetrahedron();
  const auto pts = sample_polytope(t, 20000, rng);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& x : pts) {
    BOOST_REQUIRE(x.minCoeff() >= 0 && x.sum() <= 1 + 1e-12);
    mean += x;
  }
  mean /= double(pts.size());
  BOOST_CHECK_SMALL((mean - Eigen::Vector3d::Constant(0.25)).norm(), 0.01);  // centroid
}

BOOST_AUTO_TEST_CASE(method_ordering_on_random_pairs) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const CutProblem pb = random_pair(seed);
    if (pb.overlap.empty()) continue;
    const CutResult lsf = fit_cut_plane(pb, with(CutMethod::lsf));
    const CutResult svm = fit_cut_plane(pb, with(CutMethod::svm));
    const CutResult exact = fit_cut_plane(pb, with(CutMethod::exact));
    const CutResult full = fit_cut_plane(pb, with(CutMethod::full));
    BOOST_TEST_CONTEXT("seed " << seed) {
      BOOST_CHECK_LE(exact.objective, svm.objective);  // same normal, optimal offset
      BOOST_CHECK_LE(full.objective, exact.objective);
      BOOST_CHECK_LE(full.objective, lsf.objective * (1 + 1e-12));
      BOOST_CHECK_GE(full.lost_volume, 0.0);
      // exact's offset is the best along its normal (1D grid over the overlap's range).
      const auto [lo, hi] = height_range(pb.overlap, exact.plane.normal);
      for (int i = 0; i <= 200; ++i) {
        const CutResult g = evaluate_cut_plane(pb, {exact.plane.normal, lo + (hi - lo) * i / 200.0});
        BOOST_CHECK_GE(g.objective, exact.objective - 1e-12 * exact.objective);
      }
      const auto [flo, fhi] = height_range(pb.overlap, full.plane.normal);
      BOOST_CHECK(full.plane.offset >= flo && full.plane.offset <= fhi);
      // Lost volume agrees with clipping.
      const double clipped = volume(clip(pb.a, full.plane.flipped(), 1)) + volume(clip(pb.b, full.plane, 1)) -
                             volume(intersect(pb.a, pb.b));
      BOOST_CHECK_SMALL(full.lost_volume - clipped, 1e-9 * volume(pb.a));
    }
  }
}

// full is close to a dense search (many more directions and starts).
BOOST_AUTO_TEST_CASE(full_close_to_dense_search) {
  for (std::uint64_t seed = 20; seed < 26; ++seed) {
    const CutProblem pb = random_pair(seed);
    if (pb.overlap.empty()) continue;
    CutOptions dense = with(CutMethod::full);
    dense.full_directions = 2000;
    dense.full_starts = 12;
    const CutResult f = fit_cut_plane(pb, with(CutMethod::full)), d = fit_cut_plane(pb, dense);
    BOOST_TEST_CONTEXT("seed " << seed) {
      BOOST_CHECK_LE(f.lost_volume, d.lost_volume * 1.02 + 1e-6 * volume(pb.a));
    }
  }
}

BOOST_AUTO_TEST_CASE(interference_moves_the_offset) {
  // Without interference every offset in [1/2, 1] is optimal; a region of a near x = 1/2 that
  // must not be lost pushes the plane to the far end of the overlap.
  CutProblem pb = make_problem(unit_cube(), translated(unit_cube(), Eigen::Vector3d(0.5, 0, 0)));
  pb.interference_a.push_back(box(Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d(0.9, 1, 1)));
  CutOptions o = with(CutMethod::full);
  o.lambda = 0.01;
  const CutResult r = fit_cut_plane(pb, o);
  BOOST_CHECK_GT(r.plane.normal.x(), 0.999);
  BOOST_CHECK_GE(r.plane.offset / r.plane.normal.x(), 0.9 - 1e-3);
  BOOST_CHECK_CLOSE(r.objective, 0.5, 1e-4);
  // exact keeps the SVM normal but still moves its offset toward x = 0.9.
  o.method = CutMethod::exact;
  const CutResult e = fit_cut_plane(pb, o);
  BOOST_CHECK_GE(e.plane.offset / e.plane.normal.x(), 0.8);
  // The penalty is lambda * the region's volume on the wrong side.
  const CutResult at_half = evaluate_cut_plane(pb, {Eigen::Vector3d::UnitX(), 0.5}, 0.01);
  BOOST_CHECK_CLOSE(at_half.objective, 0.5 + 0.01 * 0.4, 1e-9);
}

BOOST_AUTO_TEST_CASE(interference_on_either_side_counts_whole_or_not_at_all) {
  // Interference regions beside the overlap, wholly on one side of every plane through it, add
  // all of their volume or none (the objective gives them no slice profile); one across the
  // overlap counts in part. Against the clipped volumes summed by brute force, for planes tilted
  // every way, with the offset anywhere in the overlap's range.
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    CutProblem pb = random_pair(seed);
    std::mt19937_64 rng(seed);
    const Eigen::Vector3d centre = pb.overlap.vertices.front();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d far = 3.0 * random_unit(rng);
      pb.interference_a.push_back(random_hull(seed * 10 + k, 20, far, 0.4));
      pb.interference_b.push_back(random_hull(seed * 20 + k, 20, -far, 0.4));
    }
    pb.interference_a.push_back(random_hull(seed * 30, 20, centre, 0.3));
    pb.interference_b.push_back(random_hull(seed * 40, 20, centre, 0.3));
    const double lambda = 0.1;
    for (int t = 0; t < 6; ++t) {
      const Eigen::Vector3d n = random_unit(rng);
      double lo = 1e300, hi = -1e300;
      for (const auto& v : pb.overlap.vertices) lo = std::min(lo, n.dot(v)), hi = std::max(hi, n.dot(v));
      const CutPlane plane{n, lo + u01(rng) * (hi - lo)};
      const CutResult r = evaluate_cut_plane(pb, plane, lambda);
      const CutPlane below = r.plane, above = r.plane.flipped();  // clip keeps normal.x <= offset
      double brute = volume(clip(pb.a, above, -1)) + volume(clip(pb.b, below, -1));
      for (const auto& x : pb.interference_a) brute += lambda * volume(clip(x, above, -1));
      for (const auto& y : pb.interference_b) brute += lambda * volume(clip(y, below, -1));
      BOOST_CHECK_CLOSE(r.objective, brute, 1e-8);
    }
    // The fit's reported objective is the objective at its plane.
    CutOptions o = with(CutMethod::full);
    o.lambda = lambda;
    const CutResult f = fit_cut_plane(pb, o);
    BOOST_CHECK_CLOSE(f.objective, evaluate_cut_plane(pb, f.plane, lambda).objective, 1e-12);
  }
}

BOOST_AUTO_TEST_CASE(deterministic) {
  const CutProblem pb = random_pair(3);
  for (CutMethod m : {CutMethod::svm, CutMethod::exact, CutMethod::full}) {
    const CutResult x = fit_cut_plane(pb, with(m)), y = fit_cut_plane(pb, with(m));
    BOOST_CHECK(same_bits(x.plane, y.plane));
  }
  // Relabelling vertices and reordering faces (as another hull code might) changes nothing.
  CutProblem shuffled = pb;
  for (ConvexPolytope* p : {&shuffled.a, &shuffled.b}) {
    const int n = int(p->vertices.size());
    std::reverse(p->vertices.begin(), p->vertices.end());
    for (auto& f : p->faces) {
      for (int& v : f) v = n - 1 - v;
      std::rotate(f.begin(), f.begin() + 1, f.end());
    }
    std::reverse(p->faces.begin(), p->faces.end());
  }
  BOOST_CHECK(same_bits(fit_cut_plane(pb, with(CutMethod::svm)).plane, fit_cut_plane(shuffled, with(CutMethod::svm)).plane));
  CutOptions other = with(CutMethod::svm);
  other.seed = 2;
  BOOST_CHECK(!same_bits(fit_cut_plane(pb, with(CutMethod::svm)).plane, fit_cut_plane(pb, other).plane));
}

// The shared a ∩ b is only a cache: handing it in, or leaving it to fit/evaluate, gives the
// same bits, and it is the tagged intersection (LSF finds the curve through its tags).
BOOST_AUTO_TEST_CASE(given_current_overlap_changes_nothing) {
  for (std::uint64_t seed : {4u, 5u}) {
    const CutProblem pb = random_pair(seed);
    CutProblem given = pb;
    given.current_overlap = tagged_intersection(pb.a, pb.b);
    const ConvexPolytope& ab = *given.current_overlap;
    BOOST_TEST_REQUIRE(!ab.empty());
    BOOST_TEST(std::count(ab.face_tags.begin(), ab.face_tags.end(), 0) > 0);
    BOOST_TEST(std::count(ab.face_tags.begin(), ab.face_tags.end(), 1) > 0);
    BOOST_TEST(std::count_if(ab.face_tags.begin(), ab.face_tags.end(), [](int t) { return t != 0 && t != 1; }) == 0);
    BOOST_CHECK(same_bits(lsf_cut_plane(pb.a, pb.b), lsf_cut_plane(pb.a, pb.b, ab)));
    for (CutMethod m : {CutMethod::lsf, CutMethod::svm, CutMethod::exact, CutMethod::full}) {
      const CutResult x = fit_cut_plane(pb, with(m)), y = fit_cut_plane(given, with(m));
      BOOST_CHECK(same_bits(x.plane, y.plane));
      BOOST_TEST(x.lost_volume == y.lost_volume);
      BOOST_TEST(evaluate_cut_plane(pb, x.plane).objective == evaluate_cut_plane(given, x.plane).objective);
    }
  }
}

BOOST_AUTO_TEST_CASE(degenerate_problems_do_not_fail) {
  // Nested: b inside a.
  const CutProblem nested = make_problem(unit_cube(), box(Eigen::Vector3d::Constant(0.25), Eigen::Vector3d::Constant(0.5)));
  // Touching faces only.
  const CutProblem touching = make_problem(unit_cube(), translated(unit_cube(), Eigen::Vector3d(1, 0, 0)));
  for (const CutProblem* pb : {&nested, &touching})
    for (CutMethod m : {CutMethod::lsf, CutMethod::svm, CutMethod::exact, CutMethod::full}) {
      const CutResult r = fit_cut_plane(*pb, with(m));
      BOOST_CHECK(std::isfinite(r.plane.offset) && std::fabs(r.plane.normal.norm() - 1) < 1e-12);
      BOOST_CHECK(std::isfinite(r.lost_volume));
    }
  const CutResult t = fit_cut_plane(touching, with(CutMethod::full));
  BOOST_CHECK_SMALL(t.lost_volume, 1e-9);
}

BOOST_AUTO_TEST_SUITE_END()
