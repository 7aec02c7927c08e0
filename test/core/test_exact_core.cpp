// Exact convex core: hull, clipping, intersection, volumes, union, certification.
#include <boost/test/unit_test.hpp>

#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <cmath>
#include <random>

#include "dcshell/certify.h"
#include "dcshell/convex_hull.h"
#include "dcshell/exact_polytope.h"
#include "dcshell/mesh_volume.h"
#include "dcshell/overlaps.h"
#include "dcshell/union_volume.h"
#include "dcshell/volume_loss.h"
#include "synthetic_parts.h"
#include "test_util.h"

using namespace dcshell;
using dcshell::test::box_points;

BOOST_AUTO_TEST_SUITE(exact_core)

BOOST_AUTO_TEST_CASE(unit_cubes_offset_by_half_overlap_in_exactly_half) {
  ExactPolytope a = exact_hull(box_points(0, 0, 0, 1, 1, 1));
  ExactPolytope b = exact_hull(box_points(0.5, 0, 0, 1.5, 1, 1));
  BOOST_TEST(a.faces.size() == 6u);  // coplanar hull triangles merged into squares
  BOOST_TEST(exact_volume(a) == ExactRational(1));
  ExactPolytope x = intersect(a, b);
  BOOST_REQUIRE(!x.empty());
  BOOST_TEST(exact_volume(x) == ExactRational(1) / 2);
  auto iv = volume_interval(x);
  BOOST_TEST(iv.inf() <= 0.5);
  BOOST_TEST(iv.sup() >= 0.5);
}

BOOST_AUTO_TEST_CASE(regular_tetrahedron_volume_is_exact) {
  // Alternate corners of the cube [-1,1]^3: edge 2*sqrt(2), volume 8/3.
  std::vector<Point3> t{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  BOOST_TEST(exact_volume(exact_hull(t)) == ExactRational(8) / 3);
  BOOST_TEST(check_convexity(convex_hull_mesh(t)).volume == 8.0 / 3, boost::test_tools::tolerance(1e-15));
}

BOOST_AUTO_TEST_CASE(clip_keeps_negative_side_and_creates_cap) {
  ExactPolytope cube = exact_hull(box_points(0, 0, 0, 1, 1, 1));
  // x + y + z <= 1: the corner tetrahedron, volume 1/6.
  CutPlane p{Eigen::Vector3d(1, 1, 1), 1.0};
  ExactPolytope t = clip(cube, exact_plane(p), 7);
  BOOST_TEST(exact_volume(t) == ExactRational(1) / 6);
  BOOST_TEST(t.vertices.size() == 4u);
  int caps = 0;
  for (const auto& f : t.faces) caps += f.tag == 7;
  BOOST_TEST(caps == 1);
  // A plane through a face keeps everything; its opposite keeps nothing.
  BOOST_TEST(exact_volume(clip(cube, exact_plane({Eigen::Vector3d(1, 0, 0), 1.0}), 1)) == ExactRational(1));
  BOOST_TEST(clip(cube, exact_plane({Eigen::Vector3d(-1, 0, 0), -1.0}), 1).empty());
}

BOOST_AUTO_TEST_CASE(pruning_leaves_out_vertices_within_rounding_of_the_others_hull) {
  // A unit cube with a point 1e-11 outside the middle of an edge (its two faces become slivers
  // along the edge), two points 1e-12 above the top face (near-flat cones) and one point 1e-3
  // outside a face (a real corner): the cube's corners and the real one stay, the hull loses at
  // most delta, and a point in `keep` stays whatever its distance.
  std::vector<Point3> pts;
  for (int i = 0; i < 8; ++i) pts.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  pts.push_back({0.5, -1e-11, -1e-11});
  pts.push_back({0.5, 0.5, 1 + 1e-12});
  pts.push_back({0.25, 0.625, 1 + 1e-12});
  pts.push_back({-1e-3, 0.5, 0.5});
  pts.push_back({0.5, 0.5, 0.5});  // interior: never a hull vertex
  BOOST_TEST_REQUIRE(convex_hull_mesh(pts).number_of_vertices() == 12u);
  std::size_t pruned = 0;
  Mesh out = pruned_convex_hull_mesh(pts, 1e-7, {}, &pruned);
  BOOST_TEST(pruned == 3u);
  BOOST_TEST(out.number_of_vertices() == 9u);
  for (auto v : out.vertices()) BOOST_TEST((std::find(pts.begin(), pts.end(), out.point(v)) != pts.end()));
  BOOST_TEST(std::abs(CGAL::to_double(six_signed_volume(out)) / 6 - (1 + 1e-3 / 3)) < 1e-9);
  std::vector<Point3> keep = {pts[8]};
  BOOST_TEST(pruned_convex_hull_mesh(pts, 1e-7, keep).number_of_vertices() == 10u);
  // Far below the distance: nothing goes.
  BOOST_TEST(pruned_convex_hull_mesh(pts, 1e-13).number_of_vertices() == 12u);
}

BOOST_AUTO_TEST_CASE(touching_boxes_do_not_overlap) {
  std::vector<ExactPolytope> p{exact_hull(box_points(0, 0, 0, 1, 1, 1)), exact_hull(box_points(1, 0, 0, 2, 1, 1)),
                               exact_hull(box_points(1, 1, 1, 2, 2, 2)), exact_hull(box_points(0, 1, 0, 1, 2, 1))};
  BOOST_TEST(find_overlaps(p).empty());
  BOOST_TEST(union_volume(p).value == 4.0);
}

BOOST_AUTO_TEST_CASE(union_of_known_boxes) {
  // Three boxes pairwise overlapping with a common triple region; by hand:
  // |A|=2, |B|=1.5*1.75*1=2.625, |C|=1.25*1*1.25=1.5625
  // A∩B=[1,2]x[.25,1]x[.25,1]=0.5625; A∩C=[.5,1.75]x[.5,1]x[0,.75]=0.46875
  // B∩C=[1,1.75]x[.5,1.5]x[.25,.75]=0.375; A∩B∩C=[1,1.75]x[.5,1]x[.25,.75]=0.1875
  std::vector<ExactPolytope> p{exact_hull(box_points(0, 0, 0, 2, 1, 1)), exact_hull(box_points(1, 0.25, 0.25, 2.5, 2, 1.25)),
                               exact_hull(box_points(0.5, 0.5, -0.5, 1.75, 1.5, 0.75))};
  double expect = 2 + 2.625 + 1.5625 - 0.5625 - 0.46875 - 0.375 + 0.1875;
  UnionVolume u = union_volume(p);
  BOOST_TEST(u.value == expect, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(u.terms == 7u);
  BOOST_TEST(u.max_clique == 3u);
  BOOST_TEST(u.error_bound <= 1e-12 * expect);
  // Forcing the exact fallback gives the same value.
  UnionVolume e = union_volume(p, -1.0);
  BOOST_TEST(e.exact_fallback);
  BOOST_TEST(e.value == expect);
  // Reusing the pairwise intersections of find_overlaps: the same terms and the same sum, also
  // with a fourth box that only touches the others (no term).
  p.push_back(exact_hull(box_points(2.5, 0, 0, 3, 1, 1)));
  const std::vector<Overlap> o = find_overlaps(p);
  BOOST_TEST(o.size() == 3u);
  UnionVolume r = union_volume(p, o);
  BOOST_TEST(r.value == expect + 0.5, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(r.terms == 8u);
  BOOST_TEST(union_volume(p, o, -1.0).value == expect + 0.5);
  BOOST_TEST(exact_union_volume(p, &o) == exact_union_volume(p));
  BOOST_TEST(CGAL::to_double(exact_union_volume(p, &o)) == expect + 0.5);
}

namespace {
std::vector<ExactPolytope> hulls_of(const std::vector<Part>& parts) {
  std::vector<ExactPolytope> p;
  for (std::size_t i = 0; i < parts.size(); ++i) p.push_back(exact_hull(parts[i].points, int(i)));
  return p;
}
std::vector<Part> parts_of(const std::vector<std::vector<Point3>>& sets) {
  std::vector<Part> parts(sets.size());
  for (std::size_t i = 0; i < sets.size(); ++i) parts[i].points = sets[i];
  return parts;
}
}  // namespace

BOOST_AUTO_TEST_CASE(nerve_and_decomposition_agree_exactly) {
  // Random rotated boxes (seeded), many overlapping in threes and fours, plus a nested and a
  // duplicated one: the two methods share no code past the exact polytopes, so equal rationals
  // check both.
  std::mt19937_64 rng(7);
  std::vector<Part> sets = synthetic::random_boxes(rng, 14, 3.0, 0.4, 1.4);
  sets.push_back(parts_of({box_points(1.4, 1.4, 1.4, 1.5, 1.5, 1.5)})[0]);
  sets.push_back(sets[3]);
  const std::vector<ExactPolytope> p = hulls_of(sets);
  const UnionVolume nerve = union_volume(p, 1e-12, UnionMethod::nerve);
  const UnionVolume pieces = union_volume(p, 1e-12, UnionMethod::decomposition);
  BOOST_TEST((nerve.method == UnionMethod::nerve));
  BOOST_TEST((pieces.method == UnionMethod::decomposition));
  BOOST_TEST(nerve.max_clique >= 3u);
  BOOST_TEST(std::fabs(nerve.value - pieces.value) <= nerve.error_bound + pieces.error_bound);
  BOOST_TEST(exact_union_volume(p, nullptr, UnionMethod::nerve) == exact_union_volume(p, nullptr, UnionMethod::decomposition));
  const std::vector<Overlap> o = find_overlaps(p);
  BOOST_TEST(exact_union_volume(p, &o, UnionMethod::decomposition) == exact_union_volume(p, &o, UnionMethod::nerve));
  // Nested and duplicated parts leave no piece: a box inside a box is one piece.
  const std::vector<ExactPolytope> nested = hulls_of(parts_of({box_points(0, 0, 0, 2, 2, 2), box_points(0.5, 0.5, 0.5, 1, 1, 1),
                                                               box_points(0, 0, 0, 2, 2, 2)}));
  const UnionVolume n1 = union_volume(nested, 1e-12, UnionMethod::decomposition);
  BOOST_TEST(n1.value == 8.0);
  BOOST_TEST(n1.terms == 1u);
}

BOOST_AUTO_TEST_CASE(deep_overlap_is_summed_by_the_decomposition) {
  // Ten planks through one axis: all 1023 subsets overlap. The nerve takes them all when forced;
  // automatic gives way to the decomposition, and the exact values agree.
  const std::vector<ExactPolytope> ten = hulls_of(synthetic::plank_star(10, 0.004));
  const UnionVolume nerve = union_volume(ten, 1e-12, UnionMethod::nerve);
  BOOST_TEST(nerve.terms == 1023u);
  BOOST_TEST(nerve.max_clique == 10u);
  const UnionVolume autom = union_volume(ten);
  BOOST_TEST((autom.method == UnionMethod::decomposition));
  BOOST_TEST(autom.terms < 200u);
  BOOST_TEST(std::fabs(nerve.value - autom.value) <= nerve.error_bound + autom.error_bound);
  BOOST_TEST(exact_union_volume(ten, nullptr, UnionMethod::nerve) == exact_union_volume(ten));
  // Thirty planks: a billion nerve terms, a few thousand pieces. The union is the planks minus
  // what they share, so it lies between the largest plank and the sum, and it grows with each
  // plank added.
  const std::vector<ExactPolytope> thirty = hulls_of(synthetic::plank_star(30, 0.003));
  const UnionVolume deep = union_volume(thirty);
  BOOST_TEST((deep.method == UnionMethod::decomposition));
  BOOST_TEST(deep.error_bound <= 1e-12 * deep.value);
  BOOST_TEST(deep.value > 8 * 0.6 * 0.1 * 1.5);
  BOOST_TEST(deep.value < 30 * 8 * 0.6 * 0.1);
  std::vector<ExactPolytope> fewer(thirty.begin(), thirty.end() - 1);
  BOOST_TEST(exact_union_volume(fewer) < exact_union_volume(thirty));
}

BOOST_AUTO_TEST_CASE(walk_hands_unfinished_polytopes_to_the_decomposition) {
  // Six small boxes in a chain (shallow: the walk, smallest first, finishes them) and ten large
  // planks through one axis (1023 subsets: the walk runs out of budget there). The planks go to
  // the decomposition, the boxes' shares stay the walk's, and the total is the nerve's exactly.
  std::vector<Part> sets = synthetic::plank_star(10, 0.004);
  for (int k = 0; k < 6; ++k) {
    const double x = 5 + 0.15 * k;
    sets.push_back(parts_of({box_points(x, 5, 5, x + 0.2, 5.2, 5.2)})[0]);
  }
  const std::vector<ExactPolytope> p = hulls_of(sets);
  const UnionVolume autom = union_volume(p);
  BOOST_TEST((autom.method == UnionMethod::decomposition));
  BOOST_TEST(autom.nerve_polytopes >= 6u);
  BOOST_TEST(autom.nerve_polytopes < p.size());
  const UnionVolume nerve = union_volume(p, 1e-12, UnionMethod::nerve);
  BOOST_TEST(nerve.nerve_polytopes == p.size());
  BOOST_TEST(std::fabs(nerve.value - autom.value) <= nerve.error_bound + autom.error_bound);
  BOOST_TEST(exact_union_volume(p) == exact_union_volume(p, nullptr, UnionMethod::nerve));
  const std::vector<Overlap> o = find_overlaps(p);
  BOOST_TEST(exact_union_volume(p, &o) == exact_union_volume(p, &o, UnionMethod::nerve));
}

BOOST_AUTO_TEST_CASE(round_hulls_around_one_point_are_summed_without_rationals) {
  // Six UV spheres of 62 vertices whose centres are at most 0.2 apart: the nerve's alternating
  // sum cancels to a few digits, the decomposition's positive pieces do not. The certified
  // enclosure must hold the exact rational, computed here the slow way.
  std::mt19937_64 rng(6);
  const std::vector<Part> sets = synthetic::random_spheres(rng, 6, 6, 0.1);
  const std::vector<ExactPolytope> p = hulls_of(sets);
  const UnionVolume u = union_volume(p);
  BOOST_TEST(!u.exact_fallback);
  BOOST_TEST(u.error_bound <= 1e-12 * u.value);
  const double exact = CGAL::to_double(exact_union_volume(p, nullptr, UnionMethod::decomposition));
  BOOST_TEST(std::fabs(u.value - exact) <= u.error_bound);
}

BOOST_AUTO_TEST_CASE(fixed_point_sum_holds_the_exact_union) {
  // Asked for more digits than intervals give, the union is summed on the fixed-point grid: its
  // certified enclosure must hold the exact rational, and be some 30 digits narrow.
  std::mt19937_64 rng(11);
  for (const auto& sets : {synthetic::random_spheres(rng, 6, 6, 0.1), synthetic::random_boxes(rng, 12, 3.0, 0.4, 1.4)}) {
    const std::vector<ExactPolytope> p = hulls_of(sets);
    const ExactRational exact = exact_union_volume(p);
    const std::vector<Overlap> o = find_overlaps(p);
    for (const std::vector<Overlap>* overlaps : {static_cast<const std::vector<Overlap>*>(nullptr), &o}) {
      ExactRational centre(-1);
      const UnionVolume u = union_volume(
          p, overlaps, [](const ExactRational& v, double e) { return e <= 1e-20 * CGAL::to_double(v); },
          UnionMethod::automatic, &centre);
      BOOST_TEST(u.fixed_point);
      BOOST_TEST(!u.exact_fallback);
      BOOST_TEST(u.error_bound <= 1e-25 * u.value);
      BOOST_TEST(u.error_bound > 0.0);
      BOOST_TEST(CGAL::abs(centre - exact) <= ExactRational(u.error_bound));
      BOOST_TEST(u.value == CGAL::to_double(exact), boost::test_tools::tolerance(1e-15));
    }
  }
}

BOOST_AUTO_TEST_CASE(volume_loss_has_the_true_sign_down_to_one_ulp) {
  // Two overlapping boxes with non-representable volumes, split exactly at x = c: the shells
  // fill the union, so the loss is exactly 0, whatever the doubles' rounding of the volumes.
  const double c = 0.0731, x1 = 0.15;
  std::vector<ExactPolytope> hulls{exact_hull(box_points(0, 0, 0, 0.1, 0.3, 0.7)),
                                   exact_hull(box_points(0.05, 0, 0, x1, 0.3, 0.7))};
  auto shells_to = [&](double right) {
    return std::vector<Mesh>{convex_hull_mesh(box_points(0, 0, 0, c, 0.3, 0.7)),
                             convex_hull_mesh(box_points(c, 0, 0, right, 0.3, 0.7))};
  };
  VolumeLoss zero = volume_loss(hulls, shells_to(x1));
  BOOST_TEST(zero.value == 0.0);
  BOOST_TEST(zero.exact);
  const std::vector<Overlap> pairs = find_overlaps(hulls);  // the pipeline's path
  BOOST_TEST(volume_loss(hulls, shells_to(x1), &pairs).value == 0.0);
  BOOST_TEST(volume_loss(hulls, shells_to(std::nextafter(x1, 0.0)), &pairs).value > 0.0);
  // One ulp more or less on one face: the loss is tiny but its sign is the true one.
  VolumeLoss grown = volume_loss(hulls, shells_to(std::nextafter(x1, 1.0)));
  BOOST_TEST(grown.value < 0.0);
  BOOST_TEST(grown.value > -1e-14);
  VolumeLoss shrunk = volume_loss(hulls, shells_to(std::nextafter(x1, 0.0)));
  BOOST_TEST(shrunk.value > 0.0);
  // A real loss is decided by the interval filter and matches the exact quotient.
  VolumeLoss half = volume_loss(hulls, shells_to(0.11));
  BOOST_TEST(!half.exact);
  const ExactRational u = exact_union_volume(hulls);
  BOOST_TEST(half.value == CGAL::to_double((u - exact_volume(exact_hull(box_points(0, 0, 0, 0.11, 0.3, 0.7)))) / u),
             boost::test_tools::tolerance(1e-12));
  BOOST_TEST(half.error_bound <= 1e-9 * half.value);
  // A loss of 7e-9, which the intervals (1e-16 of the union) cannot give to 1e-9 of itself: the
  // fixed-point sum does, and matches the exact quotient.
  const double right = x1 - 1e-9;
  VolumeLoss tiny = volume_loss(hulls, shells_to(right), &pairs);
  BOOST_TEST(!tiny.exact);
  BOOST_TEST(tiny.union_stats.fixed_point);
  const ExactRational s = exact_volume(exact_hull(box_points(0, 0, 0, c, 0.3, 0.7))) +
                          exact_volume(exact_hull(box_points(c, 0, 0, right, 0.3, 0.7)));
  const double truth = CGAL::to_double((u - s) / u);
  BOOST_TEST(truth > 0.0);
  BOOST_TEST(std::fabs(tiny.value - truth) <= tiny.error_bound + 1e-16 * truth);
  BOOST_TEST(tiny.error_bound <= 1e-9 * tiny.value);
}

BOOST_AUTO_TEST_CASE(nested_and_duplicated_polytopes) {
  std::vector<ExactPolytope> p{exact_hull(box_points(0, 0, 0, 2, 2, 2)), exact_hull(box_points(0.5, 0.5, 0.5, 1, 1, 1)),
                               exact_hull(box_points(0, 0, 0, 2, 2, 2))};
  BOOST_TEST(union_volume(p).value == 8.0);
  BOOST_TEST(find_overlaps(p).size() == 3u);
}

BOOST_AUTO_TEST_CASE(certify_accepts_cubes_sharing_a_face_and_rejects_overlap) {
  std::vector<Mesh> m{convex_hull_mesh(box_points(0, 0, 0, 1, 1, 1)), convex_hull_mesh(box_points(1, 0, 0, 2, 1, 1))};
  CertificationReport r = certify(m);
  BOOST_TEST(r.certified());
  m.push_back(convex_hull_mesh(box_points(0.5, 0, 0, 1.5, 1, 1)));
  r = certify(m);
  BOOST_TEST(!r.certified());
  BOOST_REQUIRE(r.overlaps.size() == 2u);
  BOOST_TEST(r.overlaps[0].a == 0u);
  BOOST_TEST(r.overlaps[0].b == 2u);
  BOOST_TEST(r.overlaps[0].volume == 0.5);
  BOOST_TEST(r.overlaps[0].ratio_to_smaller == 0.5);
}

BOOST_AUTO_TEST_CASE(certify_sees_an_overlap_far_below_floating_tolerance) {
  // Two boxes sharing the face x = 1 except that one vertex of the second pokes 2^-40 into the
  // first: a tolerance-based check calls this touching; the exact check must not.
  std::vector<Point3> b = box_points(1, 0, 0, 2, 1, 1);
  b[0] = Point3(1 - std::ldexp(1.0, -40), 0, 0);
  std::vector<Mesh> m{convex_hull_mesh(box_points(0, 0, 0, 1, 1, 1)), convex_hull_mesh(b)};
  CertificationReport r = certify(m);
  BOOST_TEST(!r.certified());
  BOOST_REQUIRE(r.overlaps.size() == 1u);
  BOOST_TEST(r.overlaps[0].volume > 0.0);
  BOOST_TEST(r.overlaps[0].volume < 1e-11);
}

BOOST_AUTO_TEST_CASE(convexity_agrees_with_every_vertex_against_every_face) {
  // The certificate walks the exact hull instead of testing every vertex against every face;
  // on random hulls with one vertex moved (in or out, by a little or a lot) both must agree.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int convex = 0, not_convex = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Point3> pts;
    for (int i = 0; i < 40; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
    Mesh m = convex_hull_mesh(pts);
    auto vit = m.vertices().begin();
    std::advance(vit, trial % m.number_of_vertices());
    const Point3 p = m.point(*vit);
    const double s = 1 + (trial % 2 ? 1 : -1) * std::pow(10.0, -1 - trial % 7);
    m.point(*vit) = Point3(p.x() * s, p.y() * s, p.z() * s);
    bool brute = true;
    for (auto f : m.faces()) {
      auto h = m.halfedge(f);
      const Point3 &a = m.point(m.source(h)), &b = m.point(m.target(h)), &c = m.point(m.target(m.next(h)));
      for (auto v : m.vertices()) brute &= CGAL::orientation(a, b, c, m.point(v)) != CGAL::POSITIVE;
    }
    const ConvexityVerdict v = check_convexity(m);
    BOOST_TEST(v.convex == brute, "trial " << trial << ": " << v.reason);
    (brute ? convex : not_convex)++;
  }
  BOOST_TEST(convex > 20);  // both verdicts occur
  BOOST_TEST(not_convex > 20);
}

BOOST_AUTO_TEST_CASE(convexity_verdicts) {
  Mesh cube = convex_hull_mesh(box_points(0, 0, 0, 1, 1, 1));
  BOOST_TEST(check_convexity(cube).ok());
  // Push one vertex inward past the plane of its neighbours: closed, outward, not convex
  // whatever the triangulation of the square faces.
  Mesh dent = cube;
  for (auto v : dent.vertices())
    if (dent.point(v) == Point3(1, 1, 1)) dent.point(v) = Point3(0.5, 0.5, 0.5);
  ConvexityVerdict d = check_convexity(dent);
  BOOST_TEST(d.closed);
  BOOST_TEST(!d.convex);
  // Reverse orientation: inward.
  Mesh inv = cube;
  CGAL::Polygon_mesh_processing::reverse_face_orientations(inv);
  ConvexityVerdict i = check_convexity(inv);
  BOOST_TEST(!i.ok());
  BOOST_TEST(!i.outward);
  // Open mesh.
  Mesh open = cube;
  open.remove_face(*open.faces().begin());
  BOOST_TEST(!check_convexity(open).closed);
}

BOOST_AUTO_TEST_CASE(hull_is_canonical_whatever_the_order_and_heap) {
  // A box with a grid on every face and points on its edges: only the 8 corners are vertices,
  // each square facet gets 2 triangles, and the mesh is the same for shuffled inputs and
  // whatever was allocated before (CGAL's quickhull orders work by handle address).
  std::vector<Point3> pts;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 4; ++j)
      for (int k = 0; k <= 4; ++k)
        if (i % 4 == 0 || j % 4 == 0 || k % 4 == 0) pts.emplace_back(0.25 * i, 0.5 * j, 0.125 * k);
  const auto key = [](const Mesh& m) {
    std::vector<double> out;
    for (auto f : m.faces())
      for (auto v : CGAL::vertices_around_face(m.halfedge(f), m))
        for (int d = 0; d < 3; ++d) out.push_back(m.point(v)[d]);
    return out;
  };
  const Mesh first = convex_hull_mesh(pts);
  BOOST_TEST(first.number_of_vertices() == 8u);
  BOOST_TEST(first.number_of_faces() == 12u);
  BOOST_TEST(check_convexity(first).ok());
  std::vector<std::vector<double>> ballast;
  std::uint64_t s = 1;
  for (int round = 0; round < 20; ++round) {
    for (std::size_t i = pts.size(); i > 1; --i) {  // deterministic shuffle
      s = s * 6364136223846793005ULL + 1442695040888963407ULL;
      std::swap(pts[i - 1], pts[(s >> 33) % i]);
    }
    ballast.emplace_back(std::size_t(1 + (s >> 40) % 5000), 0.0);  // move the heap around
    const Mesh again = convex_hull_mesh(pts);
    BOOST_TEST((key(again) == key(first)), "round " << round);
  }
  // A regular octagon prism: cocircular facet corners, still one fixed triangulation.
  std::vector<Point3> prism;
  for (int i = 0; i < 8; ++i)
    for (double z : {0.0, 1.0}) prism.emplace_back(std::cos(i * M_PI / 4), std::sin(i * M_PI / 4), z);
  const Mesh p0 = convex_hull_mesh(prism);
  BOOST_TEST(p0.number_of_faces() == 2u * 6u + 16u);
  std::reverse(prism.begin(), prism.end());
  BOOST_TEST((key(convex_hull_mesh(prism)) == key(p0)));
}

BOOST_AUTO_TEST_SUITE_END()
