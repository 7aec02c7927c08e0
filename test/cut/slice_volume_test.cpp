#include <boost/test/unit_test.hpp>
#include <string>

#include "cut/fixtures.h"
#include "dcshell/polytope_clip.h"
#include "dcshell/slice_volume.h"

using namespace dcshell;
using namespace dcshell::test;

namespace {

struct Named {
  std::string name;
  ConvexPolytope p;
};

std::vector<Named> shapes() {
  return {{"cube", unit_cube()},
          {"tetrahedron", tetrahedron()},
          {"pyramid12", pyramid(12)},
          {"lattice_ball", lattice_ball(4)},
          {"far_box", box(Eigen::Vector3d(1e3, -2e3, 5e2), Eigen::Vector3d(1e3 + 0.1, -2e3 + 0.3, 5e2 + 0.2))},
          {"random_hull", random_hull(7, 80, Eigen::Vector3d(0.5, 0.2, -0.3), 2.0)}};
}

// Directions including degenerate ones: orthogonal to edges and faces, through several vertices.
std::vector<Eigen::Vector3d> directions() {
  std::vector<Eigen::Vector3d> d{Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitZ(),
                                 Eigen::Vector3d(1, 1, 0).normalized(), Eigen::Vector3d(1, -1, 1).normalized(),
                                 Eigen::Vector3d(1, 2, 0).normalized(), Eigen::Vector3d(1, 1e-9, 0).normalized()};
  std::mt19937_64 rng(42);
  for (int i = 0; i < 6; ++i) d.push_back(random_unit(rng));
  return d;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(slice_volume)

BOOST_AUTO_TEST_CASE(matches_brute_force_clipping) {
  for (const auto& s : shapes()) {
    const double total = volume(s.p);
    for (const auto& c : directions()) {
      const SliceProfile prof(s.p, c);
      BOOST_TEST_CONTEXT(s.name << " c=" << c.transpose()) {
        BOOST_CHECK_SMALL(prof.volume() - total, 1e-10 * total);
        const double lo = prof.min_height(), hi = prof.max_height(), span = hi - lo;
        std::vector<double> ds;
        for (int i = 0; i <= 60; ++i) ds.push_back(lo - 0.05 * span + 1.1 * span * i / 60.0);
        for (const auto& v : s.p.vertices) ds.push_back(c.dot(v));  // exactly at events
        for (double d : ds) {
          const double above = volume(clip(s.p, {-c, -d}, 1)), below = volume(clip(s.p, {c, d}, 1));
          BOOST_CHECK_SMALL(prof.volume_above(d) - above, 1e-9 * total);
          BOOST_CHECK_SMALL(prof.volume_below(d) - below, 1e-9 * total);
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(area_is_the_derivative) {
  for (const auto& s : shapes()) {
    for (const auto& c : directions()) {
      const SliceProfile prof(s.p, c);
      const double lo = prof.min_height(), hi = prof.max_height(), span = hi - lo;
      const double scale = volume(s.p) / span;  // typical section area
      for (int i = 1; i < 40; ++i) {
        const double d = lo + span * (i + 0.37) / 41.0, h = 1e-6 * span;
        const double fd = (prof.volume_above(d - h) - prof.volume_above(d + h)) / (2 * h);
        BOOST_TEST_CONTEXT(s.name << " c=" << c.transpose() << " d=" << d) {
          BOOST_CHECK_SMALL(prof.area(d) - fd, 1e-5 * scale);
          BOOST_CHECK_SMALL(prof.area(d) - section(s.p, {c, d}).area, 1e-9 * scale);
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(offset_minimum_is_global_on_a_grid) {
  std::mt19937_64 rng(9);
  for (int trial = 0; trial < 30; ++trial) {
    const ConvexPolytope a = random_hull(200 + trial, 40, Eigen::Vector3d::Zero(), 1.0);
    const ConvexPolytope b = random_hull(300 + trial, 40, Eigen::Vector3d(1.0, 0.3 * u01(rng), 0), 0.8);
    const ConvexPolytope x = trial % 2 ? lattice_ball(2) : ConvexPolytope{};
    const Eigen::Vector3d c = random_unit(rng);
    const SliceProfile pa(a, c), pb(b, c), px(x, c);
    std::vector<SliceTerm> terms{{&pa, 1.0, true}, {&pb, 1.0, false}, {&px, 0.3, true}};
    const double lo = std::min(pa.min_height(), pb.min_height()), hi = std::max(pa.max_height(), pb.max_height());
    const double l = lo + 0.2 * (hi - lo), h = hi - 0.3 * (hi - lo);
    const OffsetMinimum m = minimize_offset(terms, l, h);
    BOOST_CHECK(m.offset >= l && m.offset <= h);
    // The sweep finds each term's piece from the last one: the same pieces, the same bits.
    BOOST_CHECK_EQUAL(m.value, slice_objective(terms, m.offset));
    double grid_min = 1e300;
    for (int i = 0; i <= 4000; ++i) grid_min = std::min(grid_min, slice_objective(terms, l + (h - l) * i / 4000.0));
    BOOST_CHECK_LE(m.value, grid_min + 1e-12 * std::fabs(grid_min));
    // At an interior minimum the weighted section areas balance.
    if (m.offset > l && m.offset < h)
      BOOST_CHECK_SMALL(slice_objective_derivative(terms, m.offset), 1e-7 * pa.volume() / (hi - lo));
  }
}

BOOST_AUTO_TEST_CASE(empty_and_flat_polytopes) {
  const SliceProfile e(ConvexPolytope{}, Eigen::Vector3d::UnitZ());
  BOOST_CHECK_EQUAL(e.volume(), 0.0);
  BOOST_CHECK_EQUAL(e.volume_above(0.0), 0.0);
  BOOST_CHECK_EQUAL(e.area(0.0), 0.0);
  const SliceProfile c(unit_cube(), Eigen::Vector3d::UnitZ());
  std::vector<SliceTerm> terms{{&e, 1.0, true}, {&c, 1.0, false}};
  const OffsetMinimum m = minimize_offset(terms, 0.25, 0.75);
  BOOST_CHECK_EQUAL(m.offset, 0.25);
  BOOST_CHECK_CLOSE(m.value, 0.25, 1e-12);
}

BOOST_AUTO_TEST_SUITE_END()
