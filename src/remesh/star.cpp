// Local replacement bookkeeping and exact checks shared by simplification and regularisation.
#include "remesh/star.h"

#include <CGAL/Bbox_3.h>
#include <CGAL/Exact_rational.h>

#include <algorithm>

namespace dcshell::remesh_detail {
namespace {

// Outgoing halfedges of v, counter-clockwise seen from outside: face(h) = (v, target(h), next).
std::vector<H> outgoing(const Mesh& m, V v) {
  std::vector<H> out;
  const H start = m.opposite(m.halfedge(v));  // halfedge(v) targets v
  H h = start;
  do {
    out.push_back(h);
    h = m.opposite(m.prev(h));
  } while (h != start && out.size() <= m.number_of_halfedges());
  return out;
}

// Fills `across` and the validity flag once ring and faces are known.
void finish(const Mesh& m, Star& s) {
  const std::size_t n = s.ring.size();
  s.valid = n >= 3;
  std::vector<V> sorted = s.ring;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) s.valid = false;  // link condition
  for (V r : s.removed)
    if (std::binary_search(sorted.begin(), sorted.end(), r)) s.valid = false;
  if (!s.valid) return;
  s.across.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const H h = m.halfedge(s.ring[i], s.ring[(i + 1) % n]);  // ring[i] -> ring[i+1] lies in a star face
    if (h == Mesh::null_halfedge()) { s.valid = false; return; }
    s.across[i] = m.target(m.next(m.opposite(h)));
  }
  // A separating triangle: an across vertex that is a removed vertex or would close a second cone.
  for (V a : s.across)
    if (std::find(s.removed.begin(), s.removed.end(), a) != s.removed.end()) s.valid = false;
}

}  // namespace

Star vertex_star(const Mesh& m, V v) {
  Star s;
  s.removed = {v};
  for (H h : outgoing(m, v)) {
    s.ring.push_back(m.target(h));
    s.faces.push_back(m.face(h));
  }
  finish(m, s);
  return s;
}

Star edge_star(const Mesh& m, H h) {
  // Ring of u from v: [v, r1..rk]; ring of v from u: [u, s1..sl] with s1 = rk and sl = r1.
  // The merged ring is r1..rk followed by s2..s(l-1).
  Star s;
  const V u = m.source(h), v = m.target(h);
  s.removed = {u, v};
  const auto ou = outgoing(m, u), ov = outgoing(m, v);
  auto rot = [&](const std::vector<H>& out, V first) {
    std::vector<V> r;
    std::size_t k = 0;
    while (k < out.size() && m.target(out[k]) != first) ++k;
    for (std::size_t i = 0; i < out.size(); ++i) r.push_back(m.target(out[(k + i) % out.size()]));
    return r;
  };
  const auto ru = rot(ou, v), rv = rot(ov, u);
  for (std::size_t i = 1; i < ru.size(); ++i) s.ring.push_back(ru[i]);
  for (std::size_t i = 2; i + 1 < rv.size(); ++i) s.ring.push_back(rv[i]);
  for (H o : ou) s.faces.push_back(m.face(o));
  for (H o : ov)
    if (std::find(s.faces.begin(), s.faces.end(), m.face(o)) == s.faces.end()) s.faces.push_back(m.face(o));
  finish(m, s);
  if (s.valid && (ru.size() < 3 || rv.size() < 3 || ru.back() != rv[1] || ru[1] != rv.back())) s.valid = false;
  return s;
}

Star flip_star(const Mesh& m, H h) {
  // Face abc holds h = a->b, face bad is across; the ring of c runs ..., a, b, ...: d goes between.
  const V a = m.source(h), b = m.target(h), c = m.target(m.next(h));
  const V d = m.target(m.next(m.opposite(h)));
  Star s = vertex_star(m, c);
  if (!s.valid) return s;
  const std::size_t n = s.ring.size();
  std::size_t i = 0;
  while (i < n && !(s.ring[i] == a && s.ring[(i + 1) % n] == b)) ++i;
  if (i == n) { s.valid = false; return s; }
  s.ring.insert(s.ring.begin() + std::ptrdiff_t(i + 1), d);
  s.faces.push_back(m.face(m.opposite(h)));
  finish(m, s);  // d already next to c (a degree-3 end point) fails the link condition here
  return s;
}

void add_constraint_rows(const ShellConstraints& c, const Frame& f, double margin, std::vector<Row>& rows) {
  for (const CutPlane& p : c.cut_planes) {
    const double len = p.normal.norm();
    if (!(len > 0)) continue;
    const Eigen::Vector3d n = p.normal / len;
    // n·(origin + s y) <= d/len - margin*s
    rows.push_back({n, (p.offset / len - n.dot(f.origin)) / f.scale - margin});
  }
  for (const auto& t : c.face_planes) add_below_row(t[0], t[1], t[2], f, margin, rows);
  for (const auto& h : c.exact_planes) {
    // Rounded rows: the margin, and the exact re-check of every answer, cover the rounding.
    const Eigen::Vector3d nn(CGAL::to_double(h.a()), CGAL::to_double(h.b()), CGAL::to_double(h.c()));
    const double len = nn.norm();
    if (!(len > 0)) continue;
    const Eigen::Vector3d n = nn / len;
    rows.push_back({n, (-CGAL::to_double(h.d()) / len - n.dot(f.origin)) / f.scale - margin});
  }
}

void add_below_row(const Point3& p, const Point3& q, const Point3& r, const Frame& f, double margin,
                   std::vector<Row>& rows) {
  const Eigen::Vector3d a = vec(p), n = (vec(q) - a).cross(vec(r) - a);
  const double len = n.norm();
  if (!(len > 0)) return;
  const Eigen::Vector3d u = n / len;
  rows.push_back({u, u.dot(a - f.origin) / f.scale - margin});
}

namespace {

// Sign of orientation(w, a, b, x) for many x against one plane: the normal is computed once and a
// static error bound covers the whole batch (the analysis of CGAL's own static filter, with the
// box's sides bounding every coordinate difference, at about twice its constant); what the bound
// cannot settle goes to the exact predicate, so every answer equals CGAL::orientation's.
class PlaneBatch {
 public:
  // `box`: holds w, a, b and every x to be tested. Rounding is monotone, so every rounded
  // difference of two of its points is within the rounded side.
  PlaneBatch(const Point3& w, const Point3& a, const Point3& b, const CGAL::Bbox_3& box)
      : w_(w), a_(a), b_(b), wv_(vec(w)), n_((vec(a) - wv_).cross(vec(b) - wv_)) {
    const Eigen::Vector3d side(box.xmax() - box.xmin(), box.ymax() - box.ymin(), box.zmax() - box.zmin());
    // Within these bounds nothing overflows and underflow errors are far below eps.
    filtered_ = side.minCoeff() >= 1e-90 && side.maxCoeff() <= 1e90;
    eps_ = 1e-14 * side[0] * side[1] * side[2];
  }
  CGAL::Orientation operator()(const Point3& x) const {
    if (filtered_) {
      const double v = n_.dot(vec(x) - wv_);
      if (v > eps_) return CGAL::POSITIVE;
      if (v < -eps_) return CGAL::NEGATIVE;
    }
    return CGAL::orientation(w_, a_, b_, x);
  }

 private:
  const Point3 &w_, &a_, &b_;
  Eigen::Vector3d wv_, n_;
  bool filtered_ = false;
  double eps_ = 0;
};

}  // namespace

bool replacement_is_valid(const Mesh& m, const Star& s, const Point3& w, const std::vector<Point3>& enclose,
                          const ShellConstraints& constraints) {
  if (!s.valid || !constraints.satisfied_by(w)) return false;
  const std::size_t n = s.ring.size();
  auto ringp = [&](std::size_t i) -> const Point3& { return m.point(s.ring[i % n]); };
  CGAL::Bbox_3 all = w.bbox();  // everything the batches below test
  for (V x : m.vertices()) all += m.point(x).bbox();
  for (const Point3& o : enclose) all += o.bbox();
  // Cone faces: non-degenerate, every remaining vertex and the removed ones on or below (the
  // face's own corners lie on it).
  std::vector<PlaneBatch> cone;
  cone.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point3 &a = ringp(i), &b = ringp(i + 1);
    if (CGAL::collinear(w, a, b)) return false;
    cone.emplace_back(w, a, b, all);
    const V va = s.ring[i], vb = s.ring[(i + 1) % n];
    for (V x : m.vertices())
      if (x != va && x != vb && cone.back()(m.point(x)) == CGAL::POSITIVE) return false;
  }
  // w on or below every face that stays.
  for (F f : m.faces()) {
    if (std::find(s.faces.begin(), s.faces.end(), f) != s.faces.end()) continue;
    H h = m.halfedge(f);
    if (CGAL::orientation(m.point(m.source(h)), m.point(m.target(h)), m.point(m.target(m.next(h))), w) ==
        CGAL::POSITIVE)
      return false;
  }
  // Points to enclose: only those in the box of the removed vertices and the ring can have left
  // (the region given up lies in the hull of the old star), and the box test is exact.
  if (!enclose.empty()) {
    CGAL::Bbox_3 star = m.point(s.ring[0]).bbox();
    for (V r : s.ring) star += m.point(r).bbox();
    for (V r : s.removed) star += m.point(r).bbox();
    for (const Point3& o : enclose) {
      if (!CGAL::do_overlap(star, o.bbox())) continue;  // closed boxes: a point on the side is in
      for (const PlaneBatch& plane : cone)
        if (plane(o) == CGAL::POSITIVE) return false;
    }
  }
  return true;
}

double volume_change(const Mesh& m, const Star& s, const Point3& w) {
  const Eigen::Vector3d o = vec(w);
  auto det = [&](const Point3& a, const Point3& b, const Point3& c) {
    return (vec(a) - o).dot((vec(b) - o).cross(vec(c) - o)) / 6.0;
  };
  double d = 0;  // cone faces all contain w: zero relative to o = w
  for (F f : s.faces) {
    H h = m.halfedge(f);
    d -= det(m.point(m.source(h)), m.point(m.target(h)), m.point(m.target(m.next(h))));
  }
  return d;
}

namespace {

// Indices of the points strictly above some face of the convex `hull` (exact), skipping its own
// vertices; with first_only, at most one (the answer to "all enclosed?").
std::vector<std::size_t> above_some_face(const Mesh& hull, const std::vector<Point3>& points, bool first_only) {
  std::vector<Point3> vertices;
  vertices.reserve(hull.number_of_vertices());
  for (auto v : hull.vertices()) vertices.push_back(hull.point(v));
  std::sort(vertices.begin(), vertices.end());
  std::vector<std::size_t> test;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!std::binary_search(vertices.begin(), vertices.end(), points[i])) test.push_back(i);
  if (test.empty() || vertices.empty()) return {};
  CGAL::Bbox_3 all = vertices[0].bbox();
  for (const Point3& v : vertices) all += v.bbox();
  for (std::size_t i : test) all += points[i].bbox();
  std::vector<char> above(points.size(), 0);
  for (F f : hull.faces()) {
    const H h = hull.halfedge(f);
    const PlaneBatch plane(hull.point(hull.source(h)), hull.point(hull.target(h)), hull.point(hull.target(hull.next(h))), all);
    for (std::size_t i : test)
      if (!above[i] && plane(points[i]) == CGAL::POSITIVE) {
        if (first_only) return {i};
        above[i] = 1;
      }
  }
  std::vector<std::size_t> out;
  for (std::size_t i : test)
    if (above[i]) out.push_back(i);
  return out;
}

}  // namespace

std::vector<std::size_t> points_outside(const Mesh& hull, const std::vector<Point3>& points) {
  return above_some_face(hull, points, false);
}

bool mesh_encloses(const Mesh& hull, const std::vector<Point3>& points) { return above_some_face(hull, points, true).empty(); }

double mesh_volume(const Mesh& m) {
  if (m.number_of_vertices() == 0) return 0;
  const Eigen::Vector3d o = vec(m.point(*m.vertices().begin()));
  double v = 0;
  for (F f : m.faces()) {
    H h = m.halfedge(f);
    const Eigen::Vector3d a = vec(m.point(m.source(h))) - o, b = vec(m.point(m.target(h))) - o,
                          c = vec(m.point(m.target(m.next(h)))) - o;
    v += a.dot(b.cross(c));
  }
  return v / 6.0;
}

}  // namespace dcshell::remesh_detail

namespace dcshell {

namespace remesh_detail {

bool on_or_below(const CutPlane& p, const Point3& x) {
  // Floating-point filter: the error of n·x - d is below this bound, so the sign is certain.
  const double v = p.eval(vec(x));
  const double bound = 1e-14 * (std::abs(p.normal.x() * x.x()) + std::abs(p.normal.y() * x.y()) +
                                std::abs(p.normal.z() * x.z()) + std::abs(p.offset));
  if (v < -bound) return true;
  if (v > bound) return false;
  using Q = CGAL::Exact_rational;
  return Q(p.normal.x()) * Q(x.x()) + Q(p.normal.y()) * Q(x.y()) + Q(p.normal.z()) * Q(x.z()) - Q(p.offset) <= 0;
}

}  // namespace remesh_detail

bool ShellConstraints::satisfied_by(const Point3& x) const {
  for (const CutPlane& p : cut_planes)
    if (!remesh_detail::on_or_below(p, x)) return false;
  for (const auto& t : face_planes)
    if (CGAL::orientation(t[0], t[1], t[2], x) == CGAL::POSITIVE) return false;
  for (const auto& h : exact_planes)
    if (h.oriented_side(Epeck::Point_3(x.x(), x.y(), x.z())) == CGAL::ON_POSITIVE_SIDE) return false;
  return true;
}

}  // namespace dcshell
