// Exact convex polytope operations (Epeck). See exact_polytope.h for the representation.
#include "dcshell/exact_polytope.h"

#include <CGAL/convex_hull_3.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

#include "dcshell/convex_hull.h"

namespace dcshell {

namespace {

using EPoint = Epeck::Point_3;
using EPlane = Epeck::Plane_3;

std::uint64_t edge_key(int u, int v) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32) | static_cast<std::uint32_t>(v);
}

// Meet of three planes known to cross in a single point (two faces meeting along an edge and a
// plane that strictly separates the edge's endpoints).
EPoint meet(const EPlane& a, const EPlane& b, const EPlane& c) {
  auto r = CGAL::intersection(a, b, c);
  if (r) {
    if (const EPoint* p = boost::get<EPoint>(&*r)) return *p;
  }
  throw std::logic_error("exact polytope: face planes do not meet in a point (corrupt polytope)");
}

}  // namespace

CGAL::Oriented_side side(const EPlane& h, const EPoint& q) { return h.oriented_side(q); }

EPlane exact_plane(const CutPlane& p) {
  // normal·x - offset: the doubles are converted exactly.
  return EPlane(p.normal.x(), p.normal.y(), p.normal.z(), -p.offset);
}

ExactPolytope exact_hull(const std::vector<Point3>& points, int tag) {
  ExactPolytope out;
  Mesh hull = convex_hull_mesh(points);
  if (hull.number_of_faces() == 0) return out;
  // Merge coplanar adjacent triangles so that every edge lies between two non-parallel
  // planes: clipping then always creates vertices as a meet of three planes.
  std::vector<int> group(hull.number_of_faces());
  std::iota(group.begin(), group.end(), 0);
  std::function<int(int)> find = [&](int x) { return group[x] == x ? x : group[x] = find(group[x]); };
  for (auto e : hull.edges()) {
    auto h = hull.halfedge(e);
    auto f0 = hull.face(h), f1 = hull.face(hull.opposite(h));
    const Point3& a = hull.point(hull.source(h));
    const Point3& b = hull.point(hull.target(h));
    const Point3& c = hull.point(hull.target(hull.next(h)));
    const Point3& d = hull.point(hull.target(hull.next(hull.opposite(h))));
    if (CGAL::orientation(a, b, c, d) == CGAL::COPLANAR) group[find(int(f0))] = find(int(f1));
  }
  out.vertices.reserve(hull.number_of_vertices());
  for (auto v : hull.vertices()) {
    const Point3& p = hull.point(v);
    out.vertices.emplace_back(p.x(), p.y(), p.z());
  }
  // Boundary of each group: halfedges whose opposite face is in another group, chained.
  std::map<int, std::unordered_map<int, int>> next_of;  // group -> (source -> target)
  for (auto h : hull.halfedges()) {
    auto f = hull.face(h), g = hull.face(hull.opposite(h));
    if (find(int(f)) == find(int(g))) continue;
    next_of[find(int(f))][int(hull.source(h))] = int(hull.target(h));
  }
  for (auto& [gid, nxt] : next_of) {
    ExactPolytope::Face face;
    // A deterministic start: the smallest vertex index of the loop.
    int start = std::min_element(nxt.begin(), nxt.end())->first;
    int v = start;
    do {
      face.loop.push_back(v);
      v = nxt.at(v);
    } while (v != start && face.loop.size() <= nxt.size());
    auto fh = hull.halfedge(Mesh::Face_index(gid));
    face.plane = EPlane(out.vertices[hull.source(fh)], out.vertices[hull.target(fh)],
                        out.vertices[hull.target(hull.next(fh))]);
    face.tag = tag;
    out.faces.push_back(std::move(face));
  }
  return out;
}

namespace {

using Interval = CGAL::Interval_nt<false>;

// h's coefficients as intervals, evaluated at interval points (a vertex's approximation, or a
// box). The caller holds a rounding guard (CGAL::Protect_FPU_rounding) while evaluating.
struct IntervalPlane {
  Interval a, b, c, d;
  explicit IntervalPlane(const EPlane& h)
      : a(CGAL::approx(h.a())), b(CGAL::approx(h.b())), c(CGAL::approx(h.c())), d(CGAL::approx(h.d())) {}
  Interval at(const Interval& x, const Interval& y, const Interval& z) const { return a * x + b * y + c * z + d; }
};

// Side of every vertex of p with respect to h: interval approximations under one rounding
// guard, the exact predicate only where they do not decide.
struct VertexSides {
  std::vector<CGAL::Oriented_side> s;
  bool any_neg = false, any_pos = false;
};
VertexSides vertex_sides(const ExactPolytope& p, const EPlane& h) {
  VertexSides r;
  const std::size_t n = p.vertices.size();
  r.s.assign(n, CGAL::ON_ORIENTED_BOUNDARY);
  std::vector<std::size_t> undecided;
  {
    CGAL::Protect_FPU_rounding<true> guard;
    const IntervalPlane plane(h);
    for (std::size_t i = 0; i < n; ++i) {
      const auto& q = CGAL::approx(p.vertices[i]);
      const Interval v = plane.at(q.x(), q.y(), q.z());
      if (v.inf() > 0) r.s[i] = CGAL::ON_POSITIVE_SIDE;
      else if (v.sup() < 0) r.s[i] = CGAL::ON_NEGATIVE_SIDE;
      else undecided.push_back(i);
    }
  }
  for (std::size_t i : undecided) r.s[i] = h.oriented_side(p.vertices[i]);
  for (auto x : r.s) {
    r.any_neg |= x == CGAL::ON_NEGATIVE_SIDE;
    r.any_pos |= x == CGAL::ON_POSITIVE_SIDE;
  }
  return r;
}

// p ∩ {h <= 0} when h has vertices strictly on both sides (`s` from vertex_sides). Runs once
// per plane of an intersection, so it avoids per-face hashing and regrowth: lookups go through
// the sorted list of crossed edges, and every buffer is sized up front.
ExactPolytope cut(const ExactPolytope& p, const EPlane& h, int tag, const std::vector<CGAL::Oriented_side>& s) {
  const int n = static_cast<int>(p.vertices.size());
  // The directed edges that h crosses, each with the face it belongs to, sorted for lookup; the
  // far face of u -> v owns v -> u, and both directions share the new vertex.
  struct Crossed {
    std::uint64_t key;
    int face;
  };
  std::vector<Crossed> crossed;
  auto crosses = [&](int u, int v) {  // strictly opposite sides
    return s[u] != CGAL::ON_ORIENTED_BOUNDARY && s[v] != CGAL::ON_ORIENTED_BOUNDARY && s[u] != s[v];
  };
  for (int f = 0; f < int(p.faces.size()); ++f) {
    const auto& L = p.faces[f].loop;
    for (std::size_t k = 0; k < L.size(); ++k) {
      const int u = L[k], v = L[(k + 1) % L.size()];
      if (crosses(u, v)) crossed.push_back({edge_key(u, v), f});
    }
  }
  std::sort(crossed.begin(), crossed.end(), [](const Crossed& x, const Crossed& y) { return x.key < y.key; });
  auto find = [&](int u, int v) {
    const std::uint64_t key = edge_key(u, v);
    auto it = std::lower_bound(crossed.begin(), crossed.end(), key,
                               [](const Crossed& c, std::uint64_t k) { return c.key < k; });
    if (it == crossed.end() || it->key != key) throw std::logic_error("exact polytope: edge without a far face");
    return static_cast<std::size_t>(it - crossed.begin());
  };
  std::vector<int> new_vertex(crossed.size(), -1);  // per directed crossed edge

  // Output vertices: the kept ones in the order first met, and one per crossed edge.
  const std::size_t most = std::size_t(n) + crossed.size() / 2;
  ExactPolytope out;
  out.vertices.reserve(most);
  out.faces.reserve(p.faces.size() + 1);
  std::vector<int> remap(n, -1);
  std::vector<char> on_h(most, 0);
  auto keep = [&](int v) {
    if (remap[v] < 0) {
      remap[v] = int(out.vertices.size());
      out.vertices.push_back(p.vertices[v]);
    }
    return remap[v];
  };

  std::vector<int> cap_next(most, -1);  // cap boundary, directed: from -> to
  std::size_t cap_edges = 0;
  bool face_on_h = false;
  for (int f = 0; f < int(p.faces.size()); ++f) {
    const auto& F = p.faces[f];
    const auto& L = F.loop;
    std::vector<int> loop;
    loop.reserve(L.size() + 1);  // a convex polygon clipped by a line gains at most one corner
    bool all_zero = true;
    for (std::size_t k = 0; k < L.size(); ++k) {
      int u = L[k], v = L[(k + 1) % L.size()];
      all_zero &= s[u] == CGAL::ON_ORIENTED_BOUNDARY;
      if (s[u] != CGAL::ON_POSITIVE_SIDE) {
        int iu = keep(u);
        on_h[iu] = s[u] == CGAL::ON_ORIENTED_BOUNDARY;
        loop.push_back(iu);
      }
      if (crosses(u, v)) {
        const std::size_t here = find(u, v);
        int idx = new_vertex[here];
        if (idx < 0) {
          const std::size_t there = find(v, u);
          idx = int(out.vertices.size());
          out.vertices.push_back(meet(F.plane, p.faces[crossed[there].face].plane, h));
          on_h[idx] = 1;
          new_vertex[here] = new_vertex[there] = idx;
        }
        loop.push_back(idx);
      }
    }
    if (all_zero) face_on_h = true;  // this face already is the cap
    if (loop.size() < 3) continue;   // face clipped away or reduced to an edge/point
    if (!all_zero) {
      for (std::size_t k = 0; k < loop.size(); ++k) {
        int a = loop[k], b = loop[(k + 1) % loop.size()];
        if (on_h[a] && on_h[b]) {  // the cap runs the other way round
          cap_edges += cap_next[b] < 0;
          cap_next[b] = a;
        }
      }
    }
    out.faces.push_back({F.plane, std::move(loop), F.tag});
  }
  if (!face_on_h && cap_edges >= 3) {
    ExactPolytope::Face cap;
    cap.plane = h;
    cap.tag = tag;
    cap.loop.reserve(cap_edges);
    const int start = int(std::find_if(cap_next.begin(), cap_next.end(), [](int x) { return x >= 0; }) - cap_next.begin());
    int v = start;
    do {
      cap.loop.push_back(v);
      v = cap_next[v];
      if (v < 0) throw std::logic_error("exact polytope: open cap boundary");
    } while (v != start && cap.loop.size() <= cap_edges);
    out.faces.push_back(std::move(cap));
  }
  return out;
}

}  // namespace

ExactPolytope clip(const ExactPolytope& p, const EPlane& h, int tag) {
  const VertexSides vs = vertex_sides(p, h);
  if (!vs.any_neg) return {};  // nothing of the interior is strictly inside h
  if (!vs.any_pos) return p;   // h does not cut the interior
  return cut(p, h, tag, vs.s);
}

namespace {

// Conservative box of a polytope's vertices, from their interval approximations.
struct IntervalBox {
  Interval x, y, z;
};
IntervalBox interval_box(const ExactPolytope& p) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const auto& v : p.vertices) {
    const auto& q = CGAL::approx(v);  // the interval point: no lazy number per coordinate
    const Interval c[3] = {q.x(), q.y(), q.z()};
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], c[d].inf());
      hi[d] = std::max(hi[d], c[d].sup());
    }
  }
  return {{lo[0], hi[0]}, {lo[1], hi[1]}, {lo[2], hi[2]}};
}

// True when the whole box is certainly strictly below h: clipping by h then changes nothing.
bool box_strictly_below(const IntervalBox& b, const EPlane& h) {
  CGAL::Protect_FPU_rounding<true> guard;
  return IntervalPlane(h).at(b.x, b.y, b.z).sup() < 0;
}

}  // namespace

ExactPolytope intersect(const ExactPolytope& a, const ExactPolytope& b) {
  if (a.empty() || b.empty()) return {};
  ExactPolytope r = a;
  IntervalBox box = interval_box(r);
  // b's planes deepest into a first (by how far the centre of a's box lies above each, in
  // doubles: only the order depends on it). Two round hulls then shrink r to their lens within
  // a few cuts, and the box test skips most planes after that, where b's own order had every
  // plane facing a classify all of a's vertices until one cut deep enough.
  std::vector<std::pair<double, std::size_t>> order(b.faces.size());
  {
    const double x = 0.5 * (box.x.inf() + box.x.sup()), y = 0.5 * (box.y.inf() + box.y.sup()),
                 z = 0.5 * (box.z.inf() + box.z.sup());
    for (std::size_t i = 0; i < b.faces.size(); ++i) {
      const IntervalPlane h(b.faces[i].plane);
      const double pa = CGAL::to_double(h.a), pb = CGAL::to_double(h.b), pc = CGAL::to_double(h.c);
      const double n = std::sqrt(pa * pa + pb * pb + pc * pc);
      const double above = n > 0 ? (pa * x + pb * y + pc * z + CGAL::to_double(h.d)) / n : 0.0;
      order[i] = {std::isfinite(above) ? -above : 0.0, i};
    }
    std::sort(order.begin(), order.end());
  }
  for (const auto& [depth, i] : order) {
    const auto& f = b.faces[i];
    // Most planes of a large b miss r: an interval test on r's box skips them without
    // classifying r's vertices, and a plane that passes no vertex costs no copy of r.
    if (box_strictly_below(box, f.plane)) continue;
    const VertexSides vs = vertex_sides(r, f.plane);
    if (!vs.any_pos) continue;
    if (!vs.any_neg) return {};
    r = cut(r, f.plane, f.tag, vs.s);
    if (r.empty()) return {};
    box = interval_box(r);
  }
  return r;
}

ExactRational exact_volume(const ExactPolytope& p) {
  if (p.empty()) return ExactRational(0);
  using EK = CGAL::Exact_predicates_exact_constructions_kernel::Exact_kernel;
  std::vector<EK::Point_3> q;
  q.reserve(p.vertices.size());
  for (const auto& v : p.vertices) q.push_back(CGAL::exact(v));
  const EK::Point_3& o = q[p.faces.front().loop.front()];
  ExactRational six_vol(0);
  for (const auto& f : p.faces) {
    const auto& L = f.loop;
    for (std::size_t k = 1; k + 1 < L.size(); ++k) {
      auto a = q[L[0]] - o, b = q[L[k]] - o, c = q[L[k + 1]] - o;
      six_vol += CGAL::determinant(a, b, c);
    }
  }
  return six_vol / 6;
}

CGAL::Interval_nt<false> volume_interval(const ExactPolytope& p, bool tight) {
  using I = CGAL::Interval_nt<false>;
  if (p.empty()) return I(0);
  using AK = Epeck::Approximate_kernel;
  std::vector<AK::Point_3> q;
  q.reserve(p.vertices.size());
  for (const auto& v : p.vertices) {
    AK::Point_3 a = CGAL::approx(v);
    // A vertex from nearly parallel planes can carry a loose interval; evaluating it exactly
    // (rarely needed) makes Epeck replace its interval by a tight one.
    auto loose = [](const I& x) { return x.sup() - x.inf() > 1e-13 * (std::fabs(x.inf()) + std::fabs(x.sup()) + 1e-300); };
    if (tight ? a.x().inf() != a.x().sup() || a.y().inf() != a.y().sup() || a.z().inf() != a.z().sup()
              : loose(a.x()) || loose(a.y()) || loose(a.z())) {
      CGAL::exact(v);
      a = CGAL::approx(v);
    }
    q.push_back(a);
  }
  const AK::Point_3& o = q[p.faces.front().loop.front()];
  // Unprotected intervals are only sound with the FPU rounding towards +infinity.
  CGAL::Protect_FPU_rounding<true> upward;
  I six(0);
  for (const auto& f : p.faces)
    for (std::size_t k = 1; k + 1 < f.loop.size(); ++k)
      six += CGAL::determinant(q[f.loop[0]] - o, q[f.loop[k]] - o, q[f.loop[k + 1]] - o);
  return six / 6;
}

double approximate_volume(const ExactPolytope& p) {
  if (p.empty()) return 0.0;
  std::vector<Eigen::Vector3d> q;
  q.reserve(p.vertices.size());
  for (const auto& v : p.vertices) q.emplace_back(CGAL::to_double(v.x()), CGAL::to_double(v.y()), CGAL::to_double(v.z()));
  const Eigen::Vector3d o = q[p.faces.front().loop.front()];
  double six = 0;
  for (const auto& f : p.faces)
    for (std::size_t k = 1; k + 1 < f.loop.size(); ++k)
      six += (q[f.loop[0]] - o).dot((q[f.loop[k]] - o).cross(q[f.loop[k + 1]] - o));
  return six / 6.0;
}

ConvexPolytope to_double(const ExactPolytope& p) {
  ConvexPolytope out;
  out.vertices.reserve(p.vertices.size());
  for (const auto& v : p.vertices)
    out.vertices.emplace_back(CGAL::to_double(v.x()), CGAL::to_double(v.y()), CGAL::to_double(v.z()));
  for (const auto& f : p.faces) {
    out.faces.push_back(f.loop);
    out.face_tags.push_back(f.tag);
  }
  return out;
}

}  // namespace dcshell
