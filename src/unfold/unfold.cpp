// Cut tree -> net: Kruskal on facet groups, placement along the tree, gluing of edges whose two
// sides land on each other, features; the heuristics' weights and the retry search; and the
// unfolder itself: search, ranking, then the fold selection (fold_selection.h).
#include "dcshell/unfold.h"

#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <numeric>
#include <ostream>
#include <stdexcept>
#include <unordered_set>

#include "dcshell/net_overlap.h"
#include "dcshell/unfold_ga.h"
#include "unfold/fold_selection.h"
#include "unfold/unfold_internal.h"

namespace dcshell {

namespace {
const std::vector<std::pair<UnfoldHeuristic, std::string>> kHeuristicNames = {
    {UnfoldHeuristic::best, "best"},
    {UnfoldHeuristic::steepest, "steepest"},
    {UnfoldHeuristic::flat, "flat"},
    {UnfoldHeuristic::min_perimeter, "min-perimeter"},
    {UnfoldHeuristic::random, "random"},
    {UnfoldHeuristic::ga, "ga"},
    {UnfoldHeuristic::greedy, "greedy"}};
}  // namespace

UnfoldHeuristic parse_unfold_heuristic(const std::string& s) {
  for (auto& [h, n] : kHeuristicNames)
    if (n == s) return h;
  throw std::invalid_argument("unknown heuristic '" + s + "' (steepest|flat|min-perimeter|random|greedy|ga|best)");
}
std::string to_string(UnfoldHeuristic h) {
  for (auto& [x, n] : kHeuristicNames)
    if (x == h) return n;
  return "?";
}
UnfoldObjective parse_unfold_objective(const std::string& s) {
  if (s == "hull-area") return UnfoldObjective::hull_area;
  if (s == "cut-length") return UnfoldObjective::cut_length;
  throw std::invalid_argument("unknown objective '" + s + "' (hull-area|cut-length)");
}
std::string to_string(UnfoldObjective o) { return o == UnfoldObjective::hull_area ? "hull-area" : "cut-length"; }

namespace unfold_detail {

namespace {

using Vec2 = Eigen::Vector2d;

std::vector<Epick::Point_2> net_points(const Net& net) {
  std::vector<Epick::Point_2> pts;
  pts.reserve(3 * net.corners.size());
  for (auto& c : net.corners)
    for (auto& p : c) pts.emplace_back(p.x(), p.y());
  return pts;
}

}  // namespace

std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b) {
  // splitmix64 finaliser over the combined words: decorrelated streams per (seed, a, b).
  auto mix = [](std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  return mix(mix(mix(seed) ^ a) ^ (b * 0x632be59bd9b4e019ULL));
}

Eigen::Vector3d Rng::direction() {
  for (;;) {
    Eigen::Vector3d v(2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1);
    double n2 = v.squaredNorm();
    if (n2 > 1e-6 && n2 <= 1) return v / std::sqrt(n2);
  }
}

double hull_area(const std::vector<Epick::Point_2>& pts) {
  std::vector<Epick::Point_2> hull;
  CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull));
  double a = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto &p = hull[i], &q = hull[(i + 1) % hull.size()];
    a += p.x() * q.y() - p.y() * q.x();
  }
  return std::abs(a) / 2;
}

std::vector<char> folded_groups(const ShellGraph& g, const Genome& w) {
  // Increasing weight, ties by index (a stable sort by weight, in one pass over plain pairs).
  thread_local std::vector<std::pair<double, int>> order;
  order.resize(g.num_groups());
  for (int gi = 0; gi < g.num_groups(); ++gi) order[gi] = {w[gi], gi};
  std::sort(order.begin(), order.end());
  UnionFind uf(g.num_facets);
  std::vector<char> folded(g.num_groups(), 0);
  for (const auto& [weight, gi] : order) {
    const auto ab = g.group_facets(gi);
    folded[gi] = uf.unite(ab[0], ab[1]);
  }
  return folded;
}

std::uint64_t tree_hash(const std::vector<char>& folded) {
  std::uint64_t h = 1469598103934665603ULL;
  for (char c : folded) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ULL;
  return h;
}

Decoded decode(const ShellGraph& g, const std::vector<char>& folded, std::size_t max_overlaps, bool metrics_only) {
  const int nf = static_cast<int>(g.F.size());
  const int ne = static_cast<int>(g.edges.size());
  Decoded d;
  d.tree_hash = tree_hash(folded);
  Net& net = d.net;

  // Face tree: flat edges first (every facet becomes a subtree), then the folded groups.
  std::vector<char> in_tree(ne, 0);
  UnionFind uf(nf);
  for (int i : g.flat_edges) in_tree[i] = uf.unite(g.edges[i].f0, g.edges[i].f1);
  for (int gi = 0; gi < g.num_groups(); ++gi)
    if (folded[gi])
      for (int i : g.group_edges[gi]) in_tree[i] = uf.unite(g.edges[i].f0, g.edges[i].f1);

  // Breadth-first placement from face 0. Tree neighbours (face, edge) of face f, in edge order:
  // adj[adj_start[f] .. adj_start[f + 1]).
  std::vector<int> adj_start(nf + 1, 0);
  for (int i = 0; i < ne; ++i)
    if (in_tree[i]) ++adj_start[g.edges[i].f0 + 1], ++adj_start[g.edges[i].f1 + 1];
  for (int f = 0; f < nf; ++f) adj_start[f + 1] += adj_start[f];
  std::vector<std::pair<int, int>> adj(adj_start[nf]);
  {
    std::vector<int> fill(adj_start.begin(), adj_start.end() - 1);
    for (int i = 0; i < ne; ++i)
      if (in_tree[i]) {
        adj[fill[g.edges[i].f0]++] = {g.edges[i].f1, i};
        adj[fill[g.edges[i].f1]++] = {g.edges[i].f0, i};
      }
  }
  // Each facet is placed as one rigid copy of its chart; the transform of a facet is fixed by
  // the tree edge through which the breadth-first search enters it (rotation only: charts are
  // all counter-clockwise, so nothing is mirrored).
  std::vector<std::array<Vec2, 3>> P(nf);
  std::vector<Eigen::Matrix2d> R(g.num_facets);
  std::vector<Vec2> T(g.num_facets);
  std::vector<char> placed_facet(g.num_facets, 0);
  auto place_face = [&](int f) {
    int k = g.facet[f];
    for (int j = 0; j < 3; ++j) P[f][j] = R[k] * g.chart[f][j] + T[k];
  };
  std::vector<int> rank(nf, -1);
  net.parent.assign(nf, -1);
  std::vector<int> order;
  order.reserve(nf);
  R[g.facet[0]].setIdentity();
  T[g.facet[0]].setZero();
  placed_facet[g.facet[0]] = 1;
  place_face(0);
  rank[0] = 0;
  order.push_back(0);
  for (std::size_t qi = 0; qi < order.size(); ++qi) {
    int p = order[qi];
    for (int a = adj_start[p]; a < adj_start[p + 1]; ++a) {
      const auto [f, ei] = adj[a];
      if (rank[f] >= 0) continue;
      rank[f] = static_cast<int>(order.size());
      order.push_back(f);
      net.parent[f] = p;
      int k = g.facet[f];
      if (!placed_facet[k]) {
        // Map the shared edge's ends, as the chart of f has them, onto their places in p.
        int j = 0;
        while (g.face_edge[f][j] != ei) ++j;
        int a = g.F[f][j], b = g.F[f][(j + 1) % 3];
        auto pos_in_parent = [&](int v) {
          for (int i = 0; i < 3; ++i)
            if (g.F[p][i] == v) return P[p][i];
          return Vec2(0, 0);
        };
        // The edge's direction from its 3D vector (exact for nearby doubles), not from the
        // difference of two chart positions: those carry absolute rounding, which on a 1e-11
        // sliver side would turn the whole facet by 1e-4 rad.
        const Eigen::Vector3d ab = g.V[b] - g.V[a];
        const auto& fp = g.facet_frame[g.facet[p]];
        const auto& fk = g.facet_frame[k];
        Vec2 pa = pos_in_parent(a), dp = R[g.facet[p]] * Vec2(ab.dot(fp[1]), ab.dot(fp[2]));
        Vec2 qa = g.chart[f][j], dq(ab.dot(fk[1]), ab.dot(fk[2]));
        double c = dq.dot(dp), s = dq.x() * dp.y() - dq.y() * dp.x(), n = std::hypot(c, s);
        c /= n, s /= n;
        R[k] << c, -s, s, c;
        T[k] = pa - R[k] * qa;
        placed_facet[k] = 1;
      }
      place_face(f);
    }
  }

  // Glue: a non-tree edge that is flat, or a sibling of a folded group's tree edge, folds too
  // when its two sides land on each other (they do exactly, up to rounding, on a convex shell).
  auto corner = [&](int f, int v) {
    int k = 0;
    while (g.F[f][k] != v) ++k;
    return k;
  };
  std::vector<char> fold(in_tree);
  for (int i = 0; i < ne; ++i) {
    const auto& e = g.edges[i];
    if (in_tree[i]) continue;
    int gi = g.edge_group[i];
    if (gi >= 0 && !folded[gi]) continue;
    // The other segments of a folded polytope edge meet only as well as the file's rounding
    // keeps its subdivision points on the edge line (pyramid2, 6 decimals: 1e-6 apart); merging
    // them moves a corner by at most 1e-5 of the model size, invisible on paper.
    double tol = gi >= 0 ? std::max(1e-7 * g.edge_length[i], 1e-5 * g.scale) : 1e-7 * g.edge_length[i];
    fold[i] = (P[e.f0][corner(e.f0, e.v0)] - P[e.f1][corner(e.f1, e.v0)]).norm() <= tol &&
              (P[e.f0][corner(e.f0, e.v1)] - P[e.f1][corner(e.f1, e.v1)]).norm() <= tol;
  }

  // Net vertices: corners joined across folds share one position (the earliest placed), so
  // faces meeting along a fold touch exactly in the overlap test and in the written OBJ.
  UnionFind cu(3 * nf);
  for (int i = 0; i < ne; ++i) {
    const auto& e = g.edges[i];
    if (!fold[i]) continue;
    for (int v : {e.v0, e.v1}) cu.unite(3 * e.f0 + corner(e.f0, v), 3 * e.f1 + corner(e.f1, v));
  }
  std::vector<int> best(3 * nf, -1);
  // The net's distinct points, one per set of joined corners: its hull is that of all corners
  // (the others repeat them), from about a third of the points.
  std::vector<Epick::Point_2> points;
  for (int f : order)
    for (int k = 0; k < 3; ++k) {
      int r = cu.find(3 * f + k);
      if (best[r] < 0) best[r] = 3 * f + k, points.emplace_back(P[f][k].x(), P[f][k].y());
    }
  net.corners.resize(nf);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      int src = best[cu.find(3 * f + k)];
      net.corners[f][k] = P[src / 3][src % 3];
    }

  for (int i = 0; i < ne; ++i)
    if (!fold[i]) d.metrics.cut_length += g.edge_length[i];
  d.metrics.hull_area = hull_area(points);
  if (max_overlaps == 1)
    d.metrics.overlapping_pairs = any_overlap(net.corners) ? 1 : 0;
  else if (max_overlaps > 0)
    d.metrics.overlapping_pairs = static_cast<int>(find_net_overlaps(net, max_overlaps).size());
  if (!metrics_only) {
    net.shell_vertices = g.V;
    net.shell_faces = g.F;
    net.edges = g.edges;
    for (int i = 0; i < ne; ++i) net.edges[i].fold = fold[i];
  }
  return d;
}

void normalise_placement(Net& net) {
  std::vector<Epick::Point_2> hull;
  auto pts = net_points(net);
  CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull));
  if (hull.size() < 3) return;
  // Minimum-area bounding rectangle: one side lies along a hull edge.
  double best_area = std::numeric_limits<double>::infinity();
  Eigen::Vector2d best_dir(1, 0);
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto &p = hull[i], &q = hull[(i + 1) % hull.size()];
    Eigen::Vector2d u(q.x() - p.x(), q.y() - p.y());
    if (u.norm() == 0) continue;
    u.normalize();
    double lo_u = 1e300, hi_u = -1e300, lo_v = 1e300, hi_v = -1e300;
    for (auto& h : hull) {
      double a = u.x() * h.x() + u.y() * h.y(), b = -u.y() * h.x() + u.x() * h.y();
      lo_u = std::min(lo_u, a), hi_u = std::max(hi_u, a), lo_v = std::min(lo_v, b), hi_v = std::max(hi_v, b);
    }
    double area = (hi_u - lo_u) * (hi_v - lo_v);
    if (area < best_area * (1 - 1e-12)) {
      best_area = area;
      best_dir = (hi_u - lo_u >= hi_v - lo_v) ? u : Eigen::Vector2d(-u.y(), u.x());
    }
  }
  Eigen::Matrix2d R;
  R << best_dir.x(), best_dir.y(), -best_dir.y(), best_dir.x();
  Eigen::Vector2d lo(1e300, 1e300);
  for (auto& c : net.corners)
    for (auto& p : c) {
      p = R * p;
      lo = lo.cwiseMin(p);
    }
  for (auto& c : net.corners)
    for (auto& p : c) p -= lo;
}

// ---- heuristics as group weights ----

namespace {
double steepness(const ShellGraph& g, int gi, const Eigen::Vector3d& c) {
  Eigen::Vector3d d = g.V[g.group_ends[gi][1]] - g.V[g.group_ends[gi][0]];
  double n = d.norm();
  return n > 0 ? std::abs(c.dot(d)) / n : 0.0;
}
}  // namespace

Genome steepest_edge_weights(const ShellGraph& g, const Eigen::Vector3d& c) {
  // Steepest edge cut: every polytope vertex but the highest in direction c cuts along its
  // steepest ascending polytope edge. Those cuts form a spanning tree of the vertices; giving
  // them the largest weights makes Kruskal fold everything else.
  Genome w(g.num_groups());
  for (int gi = 0; gi < g.num_groups(); ++gi) w[gi] = steepness(g, gi, c);
  auto higher = [&](int u, int v) {  // u above v, ties broken by index (generic direction)
    double hu = c.dot(g.V[u]), hv = c.dot(g.V[v]);
    return hu > hv || (hu == hv && u > v);
  };
  for (int v = 0; v + 1 < static_cast<int>(g.end_start.size()); ++v) {
    int pick = -1;
    double best = -1;
    for (int k = g.end_start[v]; k < g.end_start[v + 1]; ++k) {
      const int gi = g.end_groups[k];
      int u = g.group_ends[gi][0] == v ? g.group_ends[gi][1] : g.group_ends[gi][0];
      if (!higher(u, v)) continue;
      double s = c.dot(g.V[u] - g.V[v]) / (g.V[u] - g.V[v]).norm();
      if (s > best) best = s, pick = gi;
    }
    if (pick >= 0) w[pick] = 2;
  }
  return w;
}

Genome flat_tree_weights(const ShellGraph& g, const Eigen::Vector3d& c) {
  // Flat spanning tree: the cut tree is the minimum spanning tree of the polytope edges
  // weighted by steepness, i.e. cuts run as level as possible; Kruskal folds the steep ones.
  Genome w(g.num_groups());
  for (int gi = 0; gi < g.num_groups(); ++gi) w[gi] = -steepness(g, gi, c);
  return w;
}

Genome min_perimeter_weights(const ShellGraph& g, Rng& rng, double jitter) {
  // Minimum perimeter: the cut tree is a minimum spanning tree by length (long edges fold).
  // Jitter and a random tie-break give other trees of about the same length on retries.
  Genome w(g.num_groups());
  for (int gi = 0; gi < g.num_groups(); ++gi)
    w[gi] = -g.group_length[gi] * (1 + jitter * (rng.uniform() - 0.5) + 1e-9 * rng.uniform());
  return w;
}

Genome random_weights(const ShellGraph& g, Rng& rng) {
  Genome w(g.num_groups());
  for (auto& x : w) x = rng.uniform();
  return w;
}

double objective_score(const NetMetrics& m, const NetMetrics& ref, UnfoldObjective obj) {
  double h = m.hull_area / std::max(ref.hull_area, 1e-300), c = m.cut_length / std::max(ref.cut_length, 1e-300);
  double s = obj == UnfoldObjective::hull_area ? h + 0.01 * c : c + 0.01 * h;
  return m.overlapping_pairs == 0 ? s : 1e6 + m.overlapping_pairs + s;
}

// ---- search ----

Genome heuristic_genome(const ShellGraph& g, UnfoldHeuristic h, int attempt, std::uint64_t seed,
                        const std::vector<Eigen::Vector3d>& preferred) {
  Rng rng(mix_seed(seed, static_cast<std::uint64_t>(h), static_cast<std::uint64_t>(attempt)));
  // The first direction is a fixed generic one, so the first net does not depend on the seed;
  // then the shell's preferred directions, then random ones.
  Eigen::Vector3d c = attempt == 0 ? Eigen::Vector3d(0.2137, 0.5318, 0.8193).normalized()
                      : attempt <= static_cast<int>(preferred.size()) ? preferred[attempt - 1]
                                                                      : rng.direction();
  switch (h) {
    case UnfoldHeuristic::steepest: return steepest_edge_weights(g, c);
    case UnfoldHeuristic::flat: return flat_tree_weights(g, c);
    case UnfoldHeuristic::min_perimeter:
      return attempt == 0 ? min_perimeter_weights(g, rng, 0.0) : min_perimeter_weights(g, rng, 0.05 * attempt);
    default: return random_weights(g, rng);
  }
}

namespace {

// Default effort: a cut tree costs about 8 + faces units (a fixed part, then linear), and the
// default spends about 100 units per heuristic: a few trees for a small shell, one per heuristic
// from 100 faces on (the retries continue until a net is overlap-free). That keeps the default
// at about a millisecond per shell of a composite model; --tries or the GA search further.
// Greedy variants `best` tries (greedy_weights).
constexpr int kGreedyVariants = 4;
// Up to this size (search-graph faces) every greedy variant is tried for the hull-area objective
// too: a few milliseconds each there (ball_large, 19,800 faces: ~70 ms each, for no gain).
constexpr int kGreedyAllFaces = 5000;

int automatic_tries(int faces) { return std::clamp(100 / (8 + std::max(faces, 1)), 1, 64); }

}  // namespace

SearchResult search_heuristics(const ShellGraph& g, const SearchGraph& sg, const UnfoldOptions& options, bool extended) {
  std::vector<UnfoldHeuristic> hs;
  bool all = options.heuristic == UnfoldHeuristic::best || options.heuristic == UnfoldHeuristic::ga;
  if (all)
    hs = {UnfoldHeuristic::steepest, UnfoldHeuristic::min_perimeter, UnfoldHeuristic::flat, UnfoldHeuristic::random};
  else
    hs = {options.heuristic};
  const int tries = options.tries > 0 ? options.tries : automatic_tries(sg.faces());
  const auto preferred = preferred_directions(g);
  // Extended: retries go on (up to 8x, at least through the preferred directions) until a net
  // is overlap-free.
  const int max_tries = extended ? std::max(8 * tries, std::clamp(20000 / (8 + sg.faces()), 16, 64)) : tries;

  // Cut-length objective: the minimum-length cut tree (min-perimeter, attempt 0) and then its
  // perturbations (jittered lengths) until one is overlap-free, even when another heuristic's
  // net already is (up to the extended retry count).
  const bool cut_first = all && options.objective == UnfoldObjective::cut_length;
  const int mst_tries = cut_first ? std::clamp(20000 / (8 + sg.faces()), 16, 64) : 0;
  bool mst_free = false;

  SearchResult r;
  std::unordered_set<std::uint64_t> seen;
  double best_score = std::numeric_limits<double>::infinity();
  for (int attempt = 0; attempt < std::max(max_tries, mst_tries); ++attempt) {
    bool more = attempt < max_tries && !(attempt >= tries && r.has_overlap_free());
    bool more_mst = cut_first && !mst_free && attempt < mst_tries;
    if (!more && !more_mst) break;
    for (auto h : hs) {
      if (!more && h != UnfoldHeuristic::min_perimeter) continue;
      Genome w = h == UnfoldHeuristic::greedy ? greedy_weights(g, sg, attempt, options.seed)
                                              : heuristic_genome(g, h, attempt, options.seed, preferred);
      if (w.empty()) w = heuristic_genome(g, UnfoldHeuristic::min_perimeter, attempt, options.seed, preferred);  // greedy: beyond its work limit
      auto folded = folded_groups(g, w);
      if (!seen.insert(tree_hash(folded)).second) continue;
      NetMetrics m = sg.evaluate(folded);
      mst_free |= h == UnfoldHeuristic::min_perimeter && m.overlapping_pairs == 0;
      r.evaluated.push_back({std::move(w), m, to_string(h)});
      double s = objective_score(m, r.evaluated.front().metrics, options.objective);
      if (s < best_score) best_score = s, r.best = static_cast<int>(r.evaluated.size()) - 1;
    }
  }
  // Cut-length objective: the overlap-aware greedy trees too (longest fold first, Blender's
  // priority, angle and length, jittered lengths); they refuse the folds that overlap instead
  // of throwing the whole tree away. After the others: the first net stays the reference.
  // Hull-area objective too: they make compact nets (on the 69 inputs 5% smaller hulls
  // than the other heuristics' best, on average), and where the normal budget found no
  // overlap-free tree they usually are one, before the caller raises the flat angle or
  // retries at length. Above kGreedyAllFaces only the first variant, unless nothing is free.
  int greedy_variants = 0;
  if (cut_first || (all && !extended && (!r.has_overlap_free() || sg.faces() <= kGreedyAllFaces)))
    greedy_variants = kGreedyVariants;
  else if (all && !extended)
    greedy_variants = 1;
  for (int v = 0; v < greedy_variants && !r.evaluated.empty(); ++v) {
    Genome w = greedy_weights(g, sg, v, options.seed);
    if (w.empty()) break;
    auto folded = folded_groups(g, w);
    if (!seen.insert(tree_hash(folded)).second) continue;
    NetMetrics m = sg.evaluate(folded);
    r.evaluated.push_back({std::move(w), m, to_string(UnfoldHeuristic::greedy)});
    double s = objective_score(m, r.evaluated.front().metrics, options.objective);
    if (s < best_score) best_score = s, r.best = static_cast<int>(r.evaluated.size()) - 1;
  }
  return r;
}

Net finish_net(const ShellGraph& g, const Genome& genome, NetMetrics* metrics) {
  Decoded d = decode(g, folded_groups(g, genome), 0);
  Net placed = d.net;
  normalise_placement(d.net);
  NetMetrics m = d.metrics;
  m.overlapping_pairs = static_cast<int>(find_net_overlaps(d.net).size());
  // Rotation rounds coordinates; keep the unrotated net in the (unseen so far) case where that
  // rounding alone creates an overlap.
  if (m.overlapping_pairs > 0) {
    int unrotated = static_cast<int>(find_net_overlaps(placed).size());
    if (unrotated < m.overlapping_pairs) {
      d.net = std::move(placed);
      m.overlapping_pairs = unrotated;
    }
  }
  if (metrics) *metrics = m;
  return std::move(d.net);
}

}  // namespace unfold_detail

using namespace unfold_detail;

namespace {

Net unfold_impl(const Mesh& mesh, const UnfoldOptions& options, const GaOptions* ga, UnfoldStats* stats,
                std::vector<double>* ga_history) {
  auto t0 = std::chrono::steady_clock::now();
  // A facet's normals stay within 10 flat angles of its first face's: its chart keeps lengths
  // to about half the square of that (5e-7 relative at 1e-4 rad), also at the wider flat angles
  // below, where a curved side would otherwise wrap into one chart.
  ShellGraph g = build_shell_graph(mesh, options.flat_angle, 10 * options.flat_angle);
  UnfoldStats st;
  st.faces = static_cast<int>(g.F.size());
  st.facets = g.num_facets;
  st.convex = g.convex;
  st.reflex_edges = g.reflex_edges;
  st.max_reflex_angle = g.max_reflex_angle;

  // A shell bent slightly everywhere (cone2: hundreds of folds of 1e-4 to 1e-3 rad) may have no
  // overlap-free net while those folds count as edges: cutting one leaves a sliver overlap. Then
  // folds up to 10x, 100x the flat angle (at most 0.01 rad) are merged into facets as well; a
  // facet is laid out as one chart, so net lengths then differ from the shell's by about the
  // square of the largest angle merged (reported as stats.flat_angle).
  // First the normal budget at each flat angle in turn, then the extended retries at each.
  std::vector<double> flats = {options.flat_angle};
  while (flats.back() > 0 && flats.back() * 10 <= 0.01 * (1 + 1e-9)) flats.push_back(flats.back() * 10);
  double flat = options.flat_angle;
  SearchGraph sg = make_search_graph(g, flat);
  SearchResult search = search_heuristics(g, sg, options, false);
  for (std::size_t round = 0, i = 1; !search.has_overlap_free() && round < 2; ++i) {
    if (i == flats.size()) i = 0, ++round;
    if (round == 2) break;
    if (flats[i] != flat) {
      flat = flats[i];
      g = build_shell_graph(mesh, flat, 10 * flat);
      sg = make_search_graph(g, flat);
    }
    search = search_heuristics(g, sg, options, round == 1);
  }
  st.facets = g.num_facets;
  st.flat_angle = flat;
  st.attempts = static_cast<int>(search.evaluated.size());
  const NetMetrics& ref = search.evaluated.front().metrics;
  // Candidates in score order: the GA's best (when run), then the heuristics' nets.
  std::vector<Candidate> ranked;
  if (ga) {
    int pop = std::max(4, ga->population);
    int evals = ga->evaluations > 0 ? ga->evaluations
                                    : std::clamp(2000000 / std::max(sg.faces(), 1), 100, 2000);
    GaRun run = run_ga(g, sg, options, evals, pop, search);
    st.attempts += run.evaluations;
    if (ga_history) *ga_history = run.best_score_per_generation;
    ranked.push_back(run.best);
  } else if (options.heuristic == UnfoldHeuristic::best && options.objective == UnfoldObjective::cut_length &&
             search.has_overlap_free()) {
    // The minimum-length cut tree is among the first trees tried (min-perimeter, attempt 0);
    // when it overlaps, edge exchanges from the best net (run_ga with population 0: local
    // search only, a few evaluations) get as close to it as overlaps allow.
    GaRun run = run_ga(g, sg, options, 16, 0, search);
    st.attempts += run.evaluations;
    if (objective_score(run.best.metrics, ref, options.objective) <
        objective_score(search.evaluated[search.best].metrics, ref, options.objective))
      ranked.push_back(run.best);
  }
  {
    std::vector<int> idx(search.evaluated.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::stable_sort(idx.begin(), idx.end(), [&](int a, int b) {
      return objective_score(search.evaluated[a].metrics, ref, options.objective) <
             objective_score(search.evaluated[b].metrics, ref, options.objective);
    });
    for (int i : idx) ranked.push_back(search.evaluated[i]);
  }
  st.first = ref;
  // Fold selection (fold_selection.h): the first overlap-free net whose folding path verifies,
  // else the best one. Shells above 5,000 faces take the best net unchecked.
  const int checks = options.fold_candidates <= 0 ? 0 : g.F.size() > 5000 ? 0 : options.fold_candidates;
  Net net;
  bool have = false;
  if (checks > 0) {
    FoldSelection selection(g, sg, options, ranked, search.evaluated, ref, st);
    if ((have = selection.run(checks))) net = std::move(selection.net());
  }
  if (!have) {
    net = finish_net(g, ranked.front().genome, &st.result);
    st.heuristic = ranked.front().heuristic;
  }
  st.objective = options.objective;
  // No net verified: the other objective ranks other trees first (cut length also searches its
  // own: the minimum-length tree, its jitters, every greedy variant), so its selection is run
  // too, and a net of it that verifies (or, when none here is overlap-free, that is) is
  // returned. Only these shells pay: four radius-1e-3 spheres at 1e9 had a 336-face shell whose
  // hull-area selection verified none of 70 nets, where the cut-length one verifies.
  if (checks > 0 && !st.fold.verified && options.fold_other_objective &&
      (options.heuristic == UnfoldHeuristic::best || options.heuristic == UnfoldHeuristic::ga)) {
    UnfoldOptions other = options;
    other.heuristic = UnfoldHeuristic::best;
    other.objective = options.objective == UnfoldObjective::hull_area ? UnfoldObjective::cut_length
                                                                         : UnfoldObjective::hull_area;
    other.fold_other_objective = false;
    // A net that folds is what is missing, not a shorter one: no descent or improvement stage.
    other.fold_descent_work = 0, other.fold_improve_attempts = 0;
    UnfoldStats ost;
    Net onet = unfold_impl(mesh, other, nullptr, &ost, nullptr);
    const bool better = ost.fold.verified || (st.result.overlapping_pairs > 0 && ost.result.overlapping_pairs == 0);
    const int attempts = st.attempts + ost.attempts, fold_checks = st.fold_checks + ost.fold_checks;
    if (better) {
      const NetMetrics first = st.first;  // the reference stays this search's first net
      net = std::move(onet), st = ost, st.first = first;
    }
    st.attempts = attempts, st.fold_checks = fold_checks;
  }
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (stats) *stats = st;
  return net;
}

}  // namespace

Net unfold_convex_mesh(const Mesh& mesh, const UnfoldOptions& options, UnfoldStats* stats) {
  if (options.heuristic == UnfoldHeuristic::ga) {
    GaOptions ga;
    return unfold_impl(mesh, options, &ga, stats, nullptr);
  }
  return unfold_impl(mesh, options, nullptr, stats, nullptr);
}

Net unfold_ga(const Mesh& mesh, const UnfoldOptions& options, const GaOptions& ga, UnfoldStats* stats,
              std::vector<double>* history) {
  UnfoldOptions o = options;
  o.heuristic = UnfoldHeuristic::ga;
  return unfold_impl(mesh, o, &ga, stats, history);
}

long long scaled_fold_work(long long work, std::size_t faces) {
  const double scaled = static_cast<double>(work) * std::clamp(static_cast<double>(faces) / 200.0, 1.0, 3.0);
  constexpr double cap = 0x1p62;  // below LLONG_MAX, exactly representable
  return scaled >= cap ? static_cast<long long>(cap) : static_cast<long long>(scaled);
}

NetMetrics net_metrics(const Net& net) {
  NetMetrics m;
  for (const auto& e : net.edges)
    if (!e.fold) m.cut_length += (net.shell_vertices[e.v1] - net.shell_vertices[e.v0]).norm();
  m.hull_area = hull_area(net_points(net));
  m.overlapping_pairs = static_cast<int>(find_net_overlaps(net).size());
  return m;
}

void write_net_obj(const Net& net, std::ostream& out) {
  // Net vertices: corners with the same shell vertex at bitwise the same point are one vertex.
  std::map<std::tuple<int, double, double>, int> index;
  std::vector<Eigen::Vector2d> verts;
  std::vector<std::array<int, 3>> faces(net.corners.size());
  for (std::size_t f = 0; f < net.corners.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto& p = net.corners[f][k];
      auto [it, fresh] = index.emplace(std::make_tuple(net.shell_faces[f][k], p.x(), p.y()), static_cast<int>(verts.size()));
      if (fresh) verts.push_back(p);
      faces[f][k] = it->second;
    }
  out << "# dcshell net" << (net.name.empty() ? "" : " " + net.name) << ": " << faces.size()
      << " faces in shell order, corners in shell order, z = 0\n";
  out << std::setprecision(17);
  for (auto& v : verts) out << "v " << v.x() << " " << v.y() << " 0\n";
  for (auto& f : faces) out << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
}

}  // namespace dcshell
