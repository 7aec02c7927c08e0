// Fat triangulations of nearly flat facets by tiny domes (see dcshell/flat_facets.h).
#include "dcshell/flat_facets.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <vector>

#include "dcshell/convex_hull.h"
#include "dcshell/fatness.h"
#include "remesh/star.h"
#include "remesh/steiner.h"

namespace dcshell {
namespace {

using remesh_detail::F;
using remesh_detail::H;
using remesh_detail::V;
using remesh_detail::vec;
using Vec = Eigen::Vector3d;

constexpr std::size_t kMaxCorners = 400;
// Steiner points: at most this many in one facet, and only in facets holding at least this share
// of the shell's area (refining costs time; small facets gain little area x fatness).
constexpr std::size_t kMaxSteinerPerFacet = 48;
constexpr double kMinSteinerArea = 0.01;
// When the domes of all facets together fail a check, at most this many results with some of
// them are tried (each is a convex hull and an enclosure check of the whole shell).
constexpr std::size_t kMaxFallbackTries = 24;

// Faces joined across edges that are flat within the angle; groups numbered by their first face.
struct Groups {
  std::vector<int> of_face;
  std::vector<std::vector<F>> faces;
  std::vector<Vec> normal;  // unit, area-weighted
  std::vector<double> area;
};

Vec area_vector(const Mesh& m, F f) {
  const H h = m.halfedge(f);
  const Vec a = vec(m.point(m.source(h))), b = vec(m.point(m.target(h))), c = vec(m.point(m.target(m.next(h))));
  return 0.5 * (b - a).cross(c - a);
}

Groups flat_groups(const Mesh& m, double flat_angle) {
  const std::size_t nf = m.number_of_faces();
  std::vector<Vec> av(nf);
  for (F f : m.faces()) av[f.idx()] = area_vector(m, f);
  std::vector<std::size_t> parent(nf);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (auto e : m.edges()) {
    const H h = m.halfedge(e);
    const std::size_t a = m.face(h).idx(), b = m.face(m.opposite(h)).idx();
    const double angle = std::atan2(av[a].cross(av[b]).norm(), av[a].dot(av[b]));
    if (angle < flat_angle) {
      const std::size_t ra = find(a), rb = find(b);
      parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  Groups g;
  g.of_face.assign(nf, -1);
  std::map<std::size_t, int> id;
  for (F f : m.faces()) {
    const std::size_t r = find(f.idx());
    auto it = id.emplace(r, int(g.faces.size())).first;
    if (it->second == int(g.faces.size())) {
      g.faces.emplace_back();
      g.normal.push_back(Vec::Zero());
      g.area.push_back(0);
    }
    const int k = it->second;
    g.of_face[f.idx()] = k;
    g.faces[k].push_back(f);
    g.normal[k] += av[f.idx()];
    g.area[k] += av[f.idx()].norm();
  }
  for (auto& n : g.normal) n.normalize();
  return g;
}

// The facet's corners in boundary order (counter-clockwise seen from outside), or empty when the
// facet is not a disk whose every vertex is on its boundary.
std::vector<V> boundary_loop(const Mesh& m, const Groups& g, int k) {
  std::map<V, H> from;  // boundary halfedge by its source
  std::vector<V> all;
  for (F f : g.faces[k]) {
    H h = m.halfedge(f);
    for (int i = 0; i < 3; ++i, h = m.next(h)) {
      all.push_back(m.source(h));
      if (g.of_face[m.face(m.opposite(h)).idx()] == k) continue;
      if (!from.emplace(m.source(h), h).second) return {};  // pinched
    }
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  if (from.empty() || all.size() != from.size() || g.faces[k].size() + 2 != from.size()) return {};
  std::vector<V> loop;
  H h = from.begin()->second;
  do {
    loop.push_back(m.source(h));
    auto it = from.find(m.target(h));
    if (it == from.end()) return {};
    h = it->second;
  } while (m.source(h) != loop.front() && loop.size() <= from.size());
  if (loop.size() != from.size()) return {};
  return loop;
}

// Fattest triangulation of a convex polygon (maximum sum of area x fatness) by dynamic
// programming over its diagonals; returns split[i][j], the apex of the triangle on (i, j), or an
// empty table when no triangulation avoids degenerate triangles.
struct Triangulation {
  std::vector<int> split;  // m x m
  double score = -1;
  int m = 0;
  int apex(int i, int j) const { return split[std::size_t(i) * std::size_t(m) + std::size_t(j)]; }
};

Triangulation fattest_triangulation(const std::vector<Vec>& p, const std::vector<Eigen::Vector2d>& q, double min_area) {
  const int m = int(p.size());
  Triangulation t;
  t.m = m;
  t.split.assign(std::size_t(m) * std::size_t(m), -1);
  const double ninf = -std::numeric_limits<double>::infinity();
  std::vector<double> best(std::size_t(m) * std::size_t(m), ninf);
  auto at = [m](int i, int j) { return std::size_t(i) * std::size_t(m) + std::size_t(j); };
  for (int i = 0; i + 1 < m; ++i) best[at(i, i + 1)] = 0;
  for (int len = 2; len < m; ++len)
    for (int i = 0; i + len < m; ++i) {
      const int j = i + len;
      for (int k = i + 1; k < j; ++k) {
        const double a = best[at(i, k)], b = best[at(k, j)];
        if (a == ninf || b == ninf) continue;
        const Eigen::Vector2d u = q[k] - q[i], v = q[j] - q[i];
        if (0.5 * (u.x() * v.y() - u.y() * v.x()) <= min_area) continue;  // degenerate or reflex
        const double area = 0.5 * (p[k] - p[i]).cross(p[j] - p[i]).norm();
        const double s = a + b + area * triangle_fatness({p[i].x(), p[i].y(), p[i].z()}, {p[k].x(), p[k].y(), p[k].z()},
                                                         {p[j].x(), p[j].y(), p[j].z()});
        if (s > best[at(i, j)]) best[at(i, j)] = s, t.split[at(i, j)] = k;
      }
    }
  if (best[at(0, m - 1)] == ninf) return {};
  t.score = best[at(0, m - 1)];
  return t;
}

// Heights over the polygon whose lower hull is the triangulation: a convex piecewise-linear
// function. In a convex polygon the line through a diagonal meets the polygon only in that
// diagonal, so max(0, distance to the diagonal's line) folds along the diagonal and nowhere else;
// a weighted sum of these over the triangulation's diagonals folds exactly along them. Returns
// heights scaled to [0, 1] and the weakest fold relative to their range: a dome of depth D
// survives noise e in the corners' heights when 2 e < margin * D.
std::vector<double> dome_heights(const Triangulation& t, const std::vector<Eigen::Vector2d>& q, double* margin) {
  const int m = t.m;
  std::vector<double> d(std::size_t(m), 0.0);
  struct Item { int i, j, apex; };  // sub-polygon i..j whose edge (i, j) has `apex` across it
  std::vector<Item> stack;
  const int k0 = t.apex(0, m - 1);
  if (k0 >= 2) stack.push_back({0, k0, m - 1});
  if (m - 1 - k0 >= 2) stack.push_back({k0, m - 1, 0});
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    const int k = t.apex(it.i, it.j);
    const Eigen::Vector2d a = q[it.i], b = q[it.j], u = (b - a).normalized();
    const double dk = cross(u, q[k] - a), da = cross(u, q[it.apex] - a);  // opposite sides of the diagonal
    // The hull's orientation test on the four corners sees the fold's volume |ij| dk dl / 6 (per
    // unit height) against noise e moving it by at most e |ij| (dk + dl) / 3: its strength is
    // dk dl / (dk + dl). Weighting each fold by 1 / strength makes every fold's strength 1, all
    // equally robust, which needs the least depth.
    const double ak = std::abs(dk), al = std::abs(da);
    const double strength = ak + al > 0 ? ak * al / (ak + al) : 0.0;
    if (!(strength > 0)) {
      *margin = 0;
      return d;
    }
    const double sign = dk > 0 ? 1 : -1;
    for (int v = 0; v < m; ++v) d[std::size_t(v)] += std::max(0.0, sign * cross(u, q[v] - a)) / strength;
    if (k - it.i >= 2) stack.push_back({it.i, k, it.j});
    if (it.j - k >= 2) stack.push_back({k, it.j, it.i});
  }
  const auto mm = std::minmax_element(d.begin(), d.end());
  const double lo = *mm.first, range = *mm.second - lo;  // values: d changes below
  *margin = range > 0 ? 1.0 / range : 0.0;  // every fold has strength 1
  for (double& h : d) h = range > 0 ? (h - lo) / range : 0.0;
  return d;
}

// Direction in which a corner of facet k moves when the facet's surface rises by one unit along
// w (= ±normal): along w, but within the plane of every other facet being domed that the corner
// lies on (that facet's heights are measured from its plane, so its dome stays as planned), and,
// moving outward, never into a neighbouring face's halfspace (which would leave the corner's old
// place outside the new hull). Any sideways part is kept small: it shifts the corner within the
// facet, which may turn a nearly straight boundary corner reflex.
Vec move_direction(const Mesh& m, const Groups& g, const std::vector<char>& domed, int k, V v, const Vec& w,
                   bool outward) {
  std::vector<Vec> basis;  // orthonormal, spanning the normals to stay perpendicular to
  auto keep_off = [&](const Vec& a) {
    Vec b = a;
    for (const Vec& e : basis) b -= b.dot(e) * e;
    if (b.norm() > 1e-3) basis.push_back(b.normalized());
  };
  std::vector<int> around;
  for (F f : CGAL::faces_around_target(m.halfedge(v), m))
    if (f != Mesh::null_face() && g.of_face[f.idx()] != k) around.push_back(g.of_face[f.idx()]);
  std::sort(around.begin(), around.end());
  around.erase(std::unique(around.begin(), around.end()), around.end());
  for (int o : around)
    if (domed[std::size_t(o)]) keep_off(g.normal[std::size_t(o)]);
  auto project = [&](Vec u) {
    for (const Vec& e : basis) u -= u.dot(e) * e;
    return u;
  };
  Vec u = project(w);
  if (outward)
    for (int o : around)
      if (u.dot(g.normal[std::size_t(o)]) < 0) {
        keep_off(g.normal[std::size_t(o)]);
        u = project(w);
      }
  if (!(u.dot(w) > 0.2)) return Vec::Zero();  // no good direction: the caller gives up this facet
  return u / u.dot(w);  // unit rise along w
}

double ulp_noise(const std::vector<Vec>& p) {
  double big = 0;
  for (const Vec& x : p) big = std::max(big, x.cwiseAbs().maxCoeff());
  return 8 * big * std::numeric_limits<double>::epsilon();
}

// A facet's corners in order and its frame: origin c (the corners' centroid), in-plane axes e1, e2.
struct Facet {
  int k = -1;
  std::vector<V> loop;
  std::vector<Eigen::Vector2d> q;  // corners in the frame
  Vec c, e1, e2;
  double dev = 0, diam = 0, noise = 0;
  double area = 0, current = 0;  // area, and sum of area x fatness of its triangles now
};

// What doming one facet takes: its corners in order, heights in [0, 1] (corners, then the
// Steiner points), depth, and the Steiner points on the facet's plane.
struct Plan {
  int k = -1;
  std::vector<V> loop;
  std::vector<double> h;
  double depth = 0;
  double diam = 0;
  std::vector<Vec> extra;
};

// Facet k as a convex polygon of boundary corners, flat to 1e-6 of its size; false when it is not.
bool facet_geometry(const Mesh& mesh, const Groups& g, int k, Facet& fc) {
  fc.k = k;
  fc.loop = boundary_loop(mesh, g, k);
  // The dynamic programme is cubic in the corners: a facet of more corners keeps its triangles.
  if (fc.loop.size() < 3 || fc.loop.size() > kMaxCorners) return false;
  std::vector<Vec> p;
  for (V v : fc.loop) p.push_back(vec(mesh.point(v)));
  const Vec n = g.normal[k];
  fc.c = std::accumulate(p.begin(), p.end(), Vec(Vec::Zero())) / double(p.size());
  fc.e1 = n.unitOrthogonal(), fc.e2 = n.cross(fc.e1);
  for (const Vec& x : p) {
    fc.q.emplace_back((x - fc.c).dot(fc.e1), (x - fc.c).dot(fc.e2));
    fc.dev = std::max(fc.dev, std::abs((x - fc.c).dot(n)));
  }
  for (const Vec& x : p)
    for (const Vec& y : p) fc.diam = std::max(fc.diam, (x - y).norm());
  if (!(fc.diam > 0) || fc.dev > 1e-6 * fc.diam) return false;
  // The dome must rise above the facet's own unevenness and the coordinates' rounding.
  fc.noise = fc.dev + ulp_noise(p);
  fc.area = g.area[k];
  FatArea now;
  for (F f : g.faces[k]) {
    const H h = mesh.halfedge(f);
    now.add(mesh.point(mesh.source(h)), mesh.point(mesh.target(h)), mesh.point(mesh.target(mesh.next(h))));
  }
  fc.current = now.fa;
  return true;
}

// The plan realising the facet's fattest triangulation of its corners, or none when it would not
// get fatter or its dome would have to be deep to beat the rounding noise.
bool plan_corners(const Facet& fc, const Triangulation& t, const FlatFacetOptions& options, Plan& plan) {
  if (fc.loop.size() < 4 || t.score < 0 || !(t.score > fc.current * (1 + 1e-6))) return false;
  plan.k = fc.k;
  plan.loop = fc.loop;
  double margin = 0;
  plan.h = dome_heights(t, fc.q, &margin);
  plan.depth = std::max(options.depth * fc.diam, 8 * fc.noise / std::max(margin, 1e-300));
  plan.diam = fc.diam;
  return margin > 0 && plan.depth <= options.max_depth * fc.diam;
}

// The plan realising a Delaunay triangulation with interior points (steiner.h).
bool plan_steiner(const Facet& fc, const remesh_detail::SteinerMesh& sm, const FlatFacetOptions& options, Plan& plan) {
  plan.k = fc.k;
  plan.loop = fc.loop;
  double margin = 0;
  plan.h = remesh_detail::paraboloid_heights(fc.q, sm.interior, &margin);
  plan.depth = std::max(options.depth * fc.diam, 8 * fc.noise / std::max(margin, 1e-300));
  plan.diam = fc.diam;
  plan.extra.clear();
  for (const auto& x : sm.interior) {
    plan.extra.push_back(fc.c + x.x() * fc.e1 + x.y() * fc.e2);
    if (!plan.extra.back().allFinite()) return false;
  }
  return margin > 0 && plan.depth <= options.max_depth * fc.diam;
}

// Steiner points for the facets, at most `points` in all: greedily where the fatness gained
// (area x fatness) per point is largest, over prefixes of each facet's refinement sequence.
// Returns, per facet, the refinement chosen (empty: none).
std::vector<remesh_detail::SteinerMesh> allocate_steiner(const std::vector<Facet>& facets, const std::vector<double>& base,
                                                         std::size_t points, double min_area) {
  std::vector<remesh_detail::SteinerMesh> chosen(facets.size());
  std::vector<std::vector<remesh_detail::SteinerMesh>> seq(facets.size());
  for (std::size_t i = 0; i < facets.size(); ++i)
    if (facets[i].area >= min_area && facets[i].loop.size() >= 4) seq[i] = remesh_detail::refine_convex_polygon(facets[i].q, std::min(points, kMaxSteinerPerFacet));
  std::vector<std::size_t> used(facets.size(), 0);
  std::vector<double> now = base;
  std::size_t left = points;
  while (left > 0) {
    double best = 0;
    std::size_t bi = 0, bk = 0;
    for (std::size_t i = 0; i < facets.size(); ++i)
      for (std::size_t k = used[i] + 1; k <= seq[i].size() && k - used[i] <= left; ++k) {
        const double rate = (seq[i][k - 1].score - now[i]) / double(k - used[i]);
        if (rate > best) best = rate, bi = i, bk = k;
      }
    if (!(best > 0)) break;
    left -= bk - used[bi];
    used[bi] = bk;
    now[bi] = seq[bi][bk - 1].score;
    chosen[bi] = seq[bi][bk - 1];
  }
  return chosen;
}

}  // namespace

namespace {

// The hull of the mesh with the plans' facets domed (each facet's plans tried in turn until one
// can be placed); false when the result fails a check: it must keep every vertex, enclose every
// vertex that did not sink, fit the volume bound and the face allowance, and be fatter.
bool realise(const Mesh& mesh, const ShellConstraints& constraints, const FlatFacetOptions& options, const Groups& g,
             const std::vector<std::vector<Plan>>& plans, std::size_t steiner_points, FlatFacetStats& st, Mesh& out) {
  std::vector<char> domed(g.faces.size(), 0);
  for (const std::vector<Plan>& tries : plans) domed[std::size_t(tries.front().k)] = 1;
  std::vector<Point3> pts = mesh_points(mesh);  // moved in place, by vertex index; Steiner points appended
  std::vector<char> sank(pts.size(), 0);
  for (const std::vector<Plan>& tries : plans) {
    bool done = false;
    for (const Plan& plan : tries) {
      // Outward when the constraints allow it (nothing is given up), else inward.
      for (int side : {+1, -1}) {
        if (side < 0 && (!options.allow_inward || plan.depth > options.max_sink * plan.diam)) break;
        const Vec w = side * g.normal[std::size_t(plan.k)];
        std::vector<Point3> moved, extra;
        bool ok = true;
        for (std::size_t i = 0; i < plan.loop.size() && ok; ++i) {
          // Outward a concave cap, inward a convex dent: either way the hull's faces there are the
          // triangulation (the heights are convex over it).
          const double rise = plan.depth * (side > 0 ? 1 - plan.h[i] : plan.h[i]);
          if (!plan.extra.empty() && rise <= 1e-6 * plan.depth) {  // a Steiner dome's corner that stays
            moved.push_back(pts[plan.loop[i].idx()]);
            continue;
          }
          const Vec u = move_direction(mesh, g, domed, plan.k, plan.loop[i], w, side > 0);
          // Added to where an earlier facet may have moved this corner (within this facet's plane).
          const Vec x = vec(pts[plan.loop[i].idx()]) + rise * u;
          moved.emplace_back(x.x(), x.y(), x.z());
          ok = u.squaredNorm() > 0 && constraints.satisfied_by(moved.back());
        }
        for (std::size_t j = 0; j < plan.extra.size() && ok; ++j) {
          // A Steiner point rounded a unit past a constraint plane goes a few units further in,
          // far less than its margin above the hull of the others.
          const double rise = plan.depth * (side > 0 ? 1 - plan.h[plan.loop.size() + j] : plan.h[plan.loop.size() + j]);
          const Vec x = plan.extra[j] + rise * w;
          const double unit = ulp_noise({x});
          ok = false;
          for (double push : {0.0, 1.0, 2.0, 4.0}) {
            const Vec y = x - push * unit * g.normal[std::size_t(plan.k)];
            const Point3 pt(y.x(), y.y(), y.z());
            if (constraints.satisfied_by(pt)) { extra.push_back(pt); ok = true; break; }
          }
        }
        if (!ok) continue;
        for (std::size_t i = 0; i < plan.loop.size(); ++i) {
          const V v = plan.loop[i];
          if (side < 0) {
            sank[v.idx()] = 1;
            st.max_inward = std::max(st.max_inward, (vec(moved[i]) - vec(mesh.point(v))).norm());
          }
          pts[v.idx()] = moved[i];
        }
        pts.insert(pts.end(), extra.begin(), extra.end());
        st.steiner += extra.size();
        ++(side > 0 ? st.outward : st.inward);
        done = true;
        break;
      }
      if (done) break;
    }
  }
  if (st.outward + st.inward == 0) return false;
  // Accept only a hull that kept every vertex, encloses every vertex that did not sink, fits the
  // volume bound and is fatter. A corner moved within a neighbouring face's plane may leave its
  // old place a rounding unit outside: such corners are pushed out a few units more.
  std::vector<Point3> keep;
  std::vector<V> keep_v;
  for (V v : mesh.vertices())
    if (!sank[v.idx()]) keep.push_back(mesh.point(v)), keep_v.push_back(v);
  for (int round = 0;; ++round) {
    out = convex_hull_mesh(pts);
    if (out.number_of_vertices() != pts.size()) return false;
    std::vector<V> outside;
    for (std::size_t i : remesh_detail::points_outside(out, keep)) outside.push_back(keep_v[i]);
    if (outside.empty()) break;
    if (round == 8) return false;
    for (V v : outside) {
      Vec normal = Vec::Zero();
      for (F f : CGAL::faces_around_target(mesh.halfedge(v), mesh)) normal += g.normal[std::size_t(g.of_face[f.idx()])];
      const Vec x = vec(pts[v.idx()]) + std::ldexp(ulp_noise({vec(pts[v.idx()])}), round) * normal.normalized();
      pts[v.idx()] = Point3(x.x(), x.y(), x.z());
      if (!constraints.satisfied_by(pts[v.idx()])) return false;
    }
  }
  if (!options.enclose.empty() && !remesh_detail::mesh_encloses(out, options.enclose)) return false;
  if (options.max_volume > 0 && remesh_detail::mesh_volume(out) > options.max_volume) return false;
  if (out.number_of_faces() > mesh.number_of_faces() + 2 * steiner_points) return false;
  const double fat = weighted_fatness(out);
  if (!(fat > st.fatness_before)) return false;
  st.fatness_after = fat;
  return true;
}

// One attempt with at most `steiner_points` interior points; false (mesh unchanged) when the
// result would fail a check.
bool fatten(const Mesh& mesh, const ShellConstraints& constraints, const FlatFacetOptions& options,
            std::size_t steiner_points, FlatFacetStats& st, Mesh& out) {
  const Groups g = flat_groups(mesh, options.flat_angle);
  std::vector<Facet> facets;
  std::vector<double> base;  // each facet's best score without Steiner points
  std::vector<Triangulation> tri;
  double total_area = 0;
  for (double a : g.area) total_area += a;
  for (int k = 0; k < int(g.faces.size()); ++k) {
    st.facets += g.faces[k].size() >= 2;
    Facet fc;
    if (!facet_geometry(mesh, g, k, fc)) continue;
    Triangulation t;
    if (g.faces[k].size() >= 2 && fc.loop.size() >= 4) t = fattest_triangulation(
        [&] { std::vector<Vec> p; for (V v : fc.loop) p.push_back(vec(mesh.point(v))); return p; }(), fc.q,
        1e-10 * fc.diam * fc.diam);
    base.push_back(std::max(fc.current, t.score));
    tri.push_back(std::move(t));
    facets.push_back(std::move(fc));
  }
  // Only facets big enough to matter get Steiner points (the refinement costs time).
  const std::vector<remesh_detail::SteinerMesh> steiner =
      steiner_points > 0 ? allocate_steiner(facets, base, steiner_points, kMinSteinerArea * total_area)
                         : std::vector<remesh_detail::SteinerMesh>(facets.size());
  // Per facet the plans to try in turn: with Steiner points, then its corners only.
  std::vector<std::vector<Plan>> plans;
  std::vector<double> gain;  // planned gain in area x fatness of each facet's first plan
  for (std::size_t i = 0; i < facets.size(); ++i) {
    std::vector<Plan> tries;
    Plan with, without;
    if (!steiner[i].interior.empty() && plan_steiner(facets[i], steiner[i], options, with)) tries.push_back(std::move(with));
    if (plan_corners(facets[i], tri[i], options, without)) tries.push_back(std::move(without));
    if (tries.empty()) continue;
    gain.push_back((steiner[i].interior.empty() ? base[i] : steiner[i].score) - facets[i].current);
    plans.push_back(std::move(tries));
  }
  if (plans.empty()) return false;
  FlatFacetStats all = st;
  if (realise(mesh, constraints, options, g, plans, steiner_points, all, out)) {
    st = all;
    return true;
  }
  // One facet's dome can spoil the whole result (a corner it moves leaves an old vertex outside
  // where no push is allowed, a vertex drops off the hull, the result is less fat): on Bowser's
  // pipeline shells 8 of 28 final domes were rejected whole, about half of the planned gain. So
  // facets are then added one at a time, largest planned gain first, each kept only when the
  // result with it passes every check and is fatter than without it; each of a facet's plans
  // (Steiner points first) is tried in turn. At most kMaxFallbackTries results are computed
  // (each costs a hull and an enclosure check of the shell). Dropping only the facets around the
  // vertices that failed and keeping the rest was tried: less fat on 6 of 8 models (Bulbasaur
  // +25.5% instead of +29.6%), some domes that pass together still lower the fatness.
  std::vector<std::size_t> order(plans.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return gain[a] > gain[b]; });
  std::vector<std::vector<Plan>> kept;
  FlatFacetStats best = st;
  bool any = false;
  std::size_t tries = 0;
  for (std::size_t i : order) {
    for (const Plan& plan : plans[i]) {
      if (tries++ >= kMaxFallbackTries) break;
      kept.push_back({plan});
      FlatFacetStats s = st;
      Mesh o;
      if (realise(mesh, constraints, options, g, kept, steiner_points, s, o) && s.fatness_after > best.fatness_after) {
        best = s, out = std::move(o), any = true;
        break;
      }
      kept.pop_back();
    }
  }
  if (!any) return false;
  st = best;
  return true;
}

}  // namespace

Mesh fatten_flat_facets(const Mesh& mesh, const ShellConstraints& constraints, const FlatFacetOptions& options,
                        FlatFacetStats* stats) {
  FlatFacetStats st;
  st.fatness_before = st.fatness_after = weighted_fatness(mesh);
  if (stats) *stats = st;
  if (mesh.is_empty() || mesh.has_garbage()) return mesh;
  // With Steiner points first; should that fail a check, without.
  for (std::size_t points : {options.extra_faces / 2, std::size_t(0)}) {
    FlatFacetStats s = st;
    Mesh out;
    if (fatten(mesh, constraints, options, points, s, out)) {
      if (stats) *stats = s;
      return out;
    }
    if (points == 0) break;
  }
  return mesh;
}

}  // namespace dcshell
