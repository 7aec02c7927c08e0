// Lifted edge splits (issue 4). Between few extreme points a hull's surface is big sliver
// triangles that no collapse fixes and no point inside a flat facet reaches. A cap (one angle
// near 180 degrees) is cut well by a point on its long edge: a point w on the edge (a, b) of faces
// abc and bad, lifted above both their planes but below every other face's, sees exactly those two
// faces, so the hull of the vertices plus w replaces them by wbc, wca, wad, wdb: two more faces,
// about lift x area / 3 more volume. Smoothing and collapses then move and trade vertices as usual.
#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "remesh/passes.h"

namespace dcshell::remesh_detail {
namespace {

// Positions tried along the edge (t = k / kSteps, 0 < k < kSteps), then refined around the best
// (bisecting the step kRefine times).
constexpr int kSteps = 16;
constexpr int kRefine = 4;
// Lift above the edge: this share of the room below the nearest other face plane (measured on the
// shared models: 0.3 beat 0.02, 0.1 and 0.6 on most), else (a constraint in the way) relative to
// the edge's length, far above the rounding of the new point.
constexpr double kLiftShare = 0.3;
// A split must gain at least this share of what its two new faces hold on average (area x
// fatness): below it the faces and the smoothing time they cost buy little (measured on the
// shared models: at 0.1 as fat as at 0 overall, fewer faces, about 8% less CPU on Pikachu).
constexpr double kMinGain = 0.1;
constexpr double kLifts[] = {1e-9, 1e-8, 1e-7};

// The edge of halfedge a->b, in face abc, with face bad across.
struct Quad {
  H h;
  V a, b, c, d;
};

Quad quad_of(const Mesh& m, H h) {
  return {h, m.source(h), m.target(h), m.target(m.next(h)), m.target(m.next(m.opposite(h)))};
}

FatArea two_faces(const Mesh& m, const Quad& q) {
  FatArea r;
  r.add(m.point(q.a), m.point(q.b), m.point(q.c));
  r.add(m.point(q.b), m.point(q.a), m.point(q.d));
  return r;
}

FatArea four_faces(const Mesh& m, const Quad& q, const Point3& w) {
  const Point3 &a = m.point(q.a), &b = m.point(q.b), &c = m.point(q.c), &d = m.point(q.d);
  FatArea r;
  r.add(w, b, c);
  r.add(w, c, a);
  r.add(w, a, d);
  r.add(w, d, b);
  return r;
}

CGAL::Orientation side_of_face(const Mesh& m, F f, const Point3& w) {
  const H k = m.halfedge(f);
  return CGAL::orientation(m.point(m.source(k)), m.point(m.target(k)), m.point(m.target(m.next(k))), w);
}

// Exact: w strictly above the planes of the edge's two faces, strictly below every other face's
// and inside the constraints. Then w sees exactly those two faces (beneath-beyond), so the mesh
// with them replaced by the four new faces is the hull of the vertices and w: convex, its faces
// non-degenerate, containing the old mesh. The faces around the quad are tested first: they are
// where a candidate fails, and the full test is a pass over the mesh.
bool split_is_valid(const Mesh& m, const Quad& q, const Point3& w, const ShellConstraints& constraints) {
  const F f1 = m.face(q.h), f2 = m.face(m.opposite(q.h));
  if (side_of_face(m, f1, w) != CGAL::POSITIVE || side_of_face(m, f2, w) != CGAL::POSITIVE) return false;
  for (V v : {q.a, q.b})
    for (F f : CGAL::faces_around_target(m.halfedge(v), m))
      if (f != f1 && f != f2 && side_of_face(m, f, w) != CGAL::NEGATIVE) return false;
  if (!constraints.satisfied_by(w)) return false;
  for (F f : m.faces())
    if (f != f1 && f != f2 && side_of_face(m, f, w) != CGAL::NEGATIVE) return false;
  return true;
}

struct Entry {
  double gain;  // in area x fatness, against the shell's current fatness (first order)
  std::size_t h;
  double t;     // position along the edge
  bool operator<(const Entry& o) const { return gain != o.gain ? gain > o.gain : h < o.h; }
};

}  // namespace

std::size_t Workspace::split_pass(const ShellConstraints& constraints, double max_volume, std::size_t max_splits) {
  if (max_splits == 0) return 0;
  // A split's gain in the area-weighted fatness F is, to first order, d_fa - F d_a.
  FatArea total;
  for (F f : mesh.faces()) {
    const H k = mesh.halfedge(f);
    total.add(mesh.point(mesh.source(k)), mesh.point(mesh.target(k)), mesh.point(mesh.target(mesh.next(k))));
  }
  const double fat = total.ratio(), min_gain = kMinGain * 2 * total.fa / double(mesh.number_of_faces());
  auto gain = [&](const Quad& q, const FatArea& old, const Point3& w) {
    const FatArea now = four_faces(mesh, q, w);
    return now.fa - old.fa - fat * (now.a - old.a);
  };
  auto on_edge = [&](const Quad& q, double t) {
    return pt((1 - t) * vec(mesh.point(q.a)) + t * vec(mesh.point(q.b)));
  };
  std::vector<Entry> entries;
  for (auto e : mesh.edges()) {
    const Quad q = quad_of(mesh, mesh.halfedge(e));
    const FatArea old = two_faces(mesh, q);
    // On the edge the four faces have the two's area, and fatness is at most 0.5.
    if (0.5 * old.a - old.fa <= min_gain) continue;
    double best_t = 0.5, best = gain(q, old, on_edge(q, 0.5));
    for (int k = 1; k < kSteps; ++k) {
      const double t = double(k) / kSteps, g = gain(q, old, on_edge(q, t));
      if (g > best) best = g, best_t = t;
    }
    double step = 0.5 / kSteps;
    for (int r = 0; r < kRefine; ++r, step /= 2)
      for (const double t : {best_t - step, best_t + step}) {
        const double g = gain(q, old, on_edge(q, t));
        if (g > best) best = g, best_t = t;
      }
    if (best > min_gain) entries.push_back({best, std::size_t(mesh.halfedge(e)), best_t});
  }
  std::sort(entries.begin(), entries.end());

  // One pass splits edges whose quads share no vertex: every candidate's faces are then still
  // those its gain was computed on.
  std::vector<char> locked(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), 0);
  std::size_t splits = 0;
  for (const Entry& e : entries) {
    if (splits == max_splits) break;
    const Quad q = quad_of(mesh, H(static_cast<Mesh::size_type>(e.h)));
    if (locked[q.a] || locked[q.b] || locked[q.c] || locked[q.d]) continue;
    const Eigen::Vector3d a = vec(mesh.point(q.a)), b = vec(mesh.point(q.b)), c = vec(mesh.point(q.c)),
                          d = vec(mesh.point(q.d));
    // Lifted along the mean of the two faces' normals, which is above both at the edge.
    const Eigen::Vector3d n1 = (b - a).cross(c - a).normalized(), n2 = (a - b).cross(d - b).normalized();
    const Eigen::Vector3d up = (n1 + n2).normalized(), base = (1 - e.t) * a + e.t * b;
    if (!up.allFinite()) continue;
    const double ulp = std::ldexp(1.0, -52) * std::max(a.lpNorm<Eigen::Infinity>(), b.lpNorm<Eigen::Infinity>());
    // Room above the edge: up to the nearest plane of another face around the quad. A point well
    // inside it (kLiftShare) leaves creases that later collapses and moves can still resolve; one
    // barely above the edge makes them flat to 1e-9, where the LPs' margins no longer fit.
    double room = std::numeric_limits<double>::infinity();
    const F f1 = mesh.face(q.h), f2 = mesh.face(mesh.opposite(q.h));
    for (V v : {q.a, q.b, q.c, q.d})
      for (F f : CGAL::faces_around_target(mesh.halfedge(v), mesh)) {
        if (f == f1 || f == f2) continue;
        const H k = mesh.halfedge(f);
        const Eigen::Vector3d p = vec(mesh.point(mesh.source(k)));
        const Eigen::Vector3d n =
            (vec(mesh.point(mesh.target(k))) - p).cross(vec(mesh.point(mesh.target(mesh.next(k)))) - p);
        if (n.dot(up) > 0) room = std::min(room, -n.dot(base - p) / n.dot(up));
      }
    std::vector<double> lifts;
    if (std::isfinite(room) && room > 0) lifts = {kLiftShare * room, kLiftShare * room / 16};
    for (const double lift : kLifts) lifts.push_back(std::max(lift * (b - a).norm(), 16 * ulp));
    bool found = false;
    Point3 w;
    for (const double lift : lifts) {  // the first that passes the exact check
      w = pt(base + lift * up);
      if ((found = split_is_valid(mesh, q, w, constraints))) break;
    }
    if (!found || !(gain(q, two_faces(mesh, q), w) > 0)) continue;
    // The two tetrahedra over the old faces.
    const Eigen::Vector3d x = vec(w);
    const double dv = ((b - a).cross(c - a).dot(x - a) + (a - b).cross(d - b).dot(x - b)) / 6.0;
    if (volume + dv > max_volume) continue;
    // a->w->b after split_edge; then w joins c in face abc and d in face bad.
    const H h = q.h, hn = CGAL::Euler::split_edge(h, mesh);
    CGAL::Euler::split_face(hn, mesh.next(h), mesh);
    CGAL::Euler::split_face(mesh.opposite(h), mesh.next(mesh.opposite(hn)), mesh);
    const V v = mesh.target(hn);
    mesh.point(v) = w;
    volume += dv;
    ++splits;
    // A recycled vertex index gets a stamp above any its predecessor had, so no cache entry matches.
    for (V s : {q.a, q.b, q.c, q.d, v}) ++stamp_[s];
    for (V s : {q.a, q.b, q.c, q.d}) locked[s] = 1;
  }
  return splits;
}

}  // namespace dcshell::remesh_detail
