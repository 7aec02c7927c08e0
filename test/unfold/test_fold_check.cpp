// Continuous folding check (fold_check.h): constructed collisions are caught at their first
// contact, including one that exists only mid-way (both ends of the path are collision-free);
// free paths of the Platonic solids are verified; a crossing found by the check is real.
#include <boost/test/unit_test.hpp>

#include <limits>
#include <map>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/Box_intersection_d/Box_with_info_d.h>

#include "dcshell/build_shells.h"
#include "dcshell/convex_hull.h"
#include "dcshell/fold_check.h"
#include "dcshell/net_overlap.h"
#include "dcshell/read_mesh.h"
#include "dcshell/unfold.h"
#include "unfold/box_sweep.h"
#include "unfold/pair_slots.h"
#include "unfold_test_util.h"

using namespace dcshell;
using namespace dcshell::test;

namespace {
// Small deterministic generator (Knuth's MMIX LCG) for the randomised tests.
struct Lcg {
  std::uint64_t state;
  explicit Lcg(std::uint64_t seed) : state(seed) {}
  std::uint64_t next() { return state = state * 6364136223846793005ULL + 1442695040888963407ULL; }
  double uniform() { return static_cast<double>(next() >> 11) / 9007199254740992.0; }  // [0, 1)
};

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
const double deg = M_PI / 180;

// A unit square base (2 triangles, joined by a flat fold) with a triangular flap hinged on its
// left side (apex a) and one on its right side (apex b), folded by angle_a and angle_b (negative
// = up, towards +z: the outside of the shell faces +z and convex folds turn faces down).
// A net drawn where its shell vertices lie (z = 0): faces, cut tree and folds {v0, v1, f0, f1}
// with their angles.
Net planar_net(std::vector<Eigen::Vector3d> v, std::vector<std::array<int, 3>> faces, std::vector<int> parent,
               const std::vector<std::array<int, 4>>& folds, const std::vector<double>& angles) {
  Net n;
  n.shell_vertices = std::move(v);
  n.shell_faces = std::move(faces);
  for (auto& t : n.shell_faces) {
    std::array<Eigen::Vector2d, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = n.shell_vertices[t[k]].head<2>();
    n.corners.push_back(c);
  }
  n.parent = std::move(parent);
  for (std::size_t i = 0; i < folds.size(); ++i) {
    Net::Edge e;
    e.v0 = folds[i][0], e.v1 = folds[i][1], e.f0 = folds[i][2], e.f1 = folds[i][3], e.fold = true;
    e.fold_angle = angles[i];
    n.edges.push_back(e);
  }
  return n;
}

Net flap_net(double angle_a, double angle_b, Eigen::Vector2d a, Eigen::Vector2d b) {
  return planar_net({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {a.x(), a.y(), 0}, {b.x(), b.y(), 0}},
                    {{0, 1, 2}, {0, 2, 3}, {3, 4, 0}, {1, 5, 2}}, {-1, 0, 1, 0}, {{0, 2, 0, 1}, {3, 0, 1, 2}, {1, 2, 0, 3}},
                    {0.0, angle_a, angle_b});
}

// Independent reference: do the two flaps (faces 2 and 3, which share no vertex) intersect at t?
bool flaps_intersect(const Net& net, double t) {
  auto F = folded_faces(net, t);
  auto tri = [&](int f) {
    auto p = [&](int k) { return K::Point_3(F[f][k].x(), F[f][k].y(), F[f][k].z()); };
    return K::Triangle_3(p(0), p(1), p(2));
  };
  return CGAL::do_intersect(tri(2), tri(3));
}

double flaps_distance(const Net& net, double t) {
  auto F = folded_faces(net, t);
  auto tri = [&](int f) {
    auto p = [&](int k) { return K::Point_3(F[f][k].x(), F[f][k].y(), F[f][k].z()); };
    return K::Triangle_3(p(0), p(1), p(2));
  };
  double d2 = 1e300;
  auto A = tri(2), B = tri(3);
  for (int k = 0; k < 3; ++k) {
    d2 = std::min(d2, CGAL::to_double(CGAL::squared_distance(A.vertex(k), B)));
    d2 = std::min(d2, CGAL::to_double(CGAL::squared_distance(B.vertex(k), A)));
    for (int j = 0; j < 3; ++j)
      d2 = std::min(d2, CGAL::to_double(CGAL::squared_distance(K::Segment_3(A.vertex(k), A.vertex((k + 1) % 3)),
                                                              K::Segment_3(B.vertex(j), B.vertex((j + 1) % 3)))));
  }
  return std::sqrt(d2);
}

// Every DC-shell of a shared composite model (default pipeline) unfolds into an overlap-free net
// whose folding is verified, and the returned net checked on its own (with the unfolder's end
// proof) gets the same proof.
// Skipped without the shared data.
void expect_every_dc_shell_net_verified(const std::string& model, std::size_t shells) {
  if (!have_shared_data()) {
    BOOST_TEST_MESSAGE("shared data absent: skipped");
    return;
  }
  std::vector<std::string> warnings;
  auto parts = load_parts({shared_data() + "/composite/" + model}, warnings);
  ShellResult sr = build_shells(parts, ShellOptions{});
  BOOST_TEST_REQUIRE(sr.shells.size() == shells);
  for (std::size_t i = 0; i < sr.shells.size(); ++i) {
    UnfoldStats st;
    Net net = unfold_convex_mesh(sr.shells[i].mesh, {}, &st);
    BOOST_TEST(st.result.overlapping_pairs == 0);
    BOOST_TEST(st.fold.verified, model << " shell " << i << ": " << st.fold.message);
    FoldCheckOptions same;  // the unfolder's checks prove the end of the path on its own
    same.end_proof = UnfoldOptions{}.fold_screen;
    BOOST_TEST(check_folding(net, same).verified == st.fold.verified);
  }
}

// Random cut trees of ellipsoid hulls (3 shapes, 8 seeds each), each in its own test context.
template <class F>
void for_random_ellipsoid_nets(F f) {
  for (std::uint64_t seed : {1, 2, 3}) {
    const Mesh m = ellipsoid_hull(60, seed, 0.6, 0.35);
    for (int attempt = 0; attempt < 8; ++attempt) {
      BOOST_TEST_CONTEXT("ellipsoid " << seed << ", random net " << attempt) {
        UnfoldOptions o;
        o.heuristic = UnfoldHeuristic::random;
        o.fold_candidates = 0;
        o.seed = 100 * seed + attempt;
        f(unfold_convex_mesh(m, o));
      }
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(fold_check_reports_the_first_contact_of_crossing_flaps) {
  // Two 0.8-wide flaps fold up by 170 degrees over a unit square: their tips meet when
  // cos(angle) = -1/1.6, i.e. at t = acos(-0.625) / (170 deg) = 0.7571..., and they stay crossed.
  Net bad = flap_net(-170 * deg, -170 * deg, {-0.8, 0.5}, {1.8, 0.5});
  BOOST_TEST_REQUIRE(flaps_intersect(bad, 1.0));
  auto r = check_folding(bad);
  BOOST_TEST(!r.verified);
  BOOST_TEST(((r.face_a == 2 && r.face_b == 3)), r.message);
  const double first = std::acos(-0.625) / (170 * deg);
  BOOST_TEST(r.t <= first);          // never past the first contact
  BOOST_TEST(r.t > first - 1e-6);    // and at it, not a pessimistic early stop
  BOOST_TEST(flaps_distance(bad, r.t) < 1e-6);
  // Folded by 80 degrees only, the flaps never meet.
  auto ok = check_folding(flap_net(-80 * deg, -80 * deg, {-0.8, 0.5}, {1.8, 0.5}));
  BOOST_TEST(ok.verified, ok.message);
}

BOOST_AUTO_TEST_CASE(fold_check_skips_pairs_within_a_proved_group_only) {
  // The crossing flaps (faces 2 and 3): with both in one proved group their pair is taken as
  // proved; with the flaps in different groups it is checked and found as without groups.
  Net bad = flap_net(-170 * deg, -170 * deg, {-0.8, 0.5}, {1.8, 0.5});
  const auto plain = check_folding(bad);
  BOOST_TEST_REQUIRE(!plain.verified);
  FoldCheckOptions same;
  same.proved_group = {0, 0, 0, 0};
  BOOST_TEST(check_folding(bad, same).verified);
  FoldCheckOptions apart;
  apart.proved_group = {0, 0, 0, 1};
  const auto r = check_folding(bad, apart);
  BOOST_TEST(!r.verified);
  BOOST_TEST(((r.face_a == 2 && r.face_b == 3)), r.message);
  BOOST_TEST(r.t == plain.t);
  FoldCheckOptions wrong_size;  // not one id per face: ignored
  wrong_size.proved_group = {0, 0};
  BOOST_TEST(!check_folding(bad, wrong_size).verified);
}

BOOST_AUTO_TEST_CASE(fold_check_catches_a_collision_that_exists_only_mid_way) {
  // The long right flap (1.8 from its hinge) turns by 178 degrees, the left one by 160: the right
  // tip sweeps through the left flap around t = 0.8 and is past it (below it) at the end. Both
  // ends of the path are collision-free, so a check of the end states alone would miss it.
  Net net = flap_net(-160 * deg, -178 * deg, {-0.9, 0.5}, {1.8, 0.5});
  BOOST_TEST_REQUIRE(!flaps_intersect(net, 0.0));
  BOOST_TEST_REQUIRE(!flaps_intersect(net, 1.0));
  double hit = -1;  // reference: first sampled colliding state
  for (int i = 0; i <= 2000 && hit < 0; ++i)
    if (flaps_intersect(net, i / 2000.0)) hit = i / 2000.0;
  BOOST_TEST_REQUIRE(hit > 0.5);
  BOOST_TEST_REQUIRE(hit < 0.99);
  auto r = check_folding(net);
  BOOST_TEST(!r.verified);
  BOOST_TEST(((r.face_a == 2 && r.face_b == 3)), r.message);
  BOOST_TEST(r.t <= hit);
  BOOST_TEST(r.t > hit - 1e-2);
  BOOST_TEST(flaps_distance(net, r.t) < 1e-6);
}

BOOST_AUTO_TEST_CASE(fold_check_from_a_later_start_checks_only_the_end_of_the_path) {
  // The flaps that cross at t = 0.757 and stay crossed: from t_begin = 0.999 the check fails at
  // once, conclusively (the faces cross), in fewer steps than the whole check.
  Net crossed = flap_net(-170 * deg, -170 * deg, {-0.8, 0.5}, {1.8, 0.5});
  const auto whole = check_folding(crossed);
  BOOST_TEST_REQUIRE(!whole.verified);
  BOOST_TEST(whole.conclusive, whole.message);  // the flaps really cross at the reported state
  FoldCheckOptions end;
  end.t_begin = 0.999;
  const auto screened = check_folding(crossed, end);
  BOOST_TEST(!screened.verified);
  BOOST_TEST(screened.conclusive, screened.message);
  BOOST_TEST(screened.t >= 0.999);
  BOOST_TEST(screened.steps < whole.steps);
  // The collision that exists only mid-way (from about t = 0.8) is not in the end of the path:
  // the check from halfway between its last crossing state and 1 verifies that stretch, the one
  // from 0.5 finds the crossing.
  Net midway = flap_net(-160 * deg, -178 * deg, {-0.9, 0.5}, {1.8, 0.5});
  double last = -1;  // reference: last sampled crossing state
  for (int i = 0; i <= 2000; ++i)
    if (flaps_intersect(midway, i / 2000.0)) last = i / 2000.0;
  BOOST_TEST_REQUIRE(last > 0.5);
  BOOST_TEST_REQUIRE(last < 0.999);
  end.t_begin = (1 + last) / 2;
  const auto after = check_folding(midway, end);
  BOOST_TEST(after.verified, after.message << " (last crossing " << last << ")");
  end.t_begin = 0.5;
  const auto from_half = check_folding(midway, end);
  BOOST_TEST(!from_half.verified);
  BOOST_TEST(from_half.t <= check_folding(midway).t + 1e-2);
  // A free fold is free from any start.
  for (double t0 : {0.0, 0.5, 0.999}) {
    end.t_begin = t0;
    BOOST_TEST(check_folding(flap_net(-80 * deg, -80 * deg, {-0.8, 0.5}, {1.8, 0.5}), end).verified);
  }
}

namespace {
// Two checks of one net that must agree to the step.
void expect_same_outcome(const FoldCheckResult& a, const FoldCheckResult& b) {
  BOOST_TEST(a.verified == b.verified);
  BOOST_TEST(a.t == b.t);
  BOOST_TEST(a.steps == b.steps);
  BOOST_TEST(a.message == b.message);
}
}  // namespace

BOOST_AUTO_TEST_CASE(fold_check_conclusive_failures_of_the_end_refute_the_whole_path) {
  // Random cut trees of ellipsoid hulls, checked from t = 0.999 and from t = 0: a conclusive
  // failure of the end never belongs to a net the whole check verifies, and conclusive
  // failures do occur (they are what the unfolder's screen skips the whole check for). With
  // end_first the check returns that failure, or else exactly what the whole check with the
  // same end proof returns (the end's set-up is shared, not its proofs).
  int conclusive = 0, verified = 0;
  for_random_ellipsoid_nets([&](const Net& net) {
    FoldCheckOptions end, split;
    end.t_begin = 0.999;
    split.end_proof = 1e-3;
    const auto screened = check_folding(net, end), whole = check_folding(net, split);
    if (screened.conclusive) {
      ++conclusive;
      BOOST_TEST(!whole.verified, screened.message);
    }
    verified += whole.verified;
    // end_first: that refutation, or else exactly the whole check's result.
    FoldCheckOptions first;
    first.end_first = 1e-3;
    const auto r = check_folding(net, first);
    BOOST_TEST(r.refuted_at_end == screened.conclusive);
    if (r.refuted_at_end) {
      BOOST_TEST(r.t == screened.t);
      BOOST_TEST(r.message == screened.message);
    } else {
      expect_same_outcome(r, whole);
      BOOST_TEST(r.end_first_steps == screened.steps);
    }
  });
  BOOST_TEST(conclusive > 0);
  BOOST_TEST(verified > 0);
}

BOOST_AUTO_TEST_CASE(fold_check_end_first_defers_nets_whose_end_it_cannot_prove) {
  // With end_first_defers a net whose end [0.999, 1] fails without refuting it stops there,
  // undecided (the end's own failure, not a verdict); every other net gets exactly the result of
  // end_first alone. Such nets do occur on random ellipsoid trees, and the stop is never taken
  // for a net whose end verifies.
  int deferred = 0;
  for_random_ellipsoid_nets([&](const Net& net) {
    FoldCheckOptions end, first, defers;
    end.t_begin = 0.999;
    first.end_first = defers.end_first = 1e-3;
    defers.end_first_defers = true;
    const auto screened = check_folding(net, end), plain = check_folding(net, first), r = check_folding(net, defers);
    const bool stop = !screened.verified && !screened.conclusive;
    BOOST_TEST(r.undecided_at_end == stop);
    BOOST_TEST(!(r.undecided_at_end && r.verified));
    if (stop) {
      ++deferred;
      expect_same_outcome(r, screened);
      BOOST_TEST(!r.refuted_at_end);
    } else {
      expect_same_outcome(r, plain);
      BOOST_TEST(r.refuted_at_end == plain.refuted_at_end);
    }
  });
  BOOST_TEST(deferred > 0);
}

BOOST_AUTO_TEST_CASE(sampled_collision_finds_crossing_flaps_and_never_a_free_fold) {
  // Crossed from mid-way to the end: the first sampled state (t close to 1) refutes it, after
  // the check's first contact, and the two flaps really intersect there (CGAL, independently).
  // (The flaps are not mirror images: two mirrored flaps cross edge against edge, where no edge
  // passes through a face's interior, and only interiors are sampled.)
  Net bad = flap_net(-170 * deg, -170 * deg, {-0.8, 0.5}, {1.9, 0.4});
  auto hit = find_sampled_collision(bad);
  BOOST_TEST_REQUIRE(hit.has_value());
  BOOST_TEST(!hit->verified);
  BOOST_TEST(((hit->face_a == 2 && hit->face_b == 3)), hit->message);
  BOOST_TEST(hit->t >= check_folding(bad).t);
  BOOST_TEST(hit->t < 1.0);
  BOOST_TEST(flaps_intersect(bad, hit->t));
  // Crossed only mid-way (about t = 0.79 to 0.97): found by the states densest near the end.
  Net transient = flap_net(-160 * deg, -178 * deg, {-0.9, 0.5}, {1.8, 0.5});
  auto mid = find_sampled_collision(transient, 16);
  BOOST_TEST_REQUIRE(mid.has_value());
  BOOST_TEST(mid->t > 0.5);
  BOOST_TEST(mid->t < 0.99);
  BOOST_TEST(flaps_intersect(transient, mid->t));
  // Free folds: nothing is found, whatever the number of states.
  for (int samples : {2, 16, 200}) {
    BOOST_TEST(!find_sampled_collision(flap_net(-80 * deg, -80 * deg, {-0.8, 0.5}, {1.8, 0.5}), samples));
    for (const Mesh& m : {tetrahedron(), octahedron(), dodecahedron(), icosahedron()})
      BOOST_TEST(!find_sampled_collision(unfold_convex_mesh(m), samples));
  }
}

BOOST_AUTO_TEST_CASE(sampled_collision_counts_the_face_pairs_whose_boxes_meet) {
  // The unfolder charges a probe by these pairs: they are every pair of faces whose closed
  // bounding boxes meet, summed over the states t = 1 - (k / samples)^2, k = 1 .. samples - 1.
  const Net net = unfold_convex_mesh(icosahedron());
  const int samples = 8;
  long long pairs = -1;
  BOOST_TEST_REQUIRE(!find_sampled_collision(net, samples, 1e-7, &pairs));
  long long expected = 0;
  for (int k = 1; k < samples; ++k) {
    const double s = static_cast<double>(k) / samples;
    const auto x = folded_faces(net, 1 - s * s);
    std::vector<Eigen::AlignedBox3d> box(x.size());
    for (std::size_t f = 0; f < x.size(); ++f)
      for (const auto& c : x[f]) box[f].extend(c);
    for (std::size_t f = 0; f < x.size(); ++f)
      for (std::size_t g = f + 1; g < x.size(); ++g) expected += box[f].intersects(box[g]);
  }
  BOOST_TEST(expected > 0);
  BOOST_TEST(pairs == expected);
}

BOOST_AUTO_TEST_CASE(sampled_collision_agrees_with_the_check_on_random_nets) {
  // Random cut trees of ellipsoid hulls: wherever a sampled state collides, the check does not
  // verify the net and stops at or before that state, and the two faces reported really cross
  // there: CGAL's intersection of the two triangles is a segment (or more), not a corner they
  // share. Both outcomes occur, so the agreement is tested on both sides.
  int hits = 0, free_verified = 0;
  for_random_ellipsoid_nets([&](const Net& net) {
    const auto hit = find_sampled_collision(net);
    const auto full = check_folding(net);
    if (!hit) {
      free_verified += full.verified;
      return;
    }
    ++hits;
    BOOST_TEST(!full.verified);
    BOOST_TEST(full.t <= hit->t, full.message << " / " << hit->message);
    auto F = folded_faces(net, hit->t);
    auto tri = [&](int f) {
      auto p = [&](int k) { return K::Point_3(F[f][k].x(), F[f][k].y(), F[f][k].z()); };
      return K::Triangle_3(p(0), p(1), p(2));
    };
    const auto x = CGAL::intersection(tri(hit->face_a), tri(hit->face_b));
    const K::Segment_3* seg = x ? boost::get<K::Segment_3>(&*x) : nullptr;
    BOOST_TEST((seg ? seg->squared_length() > 0 : x && !boost::get<K::Point_3>(&*x)), hit->message);
  });
  BOOST_TEST(hits > 0);
  BOOST_TEST(free_verified > 0);
}

BOOST_AUTO_TEST_CASE(unfolder_reports_the_first_contact_of_a_net_refuted_by_sampling) {
  // The fold selection skips nets that a sampled state refutes; when the one it returns is such
  // a net (here: the only candidate allowed), its report is still the check's first contact,
  // not the sampled state. Fails when the selection reports the sampled state.
  Mesh m = ellipsoid_hull(60, 1, 0.6, 0.35);
  UnfoldOptions o;
  o.heuristic = UnfoldHeuristic::random;
  o.fold_candidates = 1;
  o.fold_fallback_slack = 0;
  int tested = 0;
  for (std::uint64_t seed = 100; seed < 116 && tested == 0; ++seed) {
    o.seed = seed;
    UnfoldStats st;
    const Net net = unfold_convex_mesh(m, o, &st);
    if (!find_sampled_collision(net)) continue;
    ++tested;
    BOOST_TEST(st.fold_checks == 1);
    const auto full = check_folding(net);
    BOOST_TEST(!st.fold.verified);
    BOOST_TEST(st.fold.t == full.t);
    BOOST_TEST(st.fold.message == full.message);
  }
  BOOST_TEST(tested == 1);
}

BOOST_AUTO_TEST_CASE(unfolder_reports_the_first_contact_of_a_net_refuted_by_its_end_screen) {
  // A net that no sampled state refutes but whose end of path fails conclusively is skipped
  // without the whole check; when it is returned all the same (the only candidate allowed),
  // its report is the whole check's first contact, not the screen's state.
  UnfoldOptions o;
  o.fold_candidates = 1;
  o.fold_fallback_slack = 0;
  FoldCheckOptions end;
  end.t_begin = 1 - o.fold_screen;
  int tested = 0;
  for (std::uint64_t mesh_seed = 1; mesh_seed <= 4 && tested == 0; ++mesh_seed) {
    const Mesh m = ellipsoid_hull(60, mesh_seed, 0.6, 0.35);
    for (auto h : {UnfoldHeuristic::steepest, UnfoldHeuristic::min_perimeter, UnfoldHeuristic::random}) {
      o.heuristic = h;
      for (std::uint64_t seed = 1; seed <= 12 && tested == 0; ++seed) {
        o.seed = seed;
        UnfoldStats st;
        const Net net = unfold_convex_mesh(m, o, &st);
        if (find_sampled_collision(net, 16) || !check_folding(net, end).conclusive) continue;
        ++tested;
        const auto full = check_folding(net);
        BOOST_TEST(st.fold_checks == 1);
        BOOST_TEST(!full.verified);
        BOOST_TEST(!st.fold.verified);
        BOOST_TEST(st.fold.t == full.t);
        BOOST_TEST(st.fold.message == full.message);
      }
    }
  }
  BOOST_TEST(tested == 1);
}

BOOST_AUTO_TEST_CASE(fold_check_verifies_platonic_nets_and_counts_pieces) {
  // The unfolder checks its best nets in turn and returns the first verified one: every Platonic
  // solid gets one. The cube's 12 triangles fold as 6 rigid pieces.
  std::vector<std::pair<std::string, Mesh>> solids = {{"tetrahedron", tetrahedron()}, {"octahedron", octahedron()},
                                                      {"dodecahedron", dodecahedron()}, {"icosahedron", icosahedron()}};
  for (auto& [name, mesh] : solids) {
    Net net = unfold_convex_mesh(mesh);
    auto r = check_folding(net);
    BOOST_TEST(r.verified, name << ": " << r.message);
    BOOST_TEST(r.t == 1.0);
  }
  UnfoldOptions o;
  o.fold_candidates = 0;
  const Net cube = unfold_convex_mesh(cube_triangles(), o);
  auto r = check_folding(cube);
  BOOST_TEST(r.pieces == 6);
  BOOST_TEST(rigid_pieces(cube) == 6);
  BOOST_TEST(rigid_pieces(unfold_convex_mesh(subdivided_cube(4), o)) == check_folding(unfold_convex_mesh(subdivided_cube(4), o)).pieces);
  // Deterministic: the same net gives the same answer and step count.
  Net ico = unfold_convex_mesh(icosahedron(), o);
  auto a = check_folding(ico), b = check_folding(ico);
  BOOST_TEST(a.steps == b.steps);
  BOOST_TEST(a.verified == b.verified);
}

BOOST_AUTO_TEST_CASE(fold_check_past_its_piece_limit_is_undecided_not_verified) {
  // The cube's net has 6 rigid pieces: at a limit of 5 it is not checked (undecided, t = 0), at
  // 6 it is checked and verified as before.
  UnfoldOptions o;
  o.fold_candidates = 0;
  const Net net = unfold_convex_mesh(cube_triangles(), o);
  FoldCheckOptions limited;
  limited.max_pieces = 5;
  const auto r = check_folding(net, limited);
  BOOST_TEST(!r.verified);
  BOOST_TEST(r.out_of_budget);
  BOOST_TEST(r.t == 0.0);
  BOOST_TEST(r.pieces == 6);
  BOOST_TEST(r.message.find("6 rigid pieces") != std::string::npos, r.message);
  limited.max_pieces = 6;
  BOOST_TEST(check_folding(net, limited).verified == check_folding(net).verified);
}

BOOST_AUTO_TEST_CASE(fold_check_pair_bound_stops_undecided_and_counts_in_the_work) {
  // The icosahedron's net: unbounded, the check verifies with P candidate pairs over its steps
  // and uses (steps + the end proof's steps) x pieces of budget. With the pairs bounded below P
  // it stops undecided at the step that passes the bound; bounded above P it gives the same
  // verdict and steps as before.
  // Corners tested against planes only add to the work.
  UnfoldOptions o;
  o.fold_candidates = 0;
  const Net net = unfold_convex_mesh(icosahedron(), o);
  FoldCheckOptions free_run;
  free_run.max_work = 1000000;  // far more steps than the check takes
  const auto a = check_folding(net, free_run);
  BOOST_TEST_REQUIRE(a.verified, a.message);
  BOOST_TEST_REQUIRE(a.pair_tests > 10);
  BOOST_TEST(a.work == static_cast<long long>(a.steps + a.end_first_steps) * a.pieces);  // the end's own pass counts too
  FoldCheckOptions low = free_run;
  low.pairs_per_work = static_cast<double>(a.pair_tests / 2) / static_cast<double>(low.max_work);
  const auto b = check_folding(net, low);
  BOOST_TEST(!b.verified);
  BOOST_TEST(b.out_of_budget);
  BOOST_TEST(b.t < 1.0);
  BOOST_TEST(b.message.find("pair limit") != std::string::npos, b.message);
  BOOST_TEST(b.pair_tests > a.pair_tests / 2);
  BOOST_TEST(b.pair_tests < a.pair_tests);
  BOOST_TEST(b.work >= static_cast<long long>(static_cast<double>(b.pair_tests) / low.pairs_per_work) - 1);
  FoldCheckOptions high = free_run;
  high.pairs_per_work = static_cast<double>(2 * a.pair_tests) / static_cast<double>(high.max_work);
  const auto c = check_folding(net, high);
  BOOST_TEST(c.verified);
  BOOST_TEST(c.steps == a.steps);
  BOOST_TEST(c.pair_tests == a.pair_tests);
  // Corners tested against planes are counted in the work, never bounded: the same verdict.
  BOOST_TEST_REQUIRE(a.corner_tests > a.work);
  FoldCheckOptions counted = free_run;
  counted.corners_per_work = 1;
  const auto d = check_folding(net, counted);
  BOOST_TEST(d.verified);
  BOOST_TEST(d.steps == a.steps);
  BOOST_TEST(d.corner_tests == a.corner_tests);
  BOOST_TEST(d.work == d.corner_tests);
}

BOOST_AUTO_TEST_CASE(fold_check_collision_found_on_a_shared_model_is_real) {
  // ellip's smallest random net (the default's choice before the greedy trees joined it)
  // collides mid-way (faces 3 and 4 near t = 0.5515, found by sampling); the check must not
  // verify it and must stop at or before that contact.
  if (!have_shared_data()) {
    BOOST_TEST_MESSAGE("shared data absent: skipped");
    return;
  }
  Mesh m = read_mesh(shared_data() + "/convex/ellip.obj");
  UnfoldOptions o;
  o.heuristic = UnfoldHeuristic::random;
  o.fold_candidates = 0;
  Net net = unfold_convex_mesh(m, o);
  auto r = check_folding(net);
  BOOST_TEST(!r.verified);
  // Reference: sample from the reported state on; the reported pair must really intersect soon.
  auto intersect = [&](double t) {
    auto F = folded_faces(net, t);
    auto tri = [&](int f) {
      Eigen::Vector3d c = (F[f][0] + F[f][1] + F[f][2]) / 3;
      auto p = [&](int k) {
        Eigen::Vector3d x = F[f][k] + 1e-3 * (c - F[f][k]);  // away from shared corners
        return K::Point_3(x.x(), x.y(), x.z());
      };
      return K::Triangle_3(p(0), p(1), p(2));
    };
    return CGAL::do_intersect(tri(r.face_a), tri(r.face_b));
  };
  BOOST_TEST(!intersect(r.t * 0.99));
  bool found = false;
  for (int i = 0; i <= 200 && !found; ++i) found = intersect(r.t + i * 1e-4);
  BOOST_TEST(found, r.message);
}

namespace {

// A unit square (2 triangles, flat fold) with a child piece hinged on its right side x = 1: the
// triangle (1,0) (1.5,0.5) (1,1) and, joined to it by a flat fold along (1,0)-(1.5,0.5), the
// triangle (1,0) `extra` (1.5,0.5). With extra = (0.8,-0.5) the child's convex hull reaches over
// the hinge line into the square (the hulls overlap) although no two faces do.
Net hinged_pair_net(double angle, Eigen::Vector2d apex, Eigen::Vector2d extra) {
  Net n;
  n.shell_vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {apex.x(), apex.y(), 0}, {extra.x(), extra.y(), 0}};
  n.shell_faces = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}, {1, 5, 4}};
  for (auto& t : n.shell_faces) {
    std::array<Eigen::Vector2d, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = n.shell_vertices[t[k]].head<2>();
    n.corners.push_back(c);
  }
  n.parent = {-1, 0, 0, 2};
  auto edge = [](int v0, int v1, int f0, int f1, double a) {
    Net::Edge e;
    e.v0 = v0, e.v1 = v1, e.f0 = f0, e.f1 = f1, e.fold = true, e.fold_angle = a;
    return e;
  };
  n.edges = {edge(0, 2, 0, 1, 0.0), edge(1, 2, 0, 2, angle), edge(1, 4, 2, 3, 0.0)};
  return n;
}

}  // namespace

BOOST_AUTO_TEST_CASE(fold_check_proves_adjacent_pieces_apart_when_their_hulls_overlap_in_the_flat_net) {
  // The child piece's hull crosses the hinge line, so the hulls touch (overlap) at t = 0, but the
  // faces do not: two pieces turning about one line meet only on it. Verified for both fold
  // directions and nearly to a half turn.
  for (double angle : {90 * deg, -90 * deg, 170 * deg}) {
    Net net = hinged_pair_net(angle, {1.5, 0.5}, {0.8, -0.5});
    BOOST_TEST_REQUIRE(find_net_overlaps(net).empty());
    auto r = check_folding(net);
    BOOST_TEST(r.verified, angle / deg << " deg: " << r.message);
    BOOST_TEST(r.pieces == 2);
  }
  // The same child folded over onto the square (apex inside it): the flat pieces overlap, so the
  // hinge argument does not apply and the check reports the flat net.
  Net bad = hinged_pair_net(90 * deg, {0.5, 0.5}, {0.8, -0.5});
  BOOST_TEST_REQUIRE(!find_net_overlaps(bad).empty());
  auto r = check_folding(bad);
  BOOST_TEST(!r.verified);
  BOOST_TEST(r.t == 0.0);
}

BOOST_AUTO_TEST_CASE(fold_check_proves_every_cow_dc_shell_net) {
  // Cow's DC-shells have polytope edges that are chains of glued folds bending by ~1e-6 at
  // nearly flat vertices: non-adjacent pieces touch in the flat net at a corner slightly off the
  // hinge lines, and corners 1e-7 of the model apart stay that close along the whole path. Plane
  // advancement (first-order separation by a plane fixed to one piece) proves these; distance
  // stepping alone verified 8 of the 16 nets (stopping at t = 0 or crawling to the step limit).
  expect_every_dc_shell_net_verified("Cow", 16);
}

BOOST_AUTO_TEST_CASE(fold_check_proves_nets_with_sliver_faces) {
  // A cube with two corners cut off by h: each corner becomes a triangle with sides of h sqrt 2,
  // its neighbours get sides that short and needle triangles. A net folding across such a side
  // used to turn its facet by the side's rounding noise, and a needle's hull, narrower than the
  // hull tolerance, has only two corners: the check could neither place a cone at it nor a plane
  // against it.
  int verified = 0, nets = 0;
  for (double h : {3e-11, 1e-12, 1e-13, 1e-14}) {
    std::vector<Point3> pts;
    for (int i = 0; i < 8; ++i) {
      double c[3] = {double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)};
      bool cut = (c[0] == 1 && c[1] == 1 && c[2] == 1) || (c[0] == 0 && c[1] == 0 && c[2] == 1);
      if (!cut) {
        pts.emplace_back(c[0], c[1], c[2]);
        continue;
      }
      for (int k = 0; k < 3; ++k) {
        double q[3] = {c[0], c[1], c[2]};
        q[k] += q[k] == 1 ? -h : h;
        pts.emplace_back(q[0], q[1], q[2]);
      }
    }
    Mesh mesh = convex_hull_mesh(pts);
    BOOST_TEST_REQUIRE(mesh.number_of_vertices() == 12u);
    for (auto heuristic : {UnfoldHeuristic::steepest, UnfoldHeuristic::flat, UnfoldHeuristic::min_perimeter,
                           UnfoldHeuristic::random}) {
      UnfoldOptions o;
      o.heuristic = heuristic;
      o.fold_candidates = 0;  // the heuristic's own best net, whatever its fold
      UnfoldStats st;
      Net net = unfold_convex_mesh(mesh, o, &st);
      BOOST_TEST(st.result.overlapping_pairs == 0);
      auto r = check_folding(net);
      // What may remain is the cube's own weak point (doc/fold_check.md): a cut edge closing
      // with a symmetric twist, which no plane proves to first order; the uncut cube's random
      // net stops there too, at the same t.
      BOOST_TEST((r.verified || (r.t > 0.9999 && r.message.find("touch in the folded shell") != std::string::npos)),
                 "h " << h << " " << to_string(heuristic) << ": " << r.message);
      verified += r.verified;
      ++nets;
    }
  }
  BOOST_TEST(nets == 16);
  BOOST_TEST(verified >= 13);  // 8 before slivers were handled
}

BOOST_AUTO_TEST_CASE(fold_check_proves_pieces_hinged_through_a_sliver) {
  // The unit square A, a sliver S = (0,0) (0.5,-w) (1,0) folded on A's side y = 0, and a triangle
  // C folded on S's side (0,0)-(0.5,-w): A and C turn about two hinges 2w apart in direction, and
  // their flat pieces touch along y = 0 within w. No two common corners lie on both hinges, and
  // at their one common corner the wedges touch, so neither the line argument nor the cone
  // applied: the check crawled at t = 0 (a shell's nearly straight edge chain with a vertex 1e-11
  // off the line, as trimming used to write, does this). The near-common-line bound proves them;
  // a relative turn past a half turn still collides.
  auto sliver_net = [](double w, double a1, double a2) {
    return planar_net({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, -w, 0}, {0.25, -1, 0}},
                      {{0, 1, 2}, {0, 2, 3}, {0, 4, 1}, {0, 5, 4}}, {-1, 0, 0, 2}, {{0, 2, 0, 1}, {0, 1, 0, 2}, {0, 4, 2, 3}},
                      {0.0, a1, a2});
  };
  for (double w : {1e-10, 1e-11, 1e-3}) {
    Net net = sliver_net(w, 0.5, 0.4);
    BOOST_TEST_REQUIRE(find_net_overlaps(net).empty());
    auto r = check_folding(net);
    BOOST_TEST(r.verified, "w " << w << ": " << r.message);
    BOOST_TEST(r.pieces == 3);
  }
  auto r = check_folding(sliver_net(1e-10, 2.0, 1.5));
  BOOST_TEST(!r.verified);
}

BOOST_AUTO_TEST_CASE(fold_check_proves_every_squirtle_dc_shell_net) {
  // Squirtle's shell 1: sibling pieces touch in the flat net at a corner of their glued chains
  // that lies 1.4e-8 off one hinge line (tolerance 1e-8): not on the hinges, so neither fixed
  // nor separable by a plane to first order, but its two copies never part by more than
  // 0.6 x 1.4e-8 (its distance to each axis is the same in every state). Counted as fixed, the
  // shell's nets verify; before, all 7 but that one did.
  expect_every_dc_shell_net_verified("Squirtle", 7);
}

BOOST_AUTO_TEST_CASE(fold_selection_budget_grows_with_the_shell) {
  // Pikachu's shells 0 (1,290 faces) and 2 (318): the selection's budgets count pieces placed,
  // so at a fixed budget a large net got few steps per check and none of their nets verified;
  // scaled with the faces (up to 3x) every shell's returned net verifies.
  expect_every_dc_shell_net_verified("Pikachu", 7);
}

BOOST_AUTO_TEST_CASE(fold_budget_scales_with_faces_and_saturates) {
  BOOST_TEST(scaled_fold_work(500000, 4) == 500000);     // at least the budget
  BOOST_TEST(scaled_fold_work(500000, 300) == 750000);   // per 200 faces
  BOOST_TEST(scaled_fold_work(500000, 5000) == 1500000); // at most 3x
  const long long huge = std::numeric_limits<long long>::max();
  BOOST_TEST(scaled_fold_work(huge, 1000) > 0);           // saturates, never overflows
  BOOST_TEST(scaled_fold_work(huge, 1000) <= huge);
}

BOOST_AUTO_TEST_CASE(fold_check_second_order_agrees_with_the_first_order_check) {
  // The second-order steps and the early stop at pairs that can never be proved up to t = 1 must
  // give the first-order check's verdict on every net (a wrong bound would verify a net the
  // first-order check cannot, or lose one): constructed flaps (colliding, mid-way collision,
  // free), the Platonic solids, and (shared data) every part-hull net of Yoshi and Donkeykong,
  // whose crawls (Donkeykong hull 9, Yoshi hull 15: thousands of steps) stop early. In total the
  // second-order check takes fewer steps.
  std::vector<std::pair<std::string, Net>> nets = {
      {"crossing flaps", flap_net(-170 * deg, -170 * deg, {-0.8, 0.5}, {1.8, 0.5})},
      {"free flaps", flap_net(-80 * deg, -80 * deg, {-0.8, 0.5}, {1.8, 0.5})},
      {"mid-way flaps", flap_net(-160 * deg, -178 * deg, {-0.9, 0.5}, {1.8, 0.5})}};
  UnfoldOptions o;
  o.fold_candidates = 0;
  for (auto& [name, mesh] : std::vector<std::pair<std::string, Mesh>>{
           {"tetrahedron", tetrahedron()}, {"octahedron", octahedron()}, {"icosahedron", icosahedron()}})
    nets.emplace_back(name, unfold_convex_mesh(mesh, o));
  if (have_shared_data())
    for (const std::string model : {"Yoshi", "Donkeykong"}) {
      std::vector<std::string> warnings;
      auto parts = load_parts({shared_data() + "/composite/" + model}, warnings);
      for (std::size_t i = 0; i < parts.size(); ++i) {
        Mesh h = convex_hull_mesh(parts[i].points);
        if (!h.is_empty()) nets.emplace_back(model + " hull " + std::to_string(i), unfold_convex_mesh(h, o));
      }
    }
  FoldCheckOptions first;
  first.second_order = false;
  long long steps_first = 0, steps_second = 0;
  int verified = 0;
  for (auto& [name, net] : nets) {
    auto a = check_folding(net, first), b = check_folding(net);
    BOOST_TEST(a.verified == b.verified, name << ": " << a.message << " / " << b.message);
    steps_first += a.steps, steps_second += b.steps, verified += b.verified;
  }
  // Not vacuous: the constructed nets alone (no shared data: a fresh clone) verify 3 times.
  BOOST_TEST(verified >= (have_shared_data() ? 4 : 3));
  BOOST_TEST(steps_second < steps_first);
}

// The folding check's broad phase (src/unfold/box_sweep.h) reports exactly the pairs of closed
// boxes CGAL's box_self_intersection_d reports, sorted, also when boxes only touch (equal
// coordinates on a grid), share low x, and move past each other between calls (the sweep keeps
// its order from the previous call). A pair it skipped would never be examined by the check.
BOOST_AUTO_TEST_CASE(fold_check_broad_phase_finds_every_meeting_pair_of_boxes) {
  using Box3 = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;
  unfold_detail::BoxSweep sweep;
  Lcg rng(12345);
  auto next = [&] { return rng.uniform(); };
  const int n = 120;
  std::vector<double> centre(3 * n), half(3 * n), lo(3 * n), hi(3 * n);
  for (int i = 0; i < 3 * n; ++i) centre[i] = std::floor(next() * 20), half[i] = std::floor(next() * 3);
  int touching = 0;
  for (int round = 0; round < 40; ++round) {
    for (int i = 0; i < 3 * n; ++i) {
      if (round > 0) centre[i] += std::floor(next() * 5) - 2;  // boxes overtake each other
      lo[i] = centre[i] - half[i], hi[i] = centre[i] + half[i];  // integers: exact touches
    }
    std::vector<std::pair<int, int>> got, want;
    sweep.pairs(lo, hi, got);
    std::vector<Box3> boxes;
    for (int b = 0; b < n; ++b) boxes.emplace_back(&lo[3 * b], &hi[3 * b], b);
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box3& a, const Box3& b) {
      want.emplace_back(std::min(a.info(), b.info()), std::max(a.info(), b.info()));
    });
    std::sort(want.begin(), want.end());
    BOOST_TEST_REQUIRE((got == want), "round " << round << ": " << got.size() << " pairs, CGAL " << want.size());
    for (auto [p, q] : got)
      for (int d = 0; d < 3; ++d) touching += hi[3 * p + d] == lo[3 * q + d] || hi[3 * q + d] == lo[3 * p + d];
  }
  BOOST_TEST(touching > 0);  // the closed case was exercised
}

namespace {

// The selection stages' tests: ellipsoid hulls of 30-60 points, and options under which only the
// best net is checked (no slack, no fallback, one objective), widened one stage at a time.
Mesh selection_shell(std::uint64_t seed) {
  return ellipsoid_hull(30 + 10 * int(seed % 4), seed, (1.0 + 0.1 * double(seed)) / 3, 0.5 / 3);
}
UnfoldOptions best_net_only() {
  UnfoldOptions o;
  o.fold_slack = 0;
  o.fold_fallback_slack = 0;
  o.fold_other_objective = false;
  return o;
}

}  // namespace

BOOST_AUTO_TEST_CASE(fold_fallback_finds_a_folding_net_beyond_the_slack) {
  // With no slack only the best net is checked; where its straight-line fold collides, the
  // fallback checks nets up to fold_fallback_slack worse and returns one that folds. Where the
  // best net folds, the fallback never runs and the answer is the same net.
  int recovered = 0;
  for (std::uint64_t seed = 1; seed <= 24; ++seed) {
    const Mesh shell = selection_shell(seed);
    const UnfoldOptions strict = best_net_only();
    UnfoldOptions fallback = strict;
    fallback.fold_fallback_slack = 3.0;
    UnfoldStats a, b;
    const Net without = unfold_convex_mesh(shell, strict, &a);
    const Net with = unfold_convex_mesh(shell, fallback, &b);
    BOOST_TEST(!a.fold_fallback);
    BOOST_TEST(b.result.overlapping_pairs == 0);
    if (a.fold.verified) {
      BOOST_TEST(!b.fold_fallback, "seed " << seed);
      BOOST_TEST(b.result.hull_area == a.result.hull_area, "seed " << seed);
      BOOST_TEST((with.corners == without.corners), "seed " << seed);
      continue;
    }
    BOOST_TEST(b.fold.verified, "seed " << seed << ": " << b.fold.message);
    BOOST_TEST(b.fold_fallback, "seed " << seed);
    BOOST_TEST(check_folding(with).verified, "seed " << seed);  // the returned net, checked afresh
    BOOST_TEST(b.result.hull_area <= 4.0 * a.result.hull_area * (1 + 1e-9), "seed " << seed);
    recovered += b.fold.verified;
  }
  BOOST_TEST_MESSAGE(recovered << " of 24 nets recovered by the fallback");
  BOOST_TEST(recovered >= 2);  // the set exercises the fallback at all
}

BOOST_AUTO_TEST_CASE(fold_selection_turns_to_the_other_objective_when_no_net_folds) {
  // With no slack only each objective's best net is checked. Where the hull-area one collides,
  // the cut-length selection runs too and a net of it that folds is returned (checked afresh),
  // marked with its objective; where the hull-area one folds, nothing changes.
  int rescued = 0;
  for (std::uint64_t seed = 1; seed <= 48; ++seed) {
    const Mesh shell = selection_shell(seed);
    const UnfoldOptions one = best_net_only();
    UnfoldOptions both = one;
    both.fold_other_objective = true;
    UnfoldStats a, b;
    const Net without = unfold_convex_mesh(shell, one, &a);
    const Net with = unfold_convex_mesh(shell, both, &b);
    BOOST_TEST((a.objective == UnfoldObjective::hull_area));
    BOOST_TEST(b.first.hull_area == a.first.hull_area, "seed " << seed);  // the same reference
    BOOST_TEST(b.attempts >= a.attempts, "seed " << seed);
    if (a.fold.verified || !b.fold.verified) {
      BOOST_TEST((b.objective == UnfoldObjective::hull_area), "seed " << seed);
      BOOST_TEST((with.corners == without.corners), "seed " << seed);
      continue;
    }
    BOOST_TEST((b.objective == UnfoldObjective::cut_length), "seed " << seed);
    BOOST_TEST(b.fold_checks > a.fold_checks, "seed " << seed);
    BOOST_TEST(check_folding(with).verified, "seed " << seed);
    BOOST_TEST(net_metrics(with).overlapping_pairs == 0, "seed " << seed);
    ++rescued;
  }
  BOOST_TEST_MESSAGE(rescued << " of 48 nets found by the cut-length selection");
  BOOST_TEST(rescued >= 1);  // the set exercises it at all
}

BOOST_AUTO_TEST_CASE(fold_fallback_proves_every_vulpix_dc_shell_net) {
  // Vulpix's shell 9 (366 faces): no net within the 25% slack folds along the straight line;
  // one 1.5x the best hull area does.
  expect_every_dc_shell_net_verified("Vulpix", 12);
}

// The pair slots of large nets (src/unfold/pair_slots.h) behave as a map from (p, q) to a slot:
// a new pair reads -1, a written slot reads back after any later insertions (rows grow in the
// middle), and pairs (p, q) and (q, p) are distinct. A lost or shared slot would classify a pair
// twice or skip it.
BOOST_AUTO_TEST_CASE(fold_check_pair_slots_act_as_a_map) {
  unfold_detail::PairSlots slots;
  std::map<std::pair<int, int>, int> model;
  Lcg rng(987654321);
  auto next = [&](int n) { return static_cast<int>(rng.next() >> 33) % n; };
  const int pieces = 300;
  slots.resize(pieces);
  int inserted = 0;
  for (int k = 0; k < 20000; ++k) {
    const int p = next(pieces), q = next(pieces);
    int& s = slots(p, q);
    auto it = model.find({p, q});
    if (it == model.end()) {
      BOOST_TEST(s == -1);
      s = k;
      model[{p, q}] = k;
      ++inserted;
    } else {
      BOOST_TEST(s == it->second);
    }
  }
  slots.resize(10);  // never shrinks
  for (const auto& [pq, value] : model) BOOST_TEST(slots(pq.first, pq.second) == value);
  BOOST_TEST(inserted > 10000);  // most draws are new pairs: the rows grow in the middle
}

namespace {

// One refinement of the fold selection, off and on, over 16 ellipsoid hulls: where the net
// returned without it verifies, the one returned with it verifies too (checked afresh), scores
// no worse, and is the same net unless it scores better. Returns how many it improved.
int selections_improved(const UnfoldOptions& off, const UnfoldOptions& on) {
  auto score = [&](const UnfoldStats& s) {  // as the selection ranks nets, against the first net
    const double h = s.result.hull_area / s.first.hull_area, c = s.result.cut_length / s.first.cut_length;
    return on.objective == UnfoldObjective::hull_area ? h + 0.01 * c : c + 0.01 * h;
  };
  int improved = 0;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    const Mesh shell = ellipsoid_hull(40 + 10 * int(seed % 3), seed, (1.0 + 0.1 * double(seed)) / 3, 0.5 / 3);
    UnfoldStats a, b;
    const Net plain = unfold_convex_mesh(shell, off, &a);
    const Net refined = unfold_convex_mesh(shell, on, &b);
    BOOST_TEST(b.first.hull_area == a.first.hull_area, "seed " << seed);  // the same reference
    if (!a.fold.verified) continue;
    BOOST_TEST(b.fold.verified, "seed " << seed);
    BOOST_TEST(check_folding(refined).verified, "seed " << seed);
    BOOST_TEST(net_metrics(refined).overlapping_pairs == 0, "seed " << seed);
    BOOST_TEST(score(b) <= score(a), "seed " << seed);
    if (score(b) < score(a))
      ++improved;
    else
      BOOST_TEST((refined.corners == plain.corners), "seed " << seed);
  }
  return improved;
}

}  // namespace

BOOST_AUTO_TEST_CASE(fold_selection_rechecks_better_nets_set_aside_undecided) {
  // With a small first share, good nets run out of it undecided and a worse one verifies first;
  // the re-check of the better ones swaps in one that verifies.
  UnfoldOptions off;
  off.fold_first_work = 4000;
  off.fold_recheck_work = 0;
  UnfoldOptions on = off;
  on.fold_recheck_work = UnfoldOptions{}.fold_recheck_work;
  const int improved = selections_improved(off, on);
  BOOST_TEST_MESSAGE(improved << " of 16 selections improved by the re-check");
  BOOST_TEST(improved >= 1);  // the set exercises the re-check at all
}

BOOST_AUTO_TEST_CASE(fold_selection_tries_fresh_trees_better_than_the_verified_net) {
  // Cut length: where the best nets collide and a worse one verifies, fresh trees that score
  // better than it are checked and one that folds replaces it.
  UnfoldOptions off;
  off.objective = UnfoldObjective::cut_length;
  off.fold_improve_attempts = 0;
  off.fold_descent_work = 0;  // the descent below would improve both
  UnfoldOptions on = off;
  on.fold_improve_attempts = UnfoldOptions{}.fold_improve_attempts;
  const int improved = selections_improved(off, on);
  BOOST_TEST_MESSAGE(improved << " of 16 selections improved by fresh trees");
  BOOST_TEST(improved >= 1);
}

BOOST_AUTO_TEST_CASE(fold_selection_descends_by_edge_swaps_from_the_verified_net) {
  // Cut length: a verified net longer than the best overlap-free one is shortened by edge swaps
  // as long as it stays overlap-free and its folding verifies (checked afresh in the helper).
  UnfoldOptions off;
  off.objective = UnfoldObjective::cut_length;
  off.fold_descent_work = 0;
  UnfoldOptions on = off;
  on.fold_descent_work = UnfoldOptions{}.fold_descent_work;
  const int improved = selections_improved(off, on);
  BOOST_TEST_MESSAGE(improved << " of 16 selections shortened by the descent");
  BOOST_TEST(improved >= 2);
}

BOOST_AUTO_TEST_CASE(fold_check_proves_the_end_once) {
  // With end_proof the end [0.999, 1] is proved on its own and the pass from 0 stops where it
  // begins. That verifies every net the single pass from 0 to 1 (the default) verifies, and a
  // net it verifies beyond those has no crossing in 4,000 sampled states. Such a net is the one
  // returned for Squirtle's DC-shell 1 (its single pass crawls at t = 1 - 1e-9 between two
  // pieces that touch in the folded shell); on the synthetic trees below none occurs.
  int single = 0, split_only = 0, ends_proved = 0;
  auto run = [&](const Net& net) {
    FoldCheckOptions split;
    split.end_proof = 1e-3;
    const auto a = check_folding(net), b = check_folding(net, split);
    single += a.verified;
    BOOST_TEST(!(a.verified && !b.verified), b.message);
    ends_proved += b.end_first_steps > 0;
    if (b.verified && !a.verified) {
      ++split_only;
      BOOST_TEST(!find_sampled_collision(net, 4000, 1e-7).has_value(), a.message);
    }
  };
  for_random_ellipsoid_nets(run);
  for (std::uint64_t seed : {1, 2, 3}) {
    const Mesh m = ellipsoid_hull(150, seed, 0.6, 0.35);
    for (int attempt = 0; attempt < 4; ++attempt) {
      UnfoldOptions o;
      o.heuristic = attempt % 2 ? UnfoldHeuristic::flat : UnfoldHeuristic::steepest;
      o.fold_candidates = 0;
      o.seed = 100 * seed + attempt;
      run(unfold_convex_mesh(m, o));
    }
  }
  BOOST_TEST(single > 0);
  BOOST_TEST(ends_proved > 0);
  if (have_shared_data()) {
    std::vector<std::string> warnings;
    auto parts = load_parts({shared_data() + "/composite/Squirtle"}, warnings);
    ShellResult sr = build_shells(parts, ShellOptions{});
    BOOST_TEST_REQUIRE(sr.shells.size() > 1);
    const int before = split_only;
    run(unfold_convex_mesh(sr.shells[1].mesh));
    BOOST_TEST(split_only == before + 1);
  }
}
