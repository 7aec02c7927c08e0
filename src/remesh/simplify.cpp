// Progressive-hull simplification (see dcshell/simplify.h).
#include "dcshell/simplify.h"

#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>
#include <queue>

#include "dcshell/fatness.h"
#include "remesh/passes.h"

namespace dcshell {
namespace {

using namespace remesh_detail;

// LP margins in local units (a fraction of the edge's scale): the LP's optimum lies on some of
// its planes, and a margin keeps the rounded point on the right side of them.
constexpr double kMargin = 1e-9;
// Faces whose corners lie this close (local units) to a constraint plane are "nearly flat"
// against it: far above the rounding of a cut face's vertices, far below any real feature.
constexpr double kNearFlat = 1e-10;

// A removed end point is a free position when it lies exactly on the plane of every face around
// the other end point (a flat neighbourhood): no volume is added.
bool is_flat_target(const Mesh& m, const Star& s, V target) {
  for (F f : s.faces) {
    H h = m.halfedge(f);
    const V a = m.source(h), b = m.target(h), c = m.target(m.next(h));
    if (a == target || b == target || c == target) continue;
    if (CGAL::orientation(m.point(a), m.point(b), m.point(c), m.point(target)) != CGAL::COPLANAR) return false;
  }
  return true;
}

// Sums of area x fatness and of area over the faces a replacement removes, and over the cone
// that replaces them.
FatArea star_fat_area(const Mesh& m, const Star& s) {
  FatArea r;
  for (F f : s.faces) {
    H h = m.halfedge(f);
    r.add(m.point(m.source(h)), m.point(m.target(h)), m.point(m.target(m.next(h))));
  }
  return r;
}

FatArea cone_fat_area(const Mesh& m, const Star& s, const Point3& w) {
  FatArea r;
  for (std::size_t i = 0; i < s.ring.size(); ++i) r.add(w, m.point(s.ring[i]), m.point(s.ring[(i + 1) % s.ring.size()]));
  return r;
}

double local_fatness_star(const Mesh& m, const Star& s) { return star_fat_area(m, s).ratio(); }
double local_fatness_cone(const Mesh& m, const Star& s, const Point3& w) { return cone_fat_area(m, s, w).ratio(); }

// The candidate at w, with what it changes in area x fatness and area.
Candidate make_candidate(const Mesh& m, const Star& s, const Point3& w, double cost) {
  const FatArea a = star_fat_area(m, s), b = cone_fat_area(m, s, w);
  Candidate c{true, cost, w};
  c.d_fa = b.fa - a.fa;
  c.d_area = b.a - a.a;
  return c;
}

Candidate best_position(const Mesh& m, const Star& s, const ShellConstraints& constraints, bool fatter_only) {
  Candidate best;
  if (!s.valid) return best;
  for (V r : s.removed)
    if (is_flat_target(m, s, r) && (!fatter_only || local_fatness_cone(m, s, m.point(r)) >= local_fatness_star(m, s)))
      return make_candidate(m, s, m.point(r), 0.0);

  // Centred on the removed vertices: an edge's mid-point, or the one vertex a flip lifts.
  const Eigen::Vector3d pu = vec(m.point(s.removed.front())), pv = vec(m.point(s.removed.back()));
  Frame frame{0.5 * (pu + pv), 0.0};
  for (V r : s.ring) frame.scale = std::max(frame.scale, (vec(m.point(r)) - frame.origin).norm());
  if (!(frame.scale > 0)) return best;
  // Rounding the result to doubles moves it by ~1e-16 of its magnitude: keep the margin above that.
  const double margin = std::max(kMargin, 1e-13 * frame.origin.lpNorm<Eigen::Infinity>() / frame.scale);

  // A star face and the face across a ring edge that lie in one plane (a flat region) pin the new
  // vertex to that plane: their rows get no margin, or the LP would be infeasible.
  const std::size_t nr = s.ring.size();
  std::vector<F> flat_faces;
  std::vector<char> flat_edge(nr, 0);
  for (std::size_t i = 0; i < nr; ++i) {
    const H h = m.halfedge(s.ring[i], s.ring[(i + 1) % nr]);
    const Point3 &a = m.point(m.source(h)), &b = m.point(m.target(h)), &c = m.point(m.target(m.next(h)));
    if (CGAL::orientation(a, b, c, m.point(s.across[i])) == CGAL::COPLANAR) {
      flat_edge[i] = 1;
      flat_faces.push_back(m.face(h));
    }
  }
  auto is_flat = [&](F f) {
    if (std::find(flat_faces.begin(), flat_faces.end(), f) != flat_faces.end()) return true;
    H h = m.halfedge(f);  // coplanar with a flat face of the star
    for (F g : flat_faces) {
      H k = m.halfedge(g);
      bool all = true;
      for (int j = 0; j < 3; ++j, h = m.next(h))
        all = all && CGAL::orientation(m.point(m.source(k)), m.point(m.target(k)), m.point(m.target(m.next(k))),
                                       m.point(m.source(h))) == CGAL::COPLANAR;
      if (all) return true;
    }
    return false;
  };
  // A cut face rounded to doubles lies within rounding of its cut plane, so the faces of such a
  // nearly flat neighbourhood and the plane leave w a slab about one rounding unit thick: rows of
  // faces lying within kNearFlat of a constraint plane get no margin, nor does that constraint's
  // row, and nearby doubles are tried against the exact check below.
  std::vector<Row> con0;
  add_constraint_rows(constraints, frame, 0, con0);
  std::vector<char> con_near(con0.size(), 0);
  bool near_flat = false;
  // A face is nearly flat against a constraint when its three corners are within kNearFlat of
  // the constraint's plane (its own normal may be far off when it is a sliver).
  auto near_constraint = [&](const Point3& p, const Point3& q, const Point3& r) {
    bool near = false;
    for (std::size_t k = 0; k < con0.size(); ++k) {
      bool all = true;
      for (const Point3* x : {&p, &q, &r}) all = all && std::abs(con0[k].a.dot(frame.to_local(vec(*x))) - con0[k].b) < kNearFlat;
      if (all) con_near[k] = 1, near = true;
    }
    near_flat = near_flat || near;
    return near;
  };
  std::vector<Row> rows;
  auto add_row = [&](const Point3& p, const Point3& q, const Point3& r, bool flat) {
    std::vector<Row> r0;
    add_below_row(p, q, r, frame, 0, r0);
    if (r0.empty()) return;
    if (!flat && !near_constraint(p, q, r)) r0[0].b -= margin;
    rows.push_back(r0[0]);
  };
  Eigen::Vector3d objective = Eigen::Vector3d::Zero();
  for (F f : s.faces) {
    H h = m.halfedge(f);
    const Point3 &a = m.point(m.source(h)), &b = m.point(m.target(h)), &c = m.point(m.target(m.next(h)));
    add_row(a, c, b, is_flat(f));  // on or above: each new tetrahedron adds volume
    objective += (vec(b) - vec(a)).cross(vec(c) - vec(a));  // gradient of the added volume (x6)
  }
  for (std::size_t i = 0; i < nr; ++i)  // below the faces across the ring: convex there
    add_row(m.point(s.ring[(i + 1) % nr]), m.point(s.ring[i]), m.point(s.across[i]), flat_edge[i]);
  // The margin keeps the rounded optimum strictly on the right side of every other plane; in a
  // flat region the exact check decides whether the rounded point stayed on the plane.
  for (std::size_t k = 0; k < con0.size(); ++k) rows.push_back({con0[k].a, con0[k].b - (con_near[k] ? 0 : margin)});
  // Nearly flat neighbourhoods (a cut face within rounding of its plane, or input facets flat up
  // to the rounding of the file's digits) leave w a slab thinner than the margins: the LP is then
  // solved without margins and nearby doubles across the slab (along the constraint's normal, or
  // the outward direction) are tried against the exact check.
  bool exact_needed = near_flat;
  std::optional<Eigen::Vector3d> y = solve_lp3(objective.normalized(), rows);
  if (!y) {
    std::vector<Row> bare;
    for (F f : s.faces) {
      H h = m.halfedge(f);
      add_below_row(m.point(m.source(h)), m.point(m.target(m.next(h))), m.point(m.target(h)), frame, 0, bare);
    }
    for (std::size_t i = 0; i < nr; ++i)
      add_below_row(m.point(s.ring[(i + 1) % nr]), m.point(s.ring[i]), m.point(s.across[i]), frame, 0, bare);
    bare.insert(bare.end(), con0.begin(), con0.end());
    y = solve_lp3(objective.normalized(), bare);
    exact_needed = true;
  }
  if (!y) return best;
  Point3 w = pt(frame.to_world(*y));
  if (exact_needed) {
    Eigen::Vector3d n = objective.normalized();
    for (std::size_t k = 0; k < con0.size(); ++k)
      if (con_near[k]) { n = con0[k].a; break; }
    const Eigen::Vector3d w0 = vec(w);
    const double ulp = std::ldexp(1.0, -52) * w0.lpNorm<Eigen::Infinity>();  // about one unit in the last place
    bool found = false;
    // Cheap necessary conditions first (the removed vertices under the cone, the constraints):
    // most nearby doubles fail one of them, and the full check costs a pass over the mesh.
    auto plausible = [&](const Point3& c) {
      if (!constraints.satisfied_by(c)) return false;
      for (V r : s.removed)
        for (std::size_t i = 0; i < nr; ++i)
          if (CGAL::orientation(c, m.point(s.ring[i]), m.point(s.ring[(i + 1) % nr]), m.point(r)) == CGAL::POSITIVE)
            return false;
      return true;
    };
    for (double k : {0.0, -1.0, 1.0, -2.0, 2.0, -4.0, 4.0}) {
      const Point3 c = pt(w0 + k * ulp * n);
      if (plausible(c) && replacement_is_valid(m, s, c, {}, constraints)) { w = c; found = true; break; }
    }
    if (!found) return best;
  }
  if (fatter_only && local_fatness_cone(m, s, w) < local_fatness_star(m, s)) return best;
  return make_candidate(m, s, w, volume_change(m, s, w));
}

struct Entry {
  double key;   // queue order
  double cost;  // added volume
  std::size_t h;  // halfedge index: deterministic tie break
  V u, v;
  unsigned su, sv;  // vertex stamps when computed
  bool fresh;       // computed in this pass (not taken from the cache)
  Point3 w;
  bool operator>(const Entry& o) const { return key != o.key ? key > o.key : h > o.h; }
};

}  // namespace

namespace remesh_detail {

Candidate cheapest_cone(const Mesh& m, const Star& s, const ShellConstraints& c, bool fatter_only) {
  return best_position(m, s, c, fatter_only);
}

Workspace::Workspace(Mesh& m) : mesh(m), volume(mesh_volume(m)) {
  stamp_ = mesh.add_property_map<V, unsigned>("v:remesh_stamp", 0).first;
  settled_ = mesh.add_property_map<V, unsigned>("v:remesh_settled", ~0u).first;
}

Workspace::~Workspace() {
  mesh.remove_property_map(stamp_);
  mesh.remove_property_map(settled_);
}

void Workspace::touched(const Star& s, V w) {
  ++stamp_[w];
  for (V r : s.ring) ++stamp_[r];
}

Candidate Workspace::edge_candidate(H h, const ShellConstraints& c, bool fresh) {
  V u = mesh.source(h), v = mesh.target(h);
  const auto key = std::minmax(u, v);
  const unsigned su = stamp_[key.first], sv = stamp_[key.second];
  if (!fresh) {
    auto it = cache_.find(key);
    if (it != cache_.end() && it->second.su == su && it->second.sv == sv) return it->second.c;
  }
  Candidate cand = best_position(mesh, edge_star(mesh, h), c, fatter_only_);
  cache_[key] = {su, sv, cand};
  return cand;
}

std::size_t Workspace::simplify_pass(const ShellConstraints& constraints, const SimplifyOptions& options,
                                     SimplifyStats& st) {
  if (fatter_only_ != options.fatter_only) cache_.clear();
  fatter_only_ = options.fatter_only;
  std::vector<char> locked(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), 0);  // indices stay valid: no garbage collection here
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  // By gain: the change in area-weighted fatness (to first order) per unit of added volume,
  // collapses that gain first; those that do not, least volume first, after them.
  const double fat = options.order_by_gain ? weighted_fatness(mesh) : 0.0;
  const double eps = 1e-12 * std::abs(volume);
  auto push_edge = [&](H h, bool fresh) {
    const V u = mesh.source(h), v = mesh.target(h);
    const Candidate c = edge_candidate(h, constraints, fresh);
    if (!c.ok) { ++st.infeasible; return; }
    double key = c.cost;
    if (options.order_by_gain) {
      const double gain = c.d_fa - fat * c.d_area;
      if (gain > 0) key = -gain / (std::max(c.cost, 0.0) + eps);
    }
    queue.push({key, c.cost, std::size_t(h), u, v, stamp_[u], stamp_[v], fresh, c.w});
  };
  for (auto e : mesh.edges()) push_edge(mesh.halfedge(e), false);

  std::size_t collapses = 0;
  while (!queue.empty()) {
    const Entry e = queue.top();
    queue.pop();
    const H h(static_cast<Mesh::size_type>(e.h));
    if (mesh.is_removed(h) || mesh.source(h) != e.u || mesh.target(h) != e.v || stamp_[e.u] != e.su ||
        stamp_[e.v] != e.sv || locked[e.u] || locked[e.v])
      continue;  // stale: the neighbourhood changed since this entry was computed
    if (volume + std::max(e.cost, 0.0) > options.max_volume) {
      if (options.order_by_gain) continue;
      break;  // cheapest first: nothing else fits
    }
    if (mesh.number_of_faces() < options.target_faces + 2 || mesh.number_of_vertices() <= 4) break;
    const Star s = edge_star(mesh, h);
    if (!s.valid || !CGAL::Euler::does_satisfy_link_condition(mesh.edge(h), mesh) ||
        !replacement_is_valid(mesh, s, e.w, {}, constraints)) {
      // A cached position may predate a change two rings away: recompute it once.
      if (!e.fresh) push_edge(h, true);
      else ++st.rejected;
      continue;
    }
    const double dv = volume_change(mesh, s, e.w);
    if (volume + std::max(dv, 0.0) > options.max_volume) { ++st.rejected; continue; }
    const V w = CGAL::Euler::collapse_edge(mesh.edge(h), mesh);
    mesh.point(w) = e.w;
    volume += dv;
    ++collapses;
    touched(s, w);
    if (options.single_pass) {
      locked[w] = 1;
      for (V r : s.ring) locked[r] = 1;
      continue;
    }
    std::vector<Mesh::Edge_index> todo;
    for (V x : s.ring)
      for (H o : CGAL::halfedges_around_source(x, mesh)) todo.push_back(mesh.edge(o));
    std::sort(todo.begin(), todo.end());
    todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
    for (auto ed : todo) push_edge(mesh.halfedge(ed), false);
  }
  st.collapses += collapses;
  return collapses;
}

}  // namespace remesh_detail

std::size_t simplify_progressive_hull(Mesh& mesh, const ShellConstraints& constraints, const SimplifyOptions& options,
                                      SimplifyStats* stats) {
  SimplifyStats local;
  std::size_t n = 0;
  {
    remesh_detail::Workspace ws(mesh);
    n = ws.simplify_pass(constraints, options, stats ? *stats : local);
  }
  mesh.collect_garbage();
  return n;
}

}  // namespace dcshell
