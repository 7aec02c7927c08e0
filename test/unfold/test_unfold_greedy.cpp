// Overlap-aware greedy cut trees (unfold_greedy.cpp): spanning trees, one piece, overlap-free
// where no join had to be forced, deterministic; where the minimum-length cut tree overlaps the
// greedy tree is overlap-free, and exactly that tree where it does not.
#include <boost/test/unit_test.hpp>

#include <limits>

#include "dcshell/build_shells.h"
#include "dcshell/convex_hull.h"
#include "dcshell/net_overlap.h"
#include "dcshell/unfold.h"
#include "unfold/unfold_internal.h"
#include "unfold_test_util.h"

using namespace dcshell;
using namespace dcshell::test;
using namespace dcshell::unfold_detail;

namespace {

int folded_count(const std::vector<char>& f) {
  int n = 0;
  for (char c : f) n += c;
  return n;
}

}  // namespace

BOOST_AUTO_TEST_CASE(greedy_trees_are_spanning_one_piece_and_deterministic) {
  std::vector<Mesh> shapes = {tetrahedron(), cube_triangles(), octahedron(), icosahedron(), dodecahedron(),
                              subdivided_cube(4), ellipsoid_hull(60, 3, 1.6, 2.3), ellipsoid_hull(150, 4, 1, 3)};
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    BOOST_TEST_CONTEXT("shape " << i) {
      ShellGraph g = build_shell_graph(shapes[i], 1e-4);
      SearchGraph sg = make_search_graph(g, 1e-4);
      for (int variant = 0; variant < 5; ++variant) {
        Genome w = greedy_weights(g, sg, variant, 1);
        BOOST_TEST_REQUIRE(w.size() == static_cast<std::size_t>(g.num_groups()));
        BOOST_TEST((greedy_weights(g, sg, variant, 1) == w));  // deterministic
        // A spanning tree of the facet graph, reproduced exactly by Kruskal (0 = folded).
        auto folded = folded_groups(g, w);
        BOOST_TEST(folded_count(folded) == g.num_facets - 1);
        for (int gi = 0; gi < g.num_groups(); ++gi) BOOST_TEST((folded[gi] != 0) == (w[gi] == 0.0));
        // One piece; overlap-free by the decoder's exact test, also after the final layout.
        NetMetrics m;
        Net net = finish_net(g, w, &m);
        auto c = check_net(net);
        BOOST_TEST(c.one_piece);
        BOOST_TEST(c.tree);
        BOOST_TEST(c.congruent);
        BOOST_TEST(m.overlapping_pairs == 0);
        if (m.overlapping_pairs == 0) BOOST_TEST(c.ok(), c.problem);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(greedy_repairs_an_overlapping_minimum_length_tree) {
  // Elongated random hulls: find those whose minimum-length cut tree overlaps (the search is
  // deterministic: seeded points). There the longest-fold-first greedy net must be overlap-free,
  // no shorter than that minimum, and shorter than the steepest-edge first net; where the
  // minimum tree does not overlap, the greedy tree is exactly it (no join is ever refused).
  int overlapping = 0, free = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    Mesh m = ellipsoid_hull(120, seed, 1.3, 3.5);
    ShellGraph g = build_shell_graph(m, 1e-4);
    SearchGraph sg = make_search_graph(g, 1e-4);
    Rng rng(1);
    auto mst_folded = folded_groups(g, min_perimeter_weights(g, rng, 0.0));
    NetMetrics mst = decode(g, mst_folded, 1).metrics;
    Genome w = greedy_weights(g, sg, 0, 1);
    BOOST_TEST_REQUIRE(!w.empty());
    auto folded = folded_groups(g, w);
    NetMetrics gm = decode(g, folded, 1).metrics;
    BOOST_TEST_CONTEXT("seed " << seed) {
      BOOST_TEST(gm.overlapping_pairs == 0);
      BOOST_TEST(gm.cut_length >= mst.cut_length * (1 - 1e-12));
      if (mst.overlapping_pairs == 0) {
        ++free;
        BOOST_TEST((folded == mst_folded));
        continue;
      }
      ++overlapping;
      UnfoldOptions o;
      o.heuristic = UnfoldHeuristic::steepest;
      o.tries = 1;
      o.fold_candidates = 0;
      UnfoldStats st;
      unfold_convex_mesh(m, o, &st);
      BOOST_TEST(gm.cut_length < st.result.cut_length);
      // best with the cut-length objective tries the greedy tree, so it is never longer.
      UnfoldOptions b;
      b.objective = UnfoldObjective::cut_length;
      b.fold_candidates = 0;
      UnfoldStats bs;
      unfold_convex_mesh(m, b, &bs);
      BOOST_TEST(bs.result.overlapping_pairs == 0);
      BOOST_TEST(bs.result.cut_length <= gm.cut_length * (1 + 1e-9));
    }
  }
  BOOST_TEST(overlapping >= 1);  // the case this is about does occur
  BOOST_TEST_MESSAGE("minimum-length tree overlapping on " << overlapping << ", overlap-free on " << free);
}

BOOST_AUTO_TEST_CASE(greedy_heuristic_by_name) {
  BOOST_TEST((parse_unfold_heuristic("greedy") == UnfoldHeuristic::greedy));
  BOOST_TEST(to_string(UnfoldHeuristic::greedy) == "greedy");
  UnfoldOptions o;
  o.heuristic = UnfoldHeuristic::greedy;
  o.objective = UnfoldObjective::cut_length;
  UnfoldStats st;
  Net net = unfold_convex_mesh(icosahedron(), o, &st);
  BOOST_TEST(st.heuristic == "greedy");
  BOOST_TEST(check_net(net).ok(), check_net(net).problem);
}

BOOST_AUTO_TEST_CASE(hull_area_search_keeps_the_greedy_trees) {
  // `best` with the hull-area objective evaluates the greedy variants as well, so its best net
  // is never larger than theirs and is overlap-free (on two of these shapes no other tree of the
  // normal budget is); a greedy tree is strictly the smallest on some (else the check would
  // hold without them).
  int greedy_wins = 0;
  for (std::uint64_t seed : {1, 2, 3, 4, 5, 6}) {
    BOOST_TEST_CONTEXT("ellipsoid seed " << seed) {
      Mesh m = ellipsoid_hull(200, seed, 0.6, 0.35);
      ShellGraph g = build_shell_graph(m, 1e-4);
      SearchGraph sg = make_search_graph(g, 1e-4);
      UnfoldOptions o;  // best, hull area
      SearchResult r = search_heuristics(g, sg, o, false);
      BOOST_TEST_REQUIRE(r.best >= 0);
      const NetMetrics& best = r.evaluated[r.best].metrics;
      BOOST_TEST(best.overlapping_pairs == 0);
      double others = std::numeric_limits<double>::infinity(), greedy = others;
      for (const auto& c : r.evaluated)
        if (c.metrics.overlapping_pairs == 0) {
          double& least = c.heuristic == "greedy" ? greedy : others;
          least = std::min(least, c.metrics.hull_area);
        }
      for (int v = 0; v < 4; ++v) {
        NetMetrics gm = sg.evaluate(folded_groups(g, greedy_weights(g, sg, v, o.seed)));
        if (gm.overlapping_pairs == 0) BOOST_TEST(best.hull_area <= gm.hull_area);
      }
      BOOST_TEST(best.hull_area <= others);
      greedy_wins += greedy < others;
    }
  }
  BOOST_TEST(greedy_wins > 0);
}

BOOST_AUTO_TEST_CASE(greedy_trees_spare_a_raised_flat_angle) {
  // Pikachu's largest DC-shell (1,290 faces, many nearly flat facets): no tree of the normal
  // budget is overlap-free at the default flat angle; the greedy trees are, so the net keeps
  // the shell's geometry to rounding instead of merging folds up to 0.01 rad.
  if (!have_shared_data()) {
    BOOST_TEST_MESSAGE("shared data absent: skipped");
    return;
  }
  std::vector<std::string> warnings;
  auto parts = load_parts({shared_data() + "/composite/Pikachu"}, warnings);
  ShellResult sr = build_shells(parts, ShellOptions{});
  BOOST_TEST_REQUIRE(!sr.shells.empty());
  const Mesh* largest = &sr.shells[0].mesh;
  for (const auto& s : sr.shells)
    if (s.mesh.number_of_faces() > largest->number_of_faces()) largest = &s.mesh;
  UnfoldOptions o;
  o.fold_candidates = 0;  // the search's own choice
  UnfoldStats st;
  Net net = unfold_convex_mesh(*largest, o, &st);
  BOOST_TEST(st.flat_angle == o.flat_angle);
  BOOST_TEST(st.result.overlapping_pairs == 0);
  BOOST_TEST(check_net(net).ok(), check_net(net).problem);
}
