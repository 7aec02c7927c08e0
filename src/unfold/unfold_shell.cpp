// The shell's dual graph: edges with signed fold angles, facets (regions joined by flat edges)
// and groups of edges between two facets.
#include <CGAL/Kernel/global_functions.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>

#include "dcshell/error.h"
#include "unfold/unfold_internal.h"

namespace dcshell::unfold_detail {

namespace {

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

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

Point3 cgal_point(const Eigen::Vector3d& p) { return Point3(p.x(), p.y(), p.z()); }

}  // namespace

ShellGraph build_shell_graph(std::vector<Eigen::Vector3d> V, std::vector<std::array<int, 3>> F,
                             double flat_angle) {
  ShellGraph g;
  g.V = std::move(V);
  g.F = std::move(F);
  const int nf = static_cast<int>(g.F.size());
  if (nf < 4) throw InputError("a closed shell needs at least 4 faces, got " + std::to_string(nf));

  Eigen::Vector3d lo = g.V[0], hi = g.V[0];
  for (auto& p : g.V) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  g.scale = std::max((hi - lo).norm(), 1e-300);

  // Degenerate faces would have no normal and no orientation in the plane.
  for (int f = 0; f < nf; ++f) {
    const auto& t = g.F[f];
    if (CGAL::collinear(cgal_point(g.V[t[0]]), cgal_point(g.V[t[1]]), cgal_point(g.V[t[2]])))
      throw InputError("face " + std::to_string(f + 1) + " is degenerate (zero area)");
  }

  // Directed edge -> (face, side). Each undirected edge must have exactly its two directions.
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(3 * nf * 2);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      auto key = edge_key(g.F[f][k], g.F[f][(k + 1) % 3]);
      if (!directed.emplace(key, 3 * f + k).second)
        throw InputError("not an oriented 2-manifold: edge " + std::to_string(g.F[f][k] + 1) + "-" +
                         std::to_string(g.F[f][(k + 1) % 3] + 1) + " is used twice in the same direction");
    }
  g.face_edge.assign(nf, {-1, -1, -1});
  int open_edges = 0;
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      if (g.face_edge[f][k] >= 0) continue;
      int a = g.F[f][k], b = g.F[f][(k + 1) % 3];
      auto it = directed.find(edge_key(b, a));
      if (it == directed.end()) {
        ++open_edges;
        continue;
      }
      int f1 = it->second / 3, k1 = it->second % 3;
      Net::Edge e;
      e.v0 = a, e.v1 = b, e.f0 = f, e.f1 = f1;
      // Signed fold angle: the angle between the normals, negative for a reflex edge. The sign
      // is decided exactly (orientation of the other face's apex against this face's plane).
      const Eigen::Vector3d &A = g.V[a], &B = g.V[b], &C0 = g.V[g.F[f][(k + 2) % 3]],
                            &C1 = g.V[g.F[f1][(k1 + 2) % 3]];
      Eigen::Vector3d n0 = (B - A).cross(C0 - A).normalized(), n1 = (A - B).cross(C1 - B).normalized();
      double phi = std::atan2(n0.cross(n1).norm(), n0.dot(n1));
      auto side = CGAL::orientation(cgal_point(A), cgal_point(B), cgal_point(C0), cgal_point(C1));
      e.fold_angle = side == CGAL::NEGATIVE ? phi : side == CGAL::POSITIVE ? -phi : 0.0;
      e.mountain = e.fold_angle >= 0;
      int id = static_cast<int>(g.edges.size());
      g.edges.push_back(e);
      g.edge_length.push_back((B - A).norm());
      g.face_edge[f][k] = id;
      g.face_edge[f1][k1] = id;
    }
  if (open_edges) throw InputError("mesh is not closed: " + std::to_string(open_edges) + " border edges");

  // Genus 0 and connected: Euler characteristic 2 over the vertices used, one component.
  std::vector<char> used(g.V.size(), 0);
  for (auto& t : g.F)
    for (int v : t) used[v] = 1;
  long nv = std::count(used.begin(), used.end(), 1);
  UnionFind comp(nf);
  for (auto& e : g.edges) comp.unite(e.f0, e.f1);
  int components = 0;
  for (int f = 0; f < nf; ++f) components += comp.find(f) == f;
  if (components != 1) throw InputError("mesh has " + std::to_string(components) + " connected components; unfold one shell at a time");
  long euler = nv - static_cast<long>(g.edges.size()) + nf;
  if (euler != 2) throw InputError("mesh is not a topological sphere (Euler characteristic " + std::to_string(euler) + ")");

  // Facets and groups.
  UnionFind facets(nf);
  g.edge_group.assign(g.edges.size(), -1);
  for (int i = 0; i < static_cast<int>(g.edges.size()); ++i) {
    const auto& e = g.edges[i];
    if (e.fold_angle < -flat_angle) {
      ++g.reflex_edges;
      g.max_reflex_angle = std::max(g.max_reflex_angle, -e.fold_angle);
    }
    if (std::abs(e.fold_angle) <= flat_angle) {
      g.flat_edges.push_back(i);
      facets.unite(e.f0, e.f1);
    }
  }
  g.convex = g.reflex_edges == 0;
  std::vector<int> facet_id(nf, -1);
  g.facet.resize(nf);
  for (int f = 0; f < nf; ++f) {
    int r = facets.find(f);
    if (facet_id[r] < 0) facet_id[r] = g.num_facets++;
    g.facet[f] = facet_id[r];
  }
  std::map<std::pair<int, int>, int> group_of;
  for (int i = 0; i < static_cast<int>(g.edges.size()); ++i) {
    const auto& e = g.edges[i];
    if (std::abs(e.fold_angle) <= flat_angle) continue;
    int a = g.facet[e.f0], b = g.facet[e.f1];
    auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto [it, fresh] = group_of.emplace(key, g.num_groups());
    if (fresh) g.group_edges.emplace_back();
    g.group_edges[it->second].push_back(i);
    g.edge_group[i] = it->second;
  }
  // Chain ends: the vertices used once by the group's edges (a subdivided polytope edge has
  // exactly two); otherwise the two group vertices farthest apart.
  for (auto& ge : g.group_edges) {
    std::map<int, int> count;
    double len = 0;
    for (int i : ge) {
      ++count[g.edges[i].v0], ++count[g.edges[i].v1];
      len += g.edge_length[i];
    }
    std::vector<int> ends;
    for (auto [v, c] : count)
      if (c == 1) ends.push_back(v);
    if (ends.size() != 2) {
      auto farthest = [&](int from) {
        int best = from;
        double d = -1;
        for (auto [v, c] : count)
          if ((g.V[v] - g.V[from]).squaredNorm() > d) d = (g.V[v] - g.V[from]).squaredNorm(), best = v;
        return best;
      };
      int a = farthest(count.begin()->first);
      ends = {a, farthest(a)};
    }
    g.group_ends.push_back({ends[0], ends[1]});
    g.group_length.push_back(len);
  }
  return g;
}

ShellGraph build_shell_graph(const Mesh& mesh, double flat_angle) {
  std::vector<Eigen::Vector3d> V;
  std::vector<int> index(mesh.num_vertices() + mesh.number_of_removed_vertices(), -1);
  for (auto v : mesh.vertices()) {
    index[v.idx()] = static_cast<int>(V.size());
    const auto& p = mesh.point(v);
    V.emplace_back(p.x(), p.y(), p.z());
  }
  std::vector<std::array<int, 3>> F;
  for (auto f : mesh.faces()) {
    std::vector<int> loop;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) loop.push_back(index[v.idx()]);
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) F.push_back({loop[0], loop[i], loop[i + 1]});
  }
  return build_shell_graph(std::move(V), std::move(F), flat_angle);
}

}  // namespace dcshell::unfold_detail
