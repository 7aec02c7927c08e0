// Nets of the Platonic solids and the shared convex models: flat, one piece, overlap-free,
// congruent with one orientation, glued only along shell edges; they fold back to the shell.
#include <boost/test/unit_test.hpp>

#include <limits>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include "dcshell/convex_hull.h"
#include "dcshell/error.h"
#include "dcshell/fold_check.h"
#include "dcshell/kernel.h"
#include "dcshell/net_overlap.h"
#include "dcshell/read_mesh.h"
#include "dcshell/unfold.h"
#include "dcshell/unfold_ga.h"
#include "unfold/fold_selection.h"
#include "unfold/unfold_internal.h"
#include "unfold_test_util.h"

using namespace dcshell;
using namespace dcshell::test;

namespace {

// The net as write_net_obj writes it: equal strings are byte-identical outputs.
std::string net_obj(const Net& net) {
  std::ostringstream os;
  write_net_obj(net, os);
  return os.str();
}

// At t = 1 every copy of a shell vertex is back in one place, and the folded net is the shell up
// to a rigid motion (pairwise distances of the shell vertices agree).
void check_folds_back(const Net& net) {
  auto faces = folded_faces(net, 1.0);
  std::map<int, Eigen::Vector3d> where;
  double size = 0;
  for (auto& v : net.shell_vertices) size = std::max(size, v.norm());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      int v = net.shell_faces[f][k];
      auto [it, fresh] = where.emplace(v, faces[f][k]);
      if (!fresh) BOOST_TEST_REQUIRE((it->second - faces[f][k]).norm() < 1e-7 * size);
    }
  for (auto& [a, pa] : where)
    for (auto& [b, pb] : where) {
      double d3 = (net.shell_vertices[a] - net.shell_vertices[b]).norm();
      BOOST_TEST_REQUIRE(std::abs((pa - pb).norm() - d3) < 1e-7 * size);
    }
}

void check_good_net(const Net& net, const std::string& what) {
  BOOST_TEST_CONTEXT(what) {
    auto c = check_net(net);
    BOOST_TEST(c.ok(), c.problem);
    BOOST_TEST(net.corners.size() == net.shell_faces.size());
  }
}

const std::vector<UnfoldHeuristic> kHeuristics = {UnfoldHeuristic::steepest, UnfoldHeuristic::flat,
                                                  UnfoldHeuristic::min_perimeter, UnfoldHeuristic::random,
                                                  UnfoldHeuristic::best};

}  // namespace

BOOST_AUTO_TEST_CASE(platonic_solids_unfold_and_fold_back) {
  std::vector<std::pair<std::string, Mesh>> solids = {{"tetrahedron", tetrahedron()},   {"cube", cube_triangles()},
                                                      {"octahedron", octahedron()},     {"dodecahedron", dodecahedron()},
                                                      {"icosahedron", icosahedron()}};
  for (auto& [name, mesh] : solids)
    for (auto h : kHeuristics) {
      UnfoldOptions o;
      o.heuristic = h;
      UnfoldStats st;
      Net net = unfold_convex_mesh(mesh, o, &st);
      check_good_net(net, name + " " + to_string(h));
      BOOST_TEST(st.convex);
      BOOST_TEST(st.result.overlapping_pairs == 0);
      check_folds_back(net);
      auto fc = check_folding(net);
      BOOST_TEST(fc.verified, name << " " << to_string(h) << ": " << fc.message);
    }
}

BOOST_AUTO_TEST_CASE(coplanar_triangles_are_never_cut_apart) {
  // A unit cube cut along 7 cube edges: cut length 7, and the 6 diagonals are folds of angle 0.
  for (auto h : kHeuristics) {
    UnfoldOptions o;
    o.heuristic = h;
    UnfoldStats st;
    Net net = unfold_convex_mesh(cube_triangles(), o, &st);
    BOOST_TEST(st.facets == 6);
    BOOST_TEST(st.result.cut_length == 7.0, boost::test_tools::tolerance(1e-12));
    int flat_folds = 0;
    for (auto& e : net.edges) flat_folds += e.fold && e.fold_angle == 0;
    BOOST_TEST(flat_folds == 6);
  }
  // Dodecahedron: the pentagons' fan diagonals stay folded; cut tree has 19 polytope edges.
  UnfoldStats st;
  Net net = unfold_convex_mesh(dodecahedron(), {}, &st);
  BOOST_TEST(st.facets == 12);
  int cuts = 0;
  for (auto& e : net.edges) cuts += !e.fold;
  BOOST_TEST(cuts == 19);
}

BOOST_AUTO_TEST_CASE(net_edges_and_angles) {
  Net net = unfold_convex_mesh(octahedron());
  BOOST_TEST(net.edges.size() == 12u);
  const double dihedral = std::acos(-1.0 / 3);  // octahedron interior dihedral
  for (auto& e : net.edges) {
    BOOST_TEST(e.fold_angle == M_PI - dihedral, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(e.mountain);
  }
  int folds = 0;
  for (auto& e : net.edges) folds += e.fold;
  BOOST_TEST(folds == 7);  // spanning tree of 8 faces
}

BOOST_AUTO_TEST_CASE(overlap_test_is_exact_and_allows_touching) {
  using V = Eigen::Vector2d;
  Triangle2 a{V(0, 0), V(1, 0), V(0, 1)};
  BOOST_TEST(!triangle_interiors_overlap(a, {V(1, 0), V(0, 0), V(0, -1)}));  // shared edge
  BOOST_TEST(!triangle_interiors_overlap(a, {V(1, 0), V(2, 0), V(1, 1)}));   // shared vertex
  BOOST_TEST(!triangle_interiors_overlap(a, {V(0.5, 0.5), V(1, 1), V(0, 1)}));  // along part of an edge
  BOOST_TEST(triangle_interiors_overlap(a, {V(0.2, 0.2), V(2, 0.2), V(0.2, 2)}));
  BOOST_TEST(triangle_interiors_overlap(a, a));
  BOOST_TEST(triangle_interiors_overlap(a, {V(0.1, 0.1), V(0.2, 0.1), V(0.1, 0.2)}));  // contained
  BOOST_TEST(triangle_interiors_overlap(a, {V(0.5, -1), V(0.5, 1), V(0.5, 2)}));      // crossing segment
  // Exactness: a vertex 1 ulp across the hypotenuse x + y = 1 overlaps; on it, it does not.
  double x = 0.5, y = std::nextafter(0.5, 0.0);
  BOOST_TEST(!triangle_interiors_overlap(a, {V(0.5, 0.5), V(2, 2), V(2, 0.5)}));
  BOOST_TEST(triangle_interiors_overlap(a, {V(x, y), V(2, 2), V(2, 0.5)}));
}

BOOST_AUTO_TEST_CASE(overlap_test_fast_path_agrees_with_exact_predicates) {
  // The overlap test first looks for an edge line that a floating-point filter proves
  // separating; it must never decide otherwise than the exact separating-axis test. Random
  // triangles sharing corners with each other, with corners on (rounded) points of each other's
  // edge lines and 1 ulp off them: the cases where the filter cannot decide.
  using V = Eigen::Vector2d;
  using P = Epick::Point_2;
  auto exact = [](const Triangle2& ta, const Triangle2& tb) {
    std::array<P, 3> a, b;
    for (int k = 0; k < 3; ++k) a[k] = P(ta[k].x(), ta[k].y()), b[k] = P(tb[k].x(), tb[k].y());
    auto separated = [](const std::array<P, 3>& x, const std::array<P, 3>& y) {
      const auto inner = CGAL::orientation(x[0], x[1], x[2]);
      for (int k = 0; k < 3; ++k) {
        bool out = true;
        for (const P& r : y) out = out && CGAL::orientation(x[k], x[(k + 1) % 3], r) != inner;
        if (out) return true;
      }
      return false;
    };
    return !separated(a, b) && !separated(b, a);
  };
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  auto nudge = [&](double v) { return rng() % 2 ? std::nextafter(v, 2.0) : std::nextafter(v, -2.0); };
  int overlapping = 0, disjoint = 0;
  for (int i = 0; i < 20000; ++i) {
    Triangle2 a{V(u(rng), u(rng)), V(u(rng), u(rng)), V(u(rng), u(rng))};
    Triangle2 b{V(u(rng), u(rng)), V(u(rng), u(rng)), V(u(rng), u(rng))};
    for (int k = 0; k < 3; ++k) {
      switch (rng() % 4) {
        case 0: b[k] = a[rng() % 3]; break;  // a shared corner
        case 1: {                             // on an edge line of a, rounded
          const double w = u(rng) * 2;
          const int e = static_cast<int>(rng() % 3);
          b[k] = a[e] + w * (a[(e + 1) % 3] - a[e]);
          break;
        }
        case 2: b[k] = V(nudge(a[rng() % 3].x()), nudge(a[rng() % 3].y())); break;  // 1 ulp off
        default: break;
      }
    }
    const auto oa = CGAL::orientation(P(a[0].x(), a[0].y()), P(a[1].x(), a[1].y()), P(a[2].x(), a[2].y()));
    const auto ob = CGAL::orientation(P(b[0].x(), b[0].y()), P(b[1].x(), b[1].y()), P(b[2].x(), b[2].y()));
    if (oa == CGAL::COLLINEAR || ob == CGAL::COLLINEAR) continue;  // segments: the fixed cases above
    const bool e = exact(a, b);
    BOOST_TEST(triangle_interiors_overlap(a, b) == e, "case " << i);
    BOOST_TEST(triangle_interiors_overlap(b, a) == e, "case " << i);
    (e ? overlapping : disjoint)++;
  }
  BOOST_TEST(overlapping > 1000);
  BOOST_TEST(disjoint > 1000);
}

BOOST_AUTO_TEST_CASE(hand_made_overlapping_net_is_detected) {
  Net net = unfold_convex_mesh(icosahedron());
  BOOST_TEST_REQUIRE(find_net_overlaps(net).empty());
  // Move the leaf face's free corner onto the middle of the root face: an overlap appears.
  Net bad = net;
  int leaf = -1;
  std::vector<int> children(net.corners.size(), 0);
  for (int p : net.parent)
    if (p >= 0) ++children[p];
  for (int f = 0; f < static_cast<int>(children.size()) && leaf < 0; ++f)
    if (children[f] == 0) leaf = f;
  int other = leaf == 0 ? 1 : 0;
  for (int g = 0; g < static_cast<int>(net.corners.size()); ++g)
    if (g != leaf && net.parent[leaf] != g) other = g;
  Eigen::Vector2d centre = (net.corners[other][0] + net.corners[other][1] + net.corners[other][2]) / 3;
  Eigen::Vector2d shift = centre - (bad.corners[leaf][0] + bad.corners[leaf][1] + bad.corners[leaf][2]) / 3;
  for (auto& p : bad.corners[leaf]) p += shift;
  auto pairs = find_net_overlaps(bad);
  BOOST_TEST_REQUIRE(!pairs.empty());
  bool found = false;
  for (auto& [f, g] : pairs) found |= (f == std::min(leaf, other) && g == std::max(leaf, other));
  BOOST_TEST(found);
  auto c = check_net(bad);
  BOOST_TEST(!c.overlap_free);
  BOOST_TEST(!c.folds_shared);  // the moved face no longer meets its parent along the fold

  // A mirrored face is a defect even if it stays in place.
  Net mirrored = net;
  std::swap(mirrored.corners[leaf][1], mirrored.corners[leaf][2]);
  BOOST_TEST(!check_net(mirrored).oriented);
}

// The folding check has its own suite: test_fold_check.cpp.

BOOST_AUTO_TEST_CASE(net_obj_lists_shell_faces_in_order) {
  Net net = unfold_convex_mesh(cube_triangles());
  std::istringstream is(net_obj(net));
  std::vector<Eigen::Vector2d> v;
  std::vector<std::array<int, 3>> f;
  std::string line;
  while (std::getline(is, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      double x, y, z;
      ls >> x >> y >> z;
      BOOST_TEST(z == 0.0);
      v.emplace_back(x, y);
    } else if (tag == "f") {
      std::array<int, 3> t;
      ls >> t[0] >> t[1] >> t[2];
      f.push_back(t);
    }
  }
  BOOST_TEST_REQUIRE(f.size() == net.corners.size());
  for (std::size_t i = 0; i < f.size(); ++i)
    for (int k = 0; k < 3; ++k) BOOST_TEST((v[f[i][k] - 1] == net.corners[i][k]));  // round trip, exact
  // Folds are shared vertices in the file: 12 triangles, 7 cut cube edges -> 14 net vertices.
  BOOST_TEST(v.size() == 14u);
}

BOOST_AUTO_TEST_CASE(ga_is_reproducible_and_improves_on_the_first_net) {
  UnfoldOptions o;
  o.seed = 7;
  GaOptions ga;
  ga.evaluations = 400;
  UnfoldStats s1, s2;
  Mesh m = icosahedron();
  Net a = unfold_ga(m, o, ga, &s1), b = unfold_ga(m, o, ga, &s2);
  BOOST_TEST(net_obj(a) == net_obj(b));
  BOOST_TEST(s1.result.overlapping_pairs == 0);
  BOOST_TEST(s1.result.hull_area <= s1.first.hull_area);
  check_good_net(a, "ga icosahedron");
}

namespace {

// A 1 x 2 x 3 box as 12 triangles: its minimum-length cut tree is 4 x 1 + 2 x 2 + 1 x 3 = 11.
Mesh box_123() {
  std::vector<std::array<double, 3>> v = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {0, 2, 0}, {0, 0, 3}, {1, 0, 3}, {1, 2, 3}, {0, 2, 3}};
  std::vector<std::vector<int>> quads = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::vector<std::vector<int>> tris;
  for (auto& q : quads) tris.push_back({q[0], q[1], q[2]}), tris.push_back({q[0], q[2], q[3]});
  return make_mesh(v, tris);
}

// Convex hull of n seeded random points on an ellipsoid (axes 1, 1.6, 2.3): irregular facets.
Mesh random_hull(int n, std::uint64_t seed) {
  dcshell::unfold_detail::Rng rng(seed);
  std::vector<Point3> pts;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d d = rng.direction();
    pts.emplace_back(d.x(), 1.6 * d.y(), 2.3 * d.z());
  }
  return convex_hull_mesh(pts);
}

double score_of(const NetMetrics& m, const NetMetrics& first, UnfoldObjective o) {
  return dcshell::unfold_detail::objective_score(m, first, o);
}

}  // namespace

BOOST_AUTO_TEST_CASE(ga_is_never_worse_than_its_seeds_and_reproducible) {
  std::vector<std::pair<std::string, Mesh>> shapes = {{"dodecahedron", dodecahedron()}, {"box", box_123()},
                                                      {"hull40", random_hull(40, 11)}, {"hull90", random_hull(90, 5)}};
  for (auto& [name, mesh] : shapes)
    for (auto obj : {UnfoldObjective::hull_area, UnfoldObjective::cut_length}) {
      BOOST_TEST_CONTEXT(name << " " << to_string(obj)) {
        UnfoldOptions o;
        o.objective = obj;
        o.seed = 3;
        o.fold_candidates = 0;  // compare the searches, not the folding check's choice
        GaOptions ga;
        ga.evaluations = 300;
        UnfoldStats sb, s1, s2;
        unfold_convex_mesh(mesh, o, &sb);
        Net a = unfold_ga(mesh, o, ga, &s1), b = unfold_ga(mesh, o, ga, &s2);
        BOOST_TEST(net_obj(a) == net_obj(b));
        BOOST_TEST(s1.result.overlapping_pairs == 0);
        check_good_net(a, name);
        // Never worse than the default search (its seeds) nor than the first net.
        BOOST_TEST(score_of(s1.result, sb.first, obj) <= score_of(sb.result, sb.first, obj) + 1e-9);
        BOOST_TEST(score_of(s1.result, s1.first, obj) <= score_of(s1.first, s1.first, obj) + 1e-9);
      }
    }
}

BOOST_AUTO_TEST_CASE(facets_stay_flat_on_finely_sampled_curved_sides) {
  using namespace dcshell::unfold_detail;
  // The hulls of 2,000 seeded points on a flat elliptic cylinder and on an elliptic cone: their
  // sides bend by less than the flat angle at many edges, so facets grown across flat edges alone
  // wrap around them, and a facet's chart (a projection on one plane) shrinks its far faces. With
  // the bound unfold uses (normals within 10 flat angles of the facet's first face), every face
  // stays within 20 flat angles of its facet's plane; at flat angle 1e-4 every chart keeps every
  // side to 1e-6 of the size. Without the bound, faces lie far off their facet's plane.
  std::mt19937_64 rng(21);
  auto u = [&](double a, double b) { return a + (b - a) * double(rng() >> 11) * 0x1p-53; };
  const double inf = std::numeric_limits<double>::infinity();
  for (int shape = 0; shape < 2; ++shape) {
    std::vector<Point3> pts;
    for (int i = 0; i < 2000; ++i) {
      const double t = u(0, 2 * M_PI), pick = u(0, 3);
      if (shape == 0) {  // a disc 2 x 0.2 x 0.02: rims and side
        const double z = pick < 1 ? -1 : pick < 2 ? 1 : u(-1, 1);
        pts.emplace_back(std::cos(t), 0.1 * std::sin(t), 0.01 * z);
      } else {  // base 2 x 0.2, height 0.3
        const double h = u(0, 1);
        pts.emplace_back((1 - h) * std::cos(t), 0.1 * (1 - h) * std::sin(t), 0.3 * h);
      }
    }
    const Mesh m = convex_hull_mesh(pts);
    for (double flat : {1e-4, 1e-2}) {
      for (double spread : {10 * flat, inf}) {
        BOOST_TEST_CONTEXT("shape " << shape << " flat " << flat << " spread " << spread) {
          const ShellGraph g = build_shell_graph(m, flat, spread);
          double off_plane = 0, worst = 0;
          for (std::size_t f = 0; f < g.F.size(); ++f) {
            const auto& t = g.F[f];
            const auto& fr = g.facet_frame[g.facet[f]];
            const Eigen::Vector3d d1 = g.V[t[1]] - g.V[t[0]], d2 = g.V[t[2]] - g.V[t[0]], n = d1.cross(d2);
            if (n.norm() > 1e-8 * d1.norm() * d2.norm()) {  // needles' normals are noise
              const Eigen::Vector3d nf = n.normalized(), np = fr[1].cross(fr[2]);
              off_plane = std::max(off_plane, std::atan2(nf.cross(np).norm(), nf.dot(np)));
            }
            for (int k = 0; k < 3; ++k) {
              const double l3 = (g.V[t[(k + 1) % 3]] - g.V[t[k]]).norm(), l2 = (g.chart[f][(k + 1) % 3] - g.chart[f][k]).norm();
              worst = std::max(worst, std::abs(l3 - l2) / g.scale);
            }
          }
          BOOST_TEST_MESSAGE("off plane " << off_plane << " rad, chart error " << worst);
          if (spread < inf) {
            BOOST_CHECK_LE(off_plane, 2 * spread);
            if (flat == 1e-4) BOOST_CHECK_LT(worst, 1e-6);
          } else if (flat == 1e-2) {
            BOOST_CHECK_GT(off_plane, 0.3);  // wrapped: a facet bends by more than 15 degrees
          }
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(cut_length_search_reaches_the_minimum_length_cut_tree) {
  using namespace dcshell::unfold_detail;
  // best and ga with the cut-length objective: the box's minimum cut tree (11), overlap-free.
  for (auto h : {UnfoldHeuristic::best, UnfoldHeuristic::ga}) {
    UnfoldOptions o;
    o.heuristic = h;
    o.objective = UnfoldObjective::cut_length;
    UnfoldStats st;
    Net net = unfold_convex_mesh(box_123(), o, &st);
    check_good_net(net, "box " + to_string(h));
    BOOST_TEST(st.result.cut_length == 11.0, boost::test_tools::tolerance(1e-12));
  }
  // The local search alone (run_ga, population 0), started from the first net only: edge
  // exchanges reach the minimum when no overlap is in the way, and never go below it.
  for (std::uint64_t seed : {11, 12, 13}) {
    Mesh m = random_hull(30, seed);
    ShellGraph g = build_shell_graph(m, 1e-4);
    SearchGraph sg = make_search_graph(g, 1e-4);
    UnfoldOptions o;
    o.objective = UnfoldObjective::cut_length;
    o.heuristic = UnfoldHeuristic::steepest;
    o.tries = 1;
    SearchResult seeds = search_heuristics(g, sg, o, false);
    BOOST_TEST_REQUIRE(seeds.evaluated.size() == 1u);
    BOOST_TEST_REQUIRE(seeds.evaluated[0].metrics.overlapping_pairs == 0);
    Rng rng(1);
    auto mst_folded = folded_groups(g, min_perimeter_weights(g, rng, 0.0));
    NetMetrics mst = decode(g, mst_folded, 1).metrics;
    GaRun run = run_ga(g, sg, o, 1000, 0, seeds);
    BOOST_TEST(run.best.metrics.overlapping_pairs == 0);
    BOOST_TEST(run.best.metrics.cut_length >= mst.cut_length * (1 - 1e-12));
    BOOST_TEST(run.best.metrics.cut_length < seeds.evaluated[0].metrics.cut_length);
    if (mst.overlapping_pairs == 0)
      BOOST_TEST(run.best.metrics.cut_length == mst.cut_length, boost::test_tools::tolerance(1e-9));
    NetMetrics check;
    Net net = finish_net(g, run.best.genome, &check);
    BOOST_TEST(check.overlapping_pairs == 0);
    BOOST_TEST(check.cut_length == run.best.metrics.cut_length, boost::test_tools::tolerance(1e-9));
  }
}

BOOST_AUTO_TEST_CASE(non_convex_and_bad_meshes) {
  // A cube with one corner pushed in: not convex, still unfolded (with a report).
  Mesh dent = cube_triangles();
  for (auto v : dent.vertices())
    if (dent.point(v) == Point3(1, 1, 1)) dent.point(v) = Point3(0.6, 0.6, 0.6);
  UnfoldStats st;
  Net net = unfold_convex_mesh(dent, {}, &st);
  BOOST_TEST(!st.convex);
  BOOST_TEST(st.reflex_edges > 0);
  BOOST_TEST(check_net(net).congruent);
  // Open mesh: refused.
  Mesh open = cube_triangles();
  open.remove_face(*open.faces().begin());
  open.collect_garbage();
  BOOST_CHECK_THROW(unfold_convex_mesh(open), InputError);
}

BOOST_AUTO_TEST_CASE(shared_convex_models) {
  if (!have_shared_data()) {
    BOOST_TEST_MESSAGE("shared data absent: skipped");
    return;
  }
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  for (auto& e : fs::directory_iterator(shared_data() + "/convex"))
    if (e.path().extension() == ".obj") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  int tested = 0;
  for (auto& file : files) {
    Mesh m = read_mesh(file);
    if (m.number_of_faces() > 5000) continue;  // the large ones are in tools/bench_unfold
    UnfoldOptions o;
    o.tries = m.number_of_faces() > 2000 ? 4 : 16;
    UnfoldStats st;
    Net net = unfold_convex_mesh(m, o, &st);
    check_good_net(net, file);
    ++tested;
  }
  BOOST_TEST(tested >= 29);  // all 34 but the 5 above 5,000 faces
}

BOOST_AUTO_TEST_CASE(search_on_coarse_facets_matches_the_fine_shell) {
  // The search decodes trees on one fan per facet; its features must be the fine net's.
  using namespace dcshell::unfold_detail;
  Mesh m = subdivided_cube(5);
  ShellGraph g = build_shell_graph(m, 1e-4);
  SearchGraph sg = make_search_graph(g, 1e-4);
  BOOST_TEST_REQUIRE(sg.use_coarse);
  BOOST_TEST(sg.coarse.F.size() == 12u);
  BOOST_TEST(g.F.size() == 300u);
  Rng rng(3);
  for (int i = 0; i < 20; ++i) {
    auto folded = folded_groups(g, random_weights(g, rng));
    NetMetrics coarse = sg.evaluate(folded), fine = decode(g, folded, 1).metrics;
    BOOST_TEST(std::abs(coarse.cut_length - fine.cut_length) <= 1e-9 * fine.cut_length);
    BOOST_TEST(std::abs(coarse.hull_area - fine.hull_area) <= 1e-9 * fine.hull_area);
    BOOST_TEST(coarse.overlapping_pairs == fine.overlapping_pairs);
  }
  // A shell without subdivided facets is searched as it is.
  ShellGraph ico = build_shell_graph(icosahedron(), 1e-4);
  BOOST_TEST(!make_search_graph(ico, 1e-4).use_coarse);
  UnfoldStats st;
  Net net = unfold_convex_mesh(m, {}, &st);
  check_good_net(net, "subdivided cube");
  BOOST_TEST(st.result.cut_length == 35.0);  // 7 cube edges of length 5
}

BOOST_AUTO_TEST_CASE(first_overlap_search_agrees_with_the_full_one) {
  // The search's trees are decoded with the metrics only and stop at the first overlap: the
  // same features, corners and overlap verdict as the full decode and find_net_overlaps.
  using namespace dcshell::unfold_detail;
  Mesh m = ellipsoid_hull(150, 7, 0.6, 0.3);
  ShellGraph g = build_shell_graph(m, 1e-4);
  Rng rng(11);
  int overlapping = 0, free = 0;
  for (int i = 0; i < 200; ++i) {
    const Genome w = i % 2 ? random_weights(g, rng) : steepest_edge_weights(g, rng.direction());
    const auto folded = folded_groups(g, w);
    const Decoded full = decode(g, folded, 0), quick = decode(g, folded, 1, true);
    const bool overlaps = !find_net_overlaps(full.net).empty();
    BOOST_TEST(any_overlap(full.net.corners) == overlaps, "tree " << i);
    BOOST_TEST(quick.metrics.overlapping_pairs == (overlaps ? 1 : 0), "tree " << i);
    BOOST_TEST(quick.metrics.cut_length == full.metrics.cut_length);
    BOOST_TEST(quick.metrics.hull_area == full.metrics.hull_area);
    BOOST_TEST((quick.net.corners == full.net.corners));
    BOOST_TEST(quick.net.edges.empty());
    (overlaps ? overlapping : free)++;
  }
  BOOST_TEST(overlapping > 20);
  BOOST_TEST(free > 20);
}

BOOST_AUTO_TEST_CASE(fine_pyramid_unfolds_overlap_free) {
  // Thousands of thin faces around an apex: steepest edge from random directions overlaps;
  // toward the apex it is the petal unfolding.
  Mesh m = fine_pyramid(1024, 2.0);
  for (auto h : {UnfoldHeuristic::steepest, UnfoldHeuristic::best}) {
    UnfoldOptions o;
    o.heuristic = h;
    o.fold_candidates = 0;
    UnfoldStats st;
    Net net = unfold_convex_mesh(m, o, &st);
    check_good_net(net, "fine pyramid, " + to_string(h));
  }
}

BOOST_AUTO_TEST_CASE(best_length_swap_is_the_best_exchange_of_the_tree) {
  // Against brute force over every (cut group, folded group) exchange that leaves a spanning tree
  // of the facets: the swap returned has the largest gain, skips the tabu pair, and none is
  // returned when no exchange shortens the cut. shared_parts joins exactly the faces linked by
  // groups folded in both trees: the tree less the group the swap cuts.
  using namespace dcshell::unfold_detail;
  int swaps = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    ShellGraph g = build_shell_graph(ellipsoid_hull(24 + 4 * static_cast<int>(seed), seed, 1.6, 2.3), 1e-4);
    Rng rng(seed);
    auto folded = folded_groups(g, random_weights(g, rng));
    auto spanning = [&](const std::vector<char>& t) {
      UnionFind uf(g.num_facets);
      int joined = 0;
      for (int gi = 0; gi < g.num_groups(); ++gi)
        if (t[gi]) {
          const auto ab = g.group_facets(gi);
          if (!uf.unite(ab[0], ab[1])) return false;  // a cycle
          ++joined;
        }
      return joined == g.num_facets - 1;
    };
    BOOST_TEST_REQUIRE(spanning(folded));
    std::set<std::pair<int, int>> tabu;
    for (int round = 0; round < 2; ++round) {
      double best = 0;
      std::pair<int, int> best_pair{-1, -1};
      for (int c = 0; c < g.num_groups(); ++c)
        for (int f = 0; f < g.num_groups(); ++f) {
          if (folded[c] || !folded[f] || tabu.count({c, f})) continue;
          auto t = folded;
          t[c] = 1, t[f] = 0;
          const double gain = g.group_length[c] - g.group_length[f];
          if (gain > 1e-9 * g.group_length[c] && gain > best && spanning(t)) best = gain, best_pair = {c, f};
        }
      const auto sw = best_length_swap(g, folded, tabu);
      BOOST_TEST(sw.has_value() == (best_pair.first >= 0));
      if (!sw) break;
      BOOST_TEST(std::abs(sw->gain - best) <= 1e-12 * best);
      auto t = folded;
      t[sw->cut] = 1, t[sw->fold] = 0;
      BOOST_TEST(spanning(t));
      // shared_parts of the tree and its swap: the tree less the group the swap cuts, so the
      // facets that group joined lie in two parts and every other fold stays within one.
      const auto part = shared_parts(g, folded, t);
      std::vector<int> facet_part(g.num_facets, -1);
      for (std::size_t f = 0; f < g.F.size(); ++f) {
        if (facet_part[g.facet[f]] < 0) facet_part[g.facet[f]] = part[f];
        BOOST_TEST(facet_part[g.facet[f]] == part[f]);  // one part per facet
      }
      for (int gi = 0; gi < g.num_groups(); ++gi)
        if (folded[gi]) {
          const auto ab = g.group_facets(gi);
          BOOST_TEST((facet_part[ab[0]] == facet_part[ab[1]]) == (gi != sw->fold));
        }
      std::set<int> parts(part.begin(), part.end());
      BOOST_TEST(parts.size() == 2u);  // a spanning tree less one folded group
      ++swaps;
      tabu.insert({sw->cut, sw->fold});
    }
  }
  BOOST_TEST(swaps >= 8);  // random trees of irregular hulls are far from the shortest
}
