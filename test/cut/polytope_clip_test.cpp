#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <random>
#include <set>
#include <utility>

#include "cut/fixtures.h"
#include "dcshell/polytope_clip.h"

using namespace dcshell;
using namespace dcshell::test;

namespace {

// Closed, consistently oriented: every directed edge has exactly one reverse twin.
bool is_closed_manifold(const ConvexPolytope& p) {
  std::multiset<std::pair<int, int>> edges;
  for (const auto& f : p.faces)
    for (std::size_t i = 0; i < f.size(); ++i) edges.emplace(f[i], f[(i + 1) % f.size()]);
  for (const auto& [u, v] : edges)
    if (edges.count({u, v}) != 1 || edges.count({v, u}) != 1) return false;
  return true;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(polytope_clip)

BOOST_AUTO_TEST_CASE(clip_cube_volumes) {
  const ConvexPolytope c = unit_cube();
  BOOST_CHECK_CLOSE(volume(c), 1.0, 1e-12);
  const ConvexPolytope half = clip(c, {Eigen::Vector3d::UnitX(), 0.3}, 7);
  BOOST_CHECK_CLOSE(volume(half), 0.3, 1e-12);
  BOOST_CHECK(is_closed_manifold(half));
  BOOST_CHECK_EQUAL(half.faces.size(), 6u);
  BOOST_CHECK_EQUAL(half.face_tags.back(), 7);
  // Hexagonal section: the kept half of the cube.
  const ConvexPolytope diag = clip(c, {Eigen::Vector3d(1, 1, 1), 1.5}, 2);
  BOOST_CHECK_CLOSE(volume(diag), 0.5, 1e-12);
  BOOST_CHECK(is_closed_manifold(diag));
  BOOST_CHECK_EQUAL(diag.faces.back().size(), 6u);
  // Plane through a vertex only (one corner cut off, tetrahedron of volume 1/6).
  BOOST_CHECK_CLOSE(volume(clip(c, {Eigen::Vector3d(1, 1, 1), 2.0}, 2)), 1.0 - 1.0 / 6, 1e-12);
  BOOST_CHECK_CLOSE(volume(clip(c, {Eigen::Vector3d(1, 1, 1), 1.0}, 2)), 1.0 / 6, 1e-12);
}

BOOST_AUTO_TEST_CASE(clip_touching_and_degenerate_planes) {
  const ConvexPolytope c = unit_cube();
  // Touching a face, an edge, a vertex from outside: unchanged.
  for (const CutPlane& h : {CutPlane{Eigen::Vector3d::UnitX(), 1.0}, CutPlane{Eigen::Vector3d(1, 1, 0), 2.0},
                            CutPlane{Eigen::Vector3d(1, 1, 1), 3.0}, CutPlane{Eigen::Vector3d::UnitX(), 1.0 - 1e-15}}) {
    const ConvexPolytope r = clip(c, h, 1);
    BOOST_CHECK_EQUAL(r.faces.size(), 6u);
    BOOST_CHECK_CLOSE(volume(r), 1.0, 1e-9);
  }
  // Touching from inside: nothing left.
  for (const CutPlane& h : {CutPlane{Eigen::Vector3d::UnitX(), 0.0}, CutPlane{Eigen::Vector3d(1, 1, 0), 0.0},
                            CutPlane{Eigen::Vector3d(1, 1, 1), 0.0}, CutPlane{Eigen::Vector3d::UnitX(), 1e-15}})
    BOOST_CHECK(clip(c, h, 1).empty());
  // Through an edge and a face diagonal: no slivers, still closed.
  const ConvexPolytope wedge = clip(c, {Eigen::Vector3d(1, 1, 0), 1.0}, 1);
  BOOST_CHECK_CLOSE(volume(wedge), 0.5, 1e-12);
  BOOST_CHECK(is_closed_manifold(wedge));
  BOOST_CHECK_EQUAL(wedge.vertices.size(), 6u);
  BOOST_CHECK(clip(ConvexPolytope{}, {Eigen::Vector3d::UnitX(), 0.5}, 1).empty());
}

BOOST_AUTO_TEST_CASE(clip_random_hulls_repeatedly) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    ConvexPolytope p = random_hull(100 + trial, 60, Eigen::Vector3d::Zero(), 1.0);
    const double v0 = volume(p);
    for (int k = 0; k < 8 && !p.empty(); ++k) {
      const Eigen::Vector3d n = random_unit(rng);
      const double d = 0.6 * (2 * u01(rng) - 1);
      const ConvexPolytope in = clip(p, {n, d}, 2), out = clip(p, {-n, -d}, 2);
      BOOST_CHECK_CLOSE(volume(in) + volume(out), volume(p), 1e-9);
      BOOST_CHECK(in.empty() || is_closed_manifold(in));
      p = in;
    }
    BOOST_CHECK_LE(volume(p), v0);
  }
}

BOOST_AUTO_TEST_CASE(intersect_keeps_tags) {
  const ConvexPolytope a = unit_cube(0), b = translated(unit_cube(1), Eigen::Vector3d(0.5, 0.25, 0));
  const ConvexPolytope ab = intersect(a, b);
  BOOST_CHECK_CLOSE(volume(ab), 0.5 * 0.75, 1e-12);
  BOOST_CHECK(is_closed_manifold(ab));
  std::set<int> tags(ab.face_tags.begin(), ab.face_tags.end());
  BOOST_CHECK(tags == (std::set<int>{0, 1}));
  BOOST_CHECK(intersect(a, translated(b, Eigen::Vector3d(3, 0, 0))).empty());
  const Eigen::Vector3d c = centroid(ab);
  BOOST_CHECK_SMALL((c - Eigen::Vector3d(0.75, 0.625, 0.5)).norm(), 1e-12);
}

BOOST_AUTO_TEST_CASE(intersect_of_large_hulls_is_the_clip_by_every_plane) {
  // Two hulls of 600 seeded random points on spheres, overlapping deeply: intersect (the deepest
  // planes first, planes that miss dropped) gives the polytope that clipping by every plane of
  // the larger one in face order gives, up to rounding; and either way round.
  std::mt19937_64 rng(3);
  auto sphere = [&](const Eigen::Vector3d& c, double r) {
    std::vector<Eigen::Vector3d> pts;
    std::normal_distribution<double> g;  // only the hull's size matters, not the platform's bits
    for (int i = 0; i < 600; ++i) {
      Eigen::Vector3d d(g(rng), g(rng), g(rng));
      pts.push_back(c + r * d.normalized());
    }
    return convex_hull_polytope(pts, 0);
  };
  ConvexPolytope a = sphere({0, 0, 0}, 1.0), b = sphere({0.9, 0.2, 0.1}, 0.8);
  a.face_tags.assign(a.faces.size(), 0);
  b.face_tags.assign(b.faces.size(), 1);
  BOOST_TEST_REQUIRE(a.faces.size() > 1000);
  ConvexPolytope by_order = b;  // clipped by every plane of a, in face order
  for (std::size_t f = 0; f < a.faces.size() && !by_order.empty(); ++f) by_order = clip(by_order, face_plane(a, f), 0);
  const ConvexPolytope ab = intersect(a, b), ba = intersect(b, a);
  BOOST_TEST_REQUIRE(volume(by_order) > 0.1);
  BOOST_CHECK_CLOSE(volume(ab), volume(by_order), 1e-9);
  BOOST_CHECK_CLOSE(volume(ba), volume(by_order), 1e-9);
  BOOST_CHECK(is_closed_manifold(ab));
  std::set<int> tags(ab.face_tags.begin(), ab.face_tags.end());
  BOOST_CHECK(tags == (std::set<int>{0, 1}));
  BOOST_CHECK_SMALL((centroid(ab) - centroid(by_order)).norm(), 1e-9);
}

BOOST_AUTO_TEST_CASE(hull_from_points) {
  const ConvexPolytope ball = lattice_ball(3);
  BOOST_CHECK(!ball.empty());
  BOOST_CHECK(is_closed_manifold(ball));
  std::vector<Eigen::Vector3d> flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.5, 0}};
  BOOST_CHECK(convex_hull_polytope(flat).empty());
  BOOST_CHECK(convex_hull_polytope({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}).empty());
  BOOST_CHECK_CLOSE(volume(polytope_from_mesh(to_mesh(unit_cube()))), 1.0, 1e-12);
}

BOOST_AUTO_TEST_CASE(section_area_and_moment) {
  const ConvexPolytope c = unit_cube();
  const PlaneSection s = section(c, {Eigen::Vector3d::UnitZ(), 0.25});
  BOOST_CHECK_CLOSE(s.area, 1.0, 1e-12);
  BOOST_CHECK_SMALL((s.moment - Eigen::Vector3d(0.5, 0.5, 0.25)).norm(), 1e-12);
  // Hexagon through the centre: area 3*sqrt(3)/4, centred at (1/2, 1/2, 1/2).
  const PlaneSection h = section(c, {Eigen::Vector3d(1, 1, 1) / std::sqrt(3.0), 1.5 / std::sqrt(3.0)});
  BOOST_CHECK_CLOSE(h.area, 3 * std::sqrt(3.0) / 4, 1e-12);
  BOOST_CHECK_SMALL((h.moment / h.area - Eigen::Vector3d(0.5, 0.5, 0.5)).norm(), 1e-12);
  // Derivatives of the clipped volume: d/dd = area, d/dn = moment (random hull, random plane).
  const ConvexPolytope p = random_hull(5, 50, Eigen::Vector3d(0.3, -0.2, 0.1), 1.0);
  std::mt19937_64 rng(3);
  for (int k = 0; k < 10; ++k) {
    const Eigen::Vector3d n = random_unit(rng), e = n.unitOrthogonal();
    const double d = n.dot(Eigen::Vector3d(0.3, -0.2, 0.1)) + 0.5 * (2 * u01(rng) - 1), eps = 1e-5;
    const PlaneSection sp = section(p, {n, d});
    const double dv = (volume(clip(p, {n, d + eps}, 1)) - volume(clip(p, {n, d - eps}, 1))) / (2 * eps);
    BOOST_CHECK_CLOSE(sp.area, dv, 1e-4);
    // vol(p ∩ {n·x >= d}) = vol(p) - vol(clip(p, {n, d})); its derivative along e is moment·e.
    auto above = [&](const Eigen::Vector3d& m) { return volume(p) - volume(clip(p, {m, d}, 1)); };
    const double dn = (above(n + eps * e) - above(n - eps * e)) / (2 * eps);
    BOOST_CHECK_SMALL(sp.moment.dot(e) - dn, 1e-6);
  }
}

BOOST_AUTO_TEST_SUITE_END()
