// Double-precision B-rep clipping of convex polytopes.
#include "dcshell/polytope_clip.h"

#include "dcshell/convex_hull.h"

#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace dcshell {

namespace {

Eigen::Vector3d to_eigen(const Point3& p) { return {p.x(), p.y(), p.z()}; }

Eigen::Vector3d vertex_mean(const std::vector<Eigen::Vector3d>& v) {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& x : v) m += x;
  return v.empty() ? m : Eigen::Vector3d(m / double(v.size()));
}

std::uint64_t edge_key(int u, int v) { return (std::uint64_t(std::uint32_t(u)) << 32) | std::uint32_t(v); }

// Orders the points of a planar convex polygon counter-clockwise seen from the side `n`
// points to. Used when the boundary of the clipped faces does not chain into one loop (only
// possible through tolerance effects); the section of a convex polytope is convex anyway.
std::vector<int> angular_loop(const std::vector<Eigen::Vector3d>& pts, std::vector<int> ids,
                              const Eigen::Vector3d& n) {
  if (ids.size() < 3) return {};
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i : ids) c += pts[i];
  c /= double(ids.size());
  Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.normalized().cross(e1);
  std::vector<std::pair<double, int>> ang;
  for (int i : ids) ang.emplace_back(std::atan2((pts[i] - c).dot(e2), (pts[i] - c).dot(e1)), i);
  std::sort(ang.begin(), ang.end());
  std::vector<int> loop;
  for (auto& a : ang) loop.push_back(a.second);
  return loop;
}

}  // namespace

ConvexPolytope polytope_from_mesh(const Mesh& mesh, int tag) {
  ConvexPolytope p;
  std::vector<int> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), -1);
  for (auto v : mesh.vertices()) {
    index[v.idx()] = int(p.vertices.size());
    p.vertices.push_back(to_eigen(mesh.point(v)));
  }
  for (auto f : mesh.faces()) {
    std::vector<int> loop;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) loop.push_back(index[v.idx()]);
    p.faces.push_back(std::move(loop));
    p.face_tags.push_back(tag);
  }
  return p;
}

ConvexPolytope convex_hull_polytope(const std::vector<Eigen::Vector3d>& points, int tag) {
  std::vector<Point3> pts;
  pts.reserve(points.size());
  for (const auto& q : points) pts.emplace_back(q.x(), q.y(), q.z());
  // convex_hull_mesh returns a canonically ordered hull, so the polytope is too.
  Mesh hull = convex_hull_mesh(pts);
  if (hull.number_of_faces() < 4 || !CGAL::is_closed(hull)) return {};
  ConvexPolytope p = polytope_from_mesh(hull, tag);
  if (!(volume(p) > 0.0)) return {};
  return p;
}

Mesh to_mesh(const ConvexPolytope& p) {
  Mesh m;
  std::vector<Mesh::Vertex_index> vs;
  for (const auto& v : p.vertices) vs.push_back(m.add_vertex(Point3(v.x(), v.y(), v.z())));
  for (const auto& f : p.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) m.add_face(vs[f[0]], vs[f[i]], vs[f[i + 1]]);
  m.collect_garbage();
  return m;
}

CutPlane face_plane(const ConvexPolytope& p, std::size_t f) {
  // Newell's normal: exact for planar polygons and a least-squares-like average otherwise.
  const auto& loop = p.faces[f];
  Eigen::Vector3d n = Eigen::Vector3d::Zero(), c = Eigen::Vector3d::Zero();
  for (int v : loop) c += p.vertices[v];
  c /= double(loop.size());
  for (std::size_t i = 0; i < loop.size(); ++i)  // relative to c: no cancellation far from 0
    n += (p.vertices[loop[i]] - c).cross(p.vertices[loop[(i + 1) % loop.size()]] - c);
  const double len = n.norm();
  if (len > 0) n /= len;
  return {n, n.dot(c)};
}

ConvexPolytope clip(const ConvexPolytope& p, const CutPlane& plane, int cap_tag) {
  if (p.empty()) return {};
  const std::size_t nv = p.vertices.size();
  std::vector<double> s(nv);
  double smin = std::numeric_limits<double>::infinity(), smax = -smin, mag = std::fabs(plane.offset);
  const double nn = plane.normal.norm();
  for (std::size_t i = 0; i < nv; ++i) {
    s[i] = plane.eval(p.vertices[i]);
    smin = std::min(smin, s[i]);
    smax = std::max(smax, s[i]);
    mag = std::max(mag, nn * p.vertices[i].lpNorm<Eigen::Infinity>());
  }
  // Tolerance: rounding error of eval() plus a tiny fraction of the extent along the normal, so
  // nearly touching planes do not create sliver faces.
  const double tol = std::max(64 * std::numeric_limits<double>::epsilon() * mag, 1e-12 * (smax - smin));
  if (smax <= tol) return p;          // nothing outside: unchanged
  if (smin >= -tol) return {};        // nothing strictly inside: no volume left
  // -1 inside, 0 on, +1 outside
  std::vector<int> side(nv);
  for (std::size_t i = 0; i < nv; ++i) side[i] = s[i] < -tol ? -1 : (s[i] > tol ? 1 : 0);

  ConvexPolytope out;
  std::vector<int> remap(nv, -1);
  // Per new vertex: does it lie on the plane (a crossing or an original vertex within tol)?
  // Only an edge between two such vertices can bound the cap: an edge with an end strictly
  // inside is kept by both faces around it (as it was, or up to the same crossing point).
  std::vector<char> on;
  on.reserve(nv);
  auto keep_vertex = [&](int v) {
    if (remap[v] < 0) {
      remap[v] = int(out.vertices.size());
      out.vertices.push_back(p.vertices[v]);
      on.push_back(side[v] == 0);
    }
    return remap[v];
  };
  std::unordered_map<std::uint64_t, int> crossing;
  auto cross_vertex = [&](int u, int w) {
    if (u > w) std::swap(u, w);  // the same point for both faces of the edge
    auto [it, inserted] = crossing.emplace(edge_key(u, w), int(out.vertices.size()));
    if (inserted) {
      const double t = s[u] / (s[u] - s[w]);
      out.vertices.push_back(p.vertices[u] + t * (p.vertices[w] - p.vertices[u]));
      on.push_back(1);
    }
    return it->second;
  };

  std::unordered_set<std::uint64_t> directed;
  std::vector<int> on_plane;  // new ids of points lying on the plane (for the fallback cap)
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    const auto& loop = p.faces[f];
    std::vector<int> nl;
    bool any_in = false;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int u = loop[i], w = loop[(i + 1) % loop.size()];
      if (side[u] <= 0) nl.push_back(keep_vertex(u));
      any_in |= side[u] < 0;
      if (side[u] * side[w] < 0) nl.push_back(cross_vertex(u, w));
    }
    // A face lying in the plane would duplicate the cap; faces with no inside vertex and no
    // crossing collapse into the plane.
    if (!any_in) continue;
    nl.erase(std::unique(nl.begin(), nl.end()), nl.end());
    while (nl.size() > 1 && nl.front() == nl.back()) nl.pop_back();
    if (nl.size() < 3) continue;
    for (std::size_t i = 0; i < nl.size(); ++i) {
      const int a = nl[i], b = nl[(i + 1) % nl.size()];
      if (on[a] && on[b]) directed.insert(edge_key(a, b));
    }
    out.faces.push_back(std::move(nl));
    out.face_tags.push_back(f < p.face_tags.size() ? p.face_tags[f] : 0);
  }
  // The cap: boundary edges of the kept faces (no twin), reversed, chained into a loop.
  std::unordered_map<int, int> next;
  bool chain_ok = true;
  for (const auto& f : out.faces)
    for (std::size_t i = 0; i < f.size(); ++i) {
      const int u = f[i], w = f[(i + 1) % f.size()];
      if (on[u] && on[w] && !directed.count(edge_key(w, u))) chain_ok &= next.emplace(w, u).second;
    }
  std::vector<int> cap;
  if (chain_ok && next.size() >= 3) {
    int v = next.begin()->first;
    for (std::size_t k = 0; k <= next.size(); ++k) {
      cap.push_back(v);
      auto it = next.find(v);
      if (it == next.end()) { chain_ok = false; break; }
      v = it->second;
      if (v == cap.front()) break;
    }
    chain_ok &= cap.size() == next.size() && v == cap.front();
  } else {
    chain_ok = false;
  }
  if (!chain_ok) {
    for (std::size_t i = 0; i < nv; ++i)
      if (side[i] == 0 && remap[i] >= 0) on_plane.push_back(remap[i]);
    for (const auto& kv : crossing) on_plane.push_back(kv.second);
    std::sort(on_plane.begin(), on_plane.end());
    cap = angular_loop(out.vertices, on_plane, plane.normal);
  }
  if (cap.size() >= 3) {
    out.faces.push_back(std::move(cap));
    out.face_tags.push_back(cap_tag);
  }
  if (out.faces.size() < 4) return {};
  if (p.face_tags.empty()) out.face_tags.clear();
  return out;
}

ConvexPolytope intersect(const ConvexPolytope& p, const ConvexPolytope& q) {
  if (p.empty() || q.empty()) return {};
  // Disjoint bounding boxes: empty without clipping.
  Eigen::AlignedBox3d bp, bq;
  for (const auto& v : p.vertices) bp.extend(v);
  for (const auto& v : q.vertices) bq.extend(v);
  if (!bp.intersects(bq)) return {};
  // Clip the polytope with fewer vertices by the planes of the other (same set, same tags,
  // much less copying when one of them is large).
  const bool swap = q.vertices.size() < p.vertices.size();
  const ConvexPolytope& clipper = swap ? p : q;
  const int clipper_default = swap ? 0 : 1;
  ConvexPolytope r = swap ? q : p;
  if (r.face_tags.size() != r.faces.size()) r.face_tags.assign(r.faces.size(), swap ? 1 : 0);
  // The planes that cut deepest into r first: r then shrinks to about the overlap at once, and
  // the later clips copy a small polytope, not the whole of r (two hulls of 2,000 points whose
  // overlap is bounded by hundreds of faces of each: 600 copies of a 2,000-vertex polytope).
  // A plane that misses r misses every part of it, so it is never needed.
  std::vector<std::pair<double, std::size_t>> order;
  std::vector<CutPlane> planes(clipper.faces.size());
  for (std::size_t f = 0; f < clipper.faces.size(); ++f) {
    const CutPlane& h = planes[f] = face_plane(clipper, f);
    const double mag = std::fabs(h.offset) + r.vertices[0].lpNorm<Eigen::Infinity>();
    double deepest = -std::numeric_limits<double>::infinity();
    for (const auto& v : r.vertices) deepest = std::max(deepest, h.eval(v));
    if (deepest > 1e-12 * mag) order.emplace_back(-deepest / h.normal.norm(), f);
  }
  std::stable_sort(order.begin(), order.end());
  for (std::size_t k = 0; k < order.size() && !r.empty(); ++k) {
    const std::size_t f = order[k].second;
    const CutPlane& h = planes[f];
    // Planes that cut the first r may miss what is left: test before clip() copies r.
    const double mag = std::fabs(h.offset) + r.vertices[0].lpNorm<Eigen::Infinity>();
    bool cuts = false;
    for (const auto& v : r.vertices)
      if (h.eval(v) > 1e-12 * mag) {
        cuts = true;
        break;
      }
    if (cuts) r = clip(r, h, f < clipper.face_tags.size() ? clipper.face_tags[f] : clipper_default);
  }
  return r;
}

ConvexPolytope tagged_intersection(const ConvexPolytope& a, const ConvexPolytope& b) {
  ConvexPolytope ta = a, tb = b;
  ta.face_tags.assign(ta.faces.size(), 0);
  tb.face_tags.assign(tb.faces.size(), 1);
  return intersect(ta, tb);
}

double volume(const ConvexPolytope& p) {
  if (p.empty()) return 0.0;
  const Eigen::Vector3d r = p.vertices[p.faces[0][0]];
  double v = 0.0;
  for (const auto& f : p.faces) {
    const Eigen::Vector3d a = p.vertices[f[0]] - r;
    for (std::size_t i = 1; i + 1 < f.size(); ++i)
      v += a.dot((p.vertices[f[i]] - r).cross(p.vertices[f[i + 1]] - r));
  }
  return v / 6.0;
}

Eigen::Vector3d centroid(const ConvexPolytope& p) {
  const Eigen::Vector3d r = vertex_mean(p.vertices);
  if (p.empty()) return r;
  double vol = 0.0;
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& f : p.faces) {
    const Eigen::Vector3d a = p.vertices[f[0]] - r;
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      const Eigen::Vector3d b = p.vertices[f[i]] - r, c = p.vertices[f[i + 1]] - r;
      const double t = a.dot(b.cross(c));
      vol += t;
      m += t * (a + b + c) / 4.0;
    }
  }
  return vol > 0 ? Eigen::Vector3d(r + m / vol) : r;
}

std::pair<double, double> height_range(const ConvexPolytope& p, const Eigen::Vector3d& n) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& v : p.vertices) {
    const double h = n.dot(v);
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  return {lo, hi};
}

PlaneSection section(const ConvexPolytope& p, const CutPlane& plane) {
  PlaneSection sec;
  if (p.empty()) return sec;
  const double nn = plane.normal.norm();
  if (!(nn > 0)) return sec;
  const Eigen::Vector3d n = plane.normal / nn;
  std::vector<double> s(p.vertices.size());
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = plane.eval(p.vertices[i]);
  // Reference point on the plane near the polytope: keeps the fan terms small.
  Eigen::Vector3d r = vertex_mean(p.vertices);
  r -= (plane.eval(r) / nn) * n;
  auto cross_point = [&](int u, int w) {
    const double t = s[u] / (s[u] - s[w]);
    return Eigen::Vector3d(p.vertices[u] + t * (p.vertices[w] - p.vertices[u]) - r);
  };
  // Each face crossing the plane contributes one oriented edge of the section polygon
  // (from where its loop goes down to where it goes up, counter-clockwise about n); the
  // area and moment are boundary sums, so the edges need not be chained.
  for (const auto& f : p.faces) {
    int up = -1, down = -1;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const bool a = s[f[i]] > 0, b = s[f[(i + 1) % f.size()]] > 0;
      if (!a && b) up = int(i);
      if (a && !b) down = int(i);
    }
    if (up < 0 || down < 0) continue;
    const Eigen::Vector3d pu = cross_point(f[up], f[(up + 1) % f.size()]);
    const Eigen::Vector3d pd = cross_point(f[down], f[(down + 1) % f.size()]);
    const double area = 0.5 * n.dot(pd.cross(pu));
    sec.area += area;
    sec.moment += area * (pd + pu) / 3.0;
  }
  sec.moment += sec.area * r;
  return sec;
}

}  // namespace dcshell
