// Internals shared by the unfolder, the heuristics and the genetic search: the shell's dual
// graph grouped into facets, and the decoding of per-group weights into a net.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "dcshell/kernel.h"
#include "dcshell/net.h"
#include "dcshell/unfold.h"

namespace dcshell::unfold_detail {

/// The shell as triangles with its edges, facets (regions joined by flat edges) and groups
/// (all edges between the same two facets: a polytope edge, possibly subdivided).
struct ShellGraph {
  std::vector<Eigen::Vector3d> V;
  std::vector<std::array<int, 3>> F;
  std::vector<Net::Edge> edges;               ///< fold = false everywhere here
  std::vector<std::array<int, 3>> face_edge;  ///< edge index of face f's side k (corner k -> k+1)
  std::vector<double> edge_length;
  std::vector<int> facet;                     ///< per face
  int num_facets = 0;
  std::vector<int> edge_group;                ///< per edge; -1 for a flat edge
  std::vector<std::vector<int>> group_edges;  ///< per group, its edges
  std::vector<std::array<int, 2>> group_ends; ///< chain end vertices of each group
  /// Groups ending at vertex v (either end), increasing: end_groups[end_start[v] .. end_start[v + 1]).
  std::vector<int> end_start, end_groups;
  std::vector<double> group_length;
  std::vector<int> flat_edges;
  /// Face corners in their facet's own plane coordinates (projection on the facet's mean plane).
  /// A facet is laid out as one rigid chart: its triangles meet exactly, however much rounding
  /// bends it within flat_angle (developing 256 nearly coplanar triangles one by one would let
  /// rounding open gaps and overlaps inside the facet).
  std::vector<std::array<Eigen::Vector2d, 3>> chart;
  std::vector<std::array<Eigen::Vector3d, 3>> facet_frame;  ///< per facet: origin, u, w (u x w outward)
  bool convex = true;
  int reflex_edges = 0;
  double max_reflex_angle = 0;
  double scale = 1;  ///< bounding-box diagonal

  int num_groups() const { return static_cast<int>(group_edges.size()); }
  /// The two facets group gi joins (an edge of the facet graph).
  std::array<int, 2> group_facets(int gi) const {
    const auto& e = edges[group_edges[gi][0]];
    return {facet[e.f0], facet[e.f1]};
  }
};

/// Disjoint sets of facets or faces (path halving; the smaller index is the root, so the
/// representatives, and everything ordered by them, do not depend on the order of unions).
struct UnionFind {
  std::vector<int> p;
  explicit UnionFind(int n) : p(n) { std::iota(p.begin(), p.end(), 0); }
  int find(int x) {
    while (p[x] != x) x = p[x] = p[p[x]];
    return x;
  }
  bool unite(int a, int b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    p[std::max(a, b)] = std::min(a, b);
    return true;
  }
};

/// Builds the graph from triangles. Throws InputError (message without file name) when the
/// triangles are not a closed oriented 2-manifold of genus 0, or a face is degenerate.
/// Facets grow across edges flat within flat_angle, over faces whose normals lie within
/// facet_spread of the facet's first face's (needles excepted: their normals are noise). Flat
/// edges alone chain around a finely sampled curved surface (a cylinder's or a cone's side bends
/// by less than 1e-4 rad at each edge), and the facet's chart, a projection on one plane, then
/// shrank its far faces (nets 5e-3 of their size off the shell) and mirrored a sliver.
ShellGraph build_shell_graph(std::vector<Eigen::Vector3d> V, std::vector<std::array<int, 3>> F,
                             double flat_angle, double facet_spread = std::numeric_limits<double>::infinity());
ShellGraph build_shell_graph(const Mesh& mesh, double flat_angle,
                             double facet_spread = std::numeric_limits<double>::infinity());

/// A candidate: per-group fold weights. Kruskal folds groups in increasing weight (ties by
/// index) after all flat edges, so the groups with the largest weights are the ones cut.
using Genome = std::vector<double>;

/// Decodes a genome into a net (unnormalised placement) and its features.
/// `first_overlap_only`: stop the overlap search at the first pair (faster; count is 0 or 1).
struct Decoded {
  Net net;
  NetMetrics metrics;
  std::uint64_t tree_hash = 0;  ///< identifies the set of folded groups
};
/// Area of the convex hull of the points (exact-predicate hull, area in doubles).
double hull_area(const std::vector<Epick::Point_2>& pts);
std::vector<char> folded_groups(const ShellGraph& g, const Genome& w);
std::uint64_t tree_hash(const std::vector<char>& folded);
/// `max_overlaps`: stop the overlap search after that many pairs (0 = no overlap search).
/// `metrics_only`: the net gets its corners and parents only (no copy of the shell and edges).
Decoded decode(const ShellGraph& g, const std::vector<char>& folded, std::size_t max_overlaps,
               bool metrics_only = false);

/// What the search and the GA decode their trees on. On a shell whose facets are subdivided (a
/// cube of 76,800 triangles has 6 facets) that is the coarse shell: each facet as a fan of its
/// polytope corners. Groups, cut lengths, hull and overlaps are the same (a convex facet is the
/// union of its triangles) at the cost of the facets, not the triangles; the returned net is
/// still decoded on the fine shell and checked in full.
struct SearchGraph {
  const ShellGraph* fine = nullptr;
  ShellGraph coarse;
  bool use_coarse = false;
  std::vector<int> group_map;  ///< fine group -> coarse group (when use_coarse)
  int faces() const { return static_cast<int>((use_coarse ? coarse : *fine).F.size()); }
  /// Features of the tree `folded` (fine groups); overlapping_pairs is 0 or 1.
  NetMetrics evaluate(const std::vector<char>& folded) const;
};
SearchGraph make_search_graph(const ShellGraph& g, double flat_angle);

/// Directions worth trying first for the direction-based heuristics: away from the largest
/// facets and toward the polytope vertices of highest degree. On a cone or pyramid (thousands
/// of thin faces around an apex) steepest edge toward the apex is the petal unfolding, which
/// never overlaps; random directions almost always do.
std::vector<Eigen::Vector3d> preferred_directions(const ShellGraph& g);

/// Rotates the net so that its minimum-area bounding rectangle is axis-aligned (longer side
/// along x) and moves it to the positive quadrant. Shared corners stay bitwise shared.
void normalise_placement(Net& net);

/// Deterministic random numbers (same bytes on every platform): mt19937_64 and own mappings.
struct Rng {
  std::mt19937_64 gen;
  explicit Rng(std::uint64_t seed) : gen(seed) {}
  double uniform() { return static_cast<double>(gen() >> 11) * 0x1.0p-53; }  // [0,1)
  int below(int n) { return static_cast<int>(uniform() * n); }
  Eigen::Vector3d direction();  ///< uniform on the sphere (rejection from the cube)
};
std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0);

/// Schlickenrieder's heuristics as group weights.
Genome steepest_edge_weights(const ShellGraph& g, const Eigen::Vector3d& c);
Genome flat_tree_weights(const ShellGraph& g, const Eigen::Vector3d& c);
Genome min_perimeter_weights(const ShellGraph& g, Rng& rng, double jitter);
Genome random_weights(const ShellGraph& g, Rng& rng);
/// The tree of heuristic h at retry `attempt`: attempt 0 is a fixed generic direction (the first
/// net does not depend on the seed), then the shell's `preferred` directions, then random ones.
Genome heuristic_genome(const ShellGraph& g, UnfoldHeuristic h, int attempt, std::uint64_t seed,
                        const std::vector<Eigen::Vector3d>& preferred);

/// Overlap-aware greedy cut tree (unfold_greedy.cpp): Kruskal over the groups in a priority
/// order on the search graph, placing pieces rigidly as they are joined and refusing a join
/// whose two pieces would overlap; when only refused joins remain, the smallest piece and its
/// neighbour facets are cut free and rejoined (wider each time), past a budget the smallest
/// piece is joined through its least overlapping group.
/// Always a spanning tree (genome: 0 = folded, 1 = cut; fine groups), overlap-free when no join
/// had to be forced (the decoder's overlap test decides). Variants: 0 longest fold first (a
/// maximum-length spanning tree of folds where nothing overlaps), 1 Blender's default priority
/// (0.5 x fold angle / pi - 0.05 x length / mean length), 2 angle and length alike, >= 3
/// lengths jittered by (variant - 2) x 5% (seeded). Empty when the shell is too large for its
/// work limit (counted in triangle tests, not time). Deterministic.
Genome greedy_weights(const ShellGraph& g, const SearchGraph& sg, int variant, std::uint64_t seed);

/// Scalar fitness to minimise: weighted normalised features; overlapping nets rank after all
/// overlap-free ones, fewer overlaps first.
double objective_score(const NetMetrics& m, const NetMetrics& ref, UnfoldObjective obj);

}  // namespace dcshell::unfold_detail

namespace dcshell::unfold_detail {

/// One evaluated cut tree.
struct Candidate {
  Genome genome;
  NetMetrics metrics;  ///< overlapping_pairs is 0 or 1 (the search stops at the first overlap)
  std::string heuristic;
};

/// Heuristics with retries. `evaluated` holds every distinct tree tried, in trial order;
/// `first` is the first one (steepest edge, first direction) and the normalisation reference.
struct SearchResult {
  std::vector<Candidate> evaluated;
  int best = -1;  ///< index of the best by the objective (overlap-free first), -1 if none tried
  /// Some tree tried is overlap-free (then the best one is: the score ranks them first).
  bool has_overlap_free() const { return best >= 0 && evaluated[best].metrics.overlapping_pairs == 0; }
};
/// `extended`: keep retrying (up to 8x the tries) while no net is overlap-free.
SearchResult search_heuristics(const ShellGraph& g, const SearchGraph& sg, const UnfoldOptions& options, bool extended);

/// Genetic search seeded with the search's candidates; returns the best genome found (the
/// search's best when nothing better turns up) and appends the best score per generation.
struct GaRun {
  Candidate best;
  int evaluations = 0;
  std::vector<double> best_score_per_generation;
};
GaRun run_ga(const ShellGraph& g, const SearchGraph& sg, const UnfoldOptions& options, int evaluations,
             int population, const SearchResult& seeds);

/// The final net of a genome: decoded, normalised, overlaps counted in full.
Net finish_net(const ShellGraph& g, const Genome& genome, NetMetrics* metrics);

}  // namespace dcshell::unfold_detail
