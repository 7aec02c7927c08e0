// The shell's dual graph: edges with signed fold angles, facets (regions joined by flat edges)
// and groups of edges between two facets.
#include <CGAL/Kernel/global_functions.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <numeric>
#include <unordered_map>

#include "dcshell/error.h"
#include "unfold/unfold_internal.h"

namespace dcshell::unfold_detail {

namespace {

std::uint64_t edge_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

Point3 cgal_point(const Eigen::Vector3d& p) { return Point3(p.x(), p.y(), p.z()); }

}  // namespace

ShellGraph build_shell_graph(std::vector<Eigen::Vector3d> V, std::vector<std::array<int, 3>> F,
                             double flat_angle, double facet_spread) {
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

  // Facets and groups (facet_spread: see unfold_internal.h).
  for (int i = 0; i < static_cast<int>(g.edges.size()); ++i) {
    const auto& e = g.edges[i];
    if (e.fold_angle < -flat_angle) {
      ++g.reflex_edges;
      g.max_reflex_angle = std::max(g.max_reflex_angle, -e.fold_angle);
    }
  }
  g.convex = g.reflex_edges == 0;
  // A needle's normal (its corners within 1e-8 of its size of one line) is rounding noise: such
  // a face is not tested against the seed, and joins across its flat edges as before.
  std::vector<Eigen::Vector3d> unit_normal(nf);
  std::vector<char> reliable(nf, 0);
  for (int f = 0; f < nf; ++f) {
    const auto& t = g.F[f];
    const Eigen::Vector3d d1 = g.V[t[1]] - g.V[t[0]], d2 = g.V[t[2]] - g.V[t[0]], c = d1.cross(d2);
    unit_normal[f] = c.normalized();
    reliable[f] = c.norm() > 1e-8 * d1.norm() * d2.norm();
  }
  auto within = [&](int f, int seed) {
    if (!reliable[f] || !reliable[seed]) return true;
    const Eigen::Vector3d &a = unit_normal[f], &b = unit_normal[seed];
    return std::atan2(a.cross(b).norm(), a.dot(b)) <= facet_spread;
  };
  g.edge_group.assign(g.edges.size(), -1);
  g.facet.assign(nf, -1);
  {
    std::vector<int> queue;
    for (int seed = 0; seed < nf; ++seed) {
      if (g.facet[seed] >= 0) continue;
      const int id = g.num_facets++;
      g.facet[seed] = id;
      queue.assign(1, seed);
      for (std::size_t qi = 0; qi < queue.size(); ++qi)
        for (int i : g.face_edge[queue[qi]]) {
          const auto& e = g.edges[i];
          const int other = e.f0 == queue[qi] ? e.f1 : e.f0;
          if (g.facet[other] >= 0 || std::abs(e.fold_angle) > flat_angle || !within(other, seed)) continue;
          g.facet[other] = id;
          queue.push_back(other);
        }
    }
  }
  // Flat edges: flat ones inside a facet (a flat edge between two facets is a fold of its own).
  auto flat_edge = [&](int i) {
    const auto& e = g.edges[i];
    return std::abs(e.fold_angle) <= flat_angle && g.facet[e.f0] == g.facet[e.f1];
  };
  for (int i = 0; i < static_cast<int>(g.edges.size()); ++i)
    if (flat_edge(i)) g.flat_edges.push_back(i);
  // Facet charts: mean plane by the area vector, first face's first edge as the u axis.
  {
    std::vector<Eigen::Vector3d> normal(g.num_facets, Eigen::Vector3d::Zero());
    std::vector<int> first(g.num_facets, -1);
    for (int f = 0; f < nf; ++f) {
      const auto& t = g.F[f];
      normal[g.facet[f]] += (g.V[t[1]] - g.V[t[0]]).cross(g.V[t[2]] - g.V[t[0]]);
      if (first[g.facet[f]] < 0) first[g.facet[f]] = f;
    }
    g.facet_frame.resize(g.num_facets);
    for (int k = 0; k < g.num_facets; ++k) {
      Eigen::Vector3d n = normal[k].normalized();
      const auto& t = g.F[first[k]];
      Eigen::Vector3d u = g.V[t[1]] - g.V[t[0]];
      u = (u - n * n.dot(u)).normalized();
      g.facet_frame[k] = {g.V[t[0]], u, n.cross(u)};
    }
    g.chart.resize(nf);
    for (int f = 0; f < nf; ++f) {
      const auto& fr = g.facet_frame[g.facet[f]];
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d d = g.V[g.F[f][k]] - fr[0];
        g.chart[f][k] = Eigen::Vector2d(d.dot(fr[1]), d.dot(fr[2]));
      }
    }
  }
  std::map<std::pair<int, int>, int> group_of;
  for (int i = 0; i < static_cast<int>(g.edges.size()); ++i) {
    if (flat_edge(i)) continue;
    const auto& e = g.edges[i];
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
  // Groups by end vertex (both ends), in increasing group order: the steepest-edge heuristic
  // visits them once per direction.
  g.end_start.assign(g.V.size() + 1, 0);
  for (const auto& ends : g.group_ends) ++g.end_start[ends[0] + 1], ++g.end_start[ends[1] + 1];
  for (std::size_t v = 0; v < g.V.size(); ++v) g.end_start[v + 1] += g.end_start[v];
  g.end_groups.resize(g.end_start.back());
  {
    std::vector<int> fill(g.end_start.begin(), g.end_start.end() - 1);
    for (int gi = 0; gi < g.num_groups(); ++gi)
      for (int v : g.group_ends[gi]) g.end_groups[fill[v]++] = gi;
  }
  return g;
}

SearchGraph make_search_graph(const ShellGraph& g, double flat_angle) {
  SearchGraph sg;
  sg.fine = &g;
  const int nf = static_cast<int>(g.F.size());
  // Worth it only when facets hold several triangles on average, and exact only when every
  // facet is planar to rounding: a facet bent within flat_angle is laid out from all its
  // vertices, a fan of its corners would be a slightly different polygon.
  if (g.num_facets * 2 > nf) return sg;
  for (int f = 0; f < nf; ++f) {
    const auto& fr = g.facet_frame[g.facet[f]];
    Eigen::Vector3d n = fr[1].cross(fr[2]);
    for (int v : g.F[f])
      if (std::abs((g.V[v] - fr[0]).dot(n)) > 1e-9 * g.scale) return sg;
  }
  // Polytope corners: vertices where three or more facets meet.
  std::vector<std::vector<int>> vfacets(g.V.size());
  for (int f = 0; f < nf; ++f)
    for (int v : g.F[f]) {
      auto& l = vfacets[v];
      if (std::find(l.begin(), l.end(), g.facet[f]) == l.end()) l.push_back(g.facet[f]);
    }
  // Boundary of each facet, directed counter-clockwise (as its faces hold the edges).
  std::vector<std::vector<std::pair<int, int>>> boundary(g.num_facets);
  for (int gi = 0; gi < g.num_groups(); ++gi)
    for (int i : g.group_edges[gi]) {
      const auto& e = g.edges[i];
      boundary[g.facet[e.f0]].push_back({e.v0, e.v1});
      boundary[g.facet[e.f1]].push_back({e.v1, e.v0});
    }
  std::vector<int> new_index(g.V.size(), -1);
  std::vector<Eigen::Vector3d> V;
  std::vector<std::array<int, 3>> F;
  std::vector<int> fan_facet;
  for (int k = 0; k < g.num_facets; ++k) {
    std::map<int, int> next;
    for (auto [a, b] : boundary[k])
      if (!next.emplace(a, b).second) return sg;  // the facet touches itself at a vertex
    // One loop through every boundary edge, listing its corners in order.
    int start = -1;
    for (auto [a, b] : next)
      if (vfacets[a].size() >= 3) {
        start = a;
        break;
      }
    if (start < 0) return sg;
    std::vector<int> corners;
    int v = start;
    std::size_t walked = 0;
    do {
      if (vfacets[v].size() >= 3) corners.push_back(v);
      auto it = next.find(v);
      if (it == next.end()) return sg;
      v = it->second;
      ++walked;
    } while (v != start && walked <= next.size());
    if (v != start || walked != next.size() || corners.size() < 3) return sg;
    for (int c : corners)
      if (new_index[c] < 0) new_index[c] = static_cast<int>(V.size()), V.push_back(g.V[c]);
    for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
      F.push_back({new_index[corners[0]], new_index[corners[i]], new_index[corners[i + 1]]});
      fan_facet.push_back(k);
    }
  }
  if (F.size() * 2 > static_cast<std::size_t>(nf)) return sg;
  try {
    sg.coarse = build_shell_graph(std::move(V), std::move(F), flat_angle);
  } catch (const InputError&) {
    return sg;  // e.g. three collinear corners: a degenerate fan triangle
  }
  // The coarse facets must be the fine ones, in the same order, with the same adjacency.
  const ShellGraph& c = sg.coarse;
  if (c.num_facets != g.num_facets || c.num_groups() != g.num_groups()) return sg;
  for (std::size_t f = 0; f < c.F.size(); ++f)
    if (c.facet[f] != fan_facet[f]) return sg;
  std::map<std::pair<int, int>, int> fine_group;
  for (int gi = 0; gi < g.num_groups(); ++gi) {
    const auto ab = g.group_facets(gi);
    fine_group[std::minmax(ab[0], ab[1])] = gi;
  }
  sg.group_map.assign(g.num_groups(), -1);
  for (int ci = 0; ci < c.num_groups(); ++ci) {
    const auto& e = c.edges[c.group_edges[ci][0]];
    auto it = fine_group.find(std::minmax(c.facet[e.f0], c.facet[e.f1]));
    if (it == fine_group.end() || sg.group_map[it->second] >= 0) return sg;
    sg.group_map[it->second] = ci;
  }
  sg.use_coarse = true;
  return sg;
}

NetMetrics SearchGraph::evaluate(const std::vector<char>& folded) const {
  if (!use_coarse) return decode(*fine, folded, 1, true).metrics;
  std::vector<char> fc(folded.size());
  for (std::size_t gi = 0; gi < folded.size(); ++gi) fc[group_map[gi]] = folded[gi];
  return decode(coarse, fc, 1, true).metrics;
}

std::vector<Eigen::Vector3d> preferred_directions(const ShellGraph& g) {
  std::vector<Eigen::Vector3d> area(g.num_facets, Eigen::Vector3d::Zero());
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (std::size_t f = 0; f < g.F.size(); ++f) {
    const auto& t = g.F[f];
    area[g.facet[f]] += (g.V[t[1]] - g.V[t[0]]).cross(g.V[t[2]] - g.V[t[0]]);
  }
  for (const auto& p : g.V) centroid += p;
  centroid /= static_cast<double>(std::max<std::size_t>(g.V.size(), 1));
  std::vector<int> facets(g.num_facets);
  std::iota(facets.begin(), facets.end(), 0);
  std::stable_sort(facets.begin(), facets.end(), [&](int a, int b) { return area[a].norm() > area[b].norm(); });
  std::map<int, int> degree;
  for (const auto& ends : g.group_ends) ++degree[ends[0]], ++degree[ends[1]];
  std::vector<std::pair<int, int>> by_degree;  // (-degree, vertex): highest degree first
  for (auto [v, d] : degree) by_degree.push_back({-d, v});
  std::sort(by_degree.begin(), by_degree.end());
  std::vector<Eigen::Vector3d> dirs;
  auto add = [&](const Eigen::Vector3d& d) {
    if (d.norm() > 0) dirs.push_back(d.normalized());
  };
  for (std::size_t i = 0; i < 3; ++i) {
    if (i < facets.size()) add(-area[facets[i]]);
    if (i < by_degree.size()) add(g.V[by_degree[i].second] - centroid);
  }
  return dirs;
}

ShellGraph build_shell_graph(const Mesh& mesh, double flat_angle, double facet_spread) {
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
  return build_shell_graph(std::move(V), std::move(F), flat_angle, facet_spread);
}

}  // namespace dcshell::unfold_detail
