// Fat triangulations of a convex polygon with interior points (see remesh/steiner.h).
#include "remesh/steiner.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "dcshell/fatness.h"

namespace dcshell::remesh_detail {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;  // corners 0..m-1, then interior
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
using P2 = K::Point_2;
using Vec2 = Eigen::Vector2d;

P2 p2(const Vec2& v) { return {v.x(), v.y()}; }
Vec2 v2(const P2& p) { return {p.x(), p.y()}; }

// Points inserted one at a time in a fixed order: no spatial sort, no randomness.
DT build(const std::vector<Vec2>& corners, const std::vector<Vec2>& interior) {
  DT dt;
  int i = 0;
  for (const Vec2& c : corners) dt.insert(p2(c))->info() = i++;
  for (const Vec2& c : interior) dt.insert(p2(c))->info() = i++;
  return dt;
}

// Every point a vertex and every corner on the hull (so the triangulation covers the polygon).
bool covers_polygon(const DT& dt, std::size_t corners, std::size_t interior) {
  return dt.dimension() == 2 && dt.number_of_vertices() == corners + interior &&
         dt.degree(dt.infinite_vertex()) == corners;
}

double face_score(const DT::Face_handle& f) {
  const P2 &a = f->vertex(0)->point(), &b = f->vertex(1)->point(), &c = f->vertex(2)->point();
  const double area = 0.5 * std::abs((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
  return area * triangle_fatness({a.x(), a.y(), 0}, {b.x(), b.y(), 0}, {c.x(), c.y(), 0});
}

double score(const DT& dt) {
  double s = 0;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) s += face_score(f);
  return s;
}

// Smallest signed distance of p to the polygon's edges (positive inside).
double boundary_distance(const std::vector<Vec2>& c, const Vec2& p) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < c.size(); ++i) {
    const Vec2 e = (c[(i + 1) % c.size()] - c[i]).normalized();
    const Vec2 r = p - c[i];
    d = std::min(d, e.x() * r.y() - e.y() * r.x());
  }
  return d;
}

// Where the next point goes: the centre of the largest empty circle (a Delaunay circumcentre)
// that is well inside the polygon, so that the new triangles reach the boundary fatly; else the
// centroid of the triangle losing the most area x fatness.
bool next_point(const DT& dt, const std::vector<Vec2>& corners, double diam, Vec2& out) {
  double best_r = 0, worst = 0;
  bool found = false;
  Vec2 fallback = Vec2::Zero();
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    const P2 cc = dt.circumcenter(f);
    const double r = std::sqrt(CGAL::squared_distance(cc, f->vertex(0)->point()));
    if (r > best_r && boundary_distance(corners, v2(cc)) >= 0.5 * r) best_r = r, out = v2(cc), found = true;
    const P2 &a = f->vertex(0)->point(), &b = f->vertex(1)->point(), &c = f->vertex(2)->point();
    const double area = 0.5 * std::abs((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
    const double loss = 0.5 * area - face_score(f);
    const Vec2 g = (v2(a) + v2(b) + v2(c)) / 3;
    if (loss > worst && boundary_distance(corners, g) > 1e-3 * diam) worst = loss, fallback = g;
  }
  if (!found && worst > 0) out = fallback, found = true;
  return found;
}

// One optimal-Delaunay-triangulation step: every interior point moves to the area-weighted mean
// of its triangles' circumcentres, if that stays well inside. Returns whether the score rose.
bool smooth(DT& dt, const std::vector<DT::Vertex_handle>& handles, const std::vector<Vec2>& corners, double diam) {
  const double before = score(dt);
  std::vector<std::pair<DT::Vertex_handle, P2>> old;
  for (const auto& v : handles) {
    Vec2 sum = Vec2::Zero();
    double area = 0;
    auto f = dt.incident_faces(v), end = f;
    do {
      if (dt.is_infinite(f)) continue;
      const P2 &a = f->vertex(0)->point(), &b = f->vertex(1)->point(), &c = f->vertex(2)->point();
      const double A = 0.5 * std::abs((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
      sum += A * v2(dt.circumcenter(f));
      area += A;
    } while (++f != end);
    if (!(area > 0)) continue;
    const Vec2 p = sum / area;
    if (!(boundary_distance(corners, p) > 1e-3 * diam)) continue;
    const P2 was = v->point();
    if (dt.move_if_no_collision(v, p2(p)) == v) old.emplace_back(v, was);
  }
  if (score(dt) > before) return true;
  for (auto it = old.rbegin(); it != old.rend(); ++it) dt.move_if_no_collision(it->first, it->second);
  return false;
}

}  // namespace

std::vector<SteinerMesh> refine_convex_polygon(const std::vector<Vec2>& corners, std::size_t max_points) {
  std::vector<SteinerMesh> out;
  if (corners.size() < 3 || max_points == 0) return out;
  double diam = 0;
  for (const Vec2& a : corners)
    for (const Vec2& b : corners) diam = std::max(diam, (a - b).norm());
  DT dt = build(corners, {});
  if (!covers_polygon(dt, corners.size(), 0)) return out;
  std::vector<DT::Vertex_handle> handles;
  for (std::size_t k = 1; k <= max_points; ++k) {
    Vec2 p;
    if (!next_point(dt, corners, diam, p)) break;
    const std::size_t n = dt.number_of_vertices();
    const auto v = dt.insert(p2(p));
    if (dt.number_of_vertices() != n + 1) break;  // fell on an existing point
    v->info() = int(n);
    handles.push_back(v);
    for (int it = 0; it < 3; ++it)
      if (!smooth(dt, handles, corners, diam)) break;
    if (!covers_polygon(dt, corners.size(), handles.size())) break;
    SteinerMesh s;
    for (const auto& h : handles) s.interior.push_back(v2(h->point()));
    s.score = score(dt);
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<double> paraboloid_heights(const std::vector<Vec2>& corners, const std::vector<Vec2>& interior,
                                       double* margin) {
  Vec2 c0 = Vec2::Zero();
  for (const Vec2& c : corners) c0 += c;
  c0 /= double(corners.size());
  std::vector<Vec2> all = corners;
  all.insert(all.end(), interior.begin(), interior.end());
  // Minus the affine function closest to it at the corners (which leaves the lower hull as it
  // is): the corners then rise or sink about equally, the interior points most.
  Eigen::MatrixXd a(corners.size(), 3);
  Eigen::VectorXd f(corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i) {
    a.row(Eigen::Index(i)) << corners[i].x() - c0.x(), corners[i].y() - c0.y(), 1.0;
    f[Eigen::Index(i)] = (corners[i] - c0).squaredNorm();
  }
  const Eigen::Vector3d fit = a.colPivHouseholderQr().solve(f);
  std::vector<double> h;
  for (const Vec2& p : all) h.push_back((p - c0).squaredNorm() - fit.dot(Eigen::Vector3d(p.x() - c0.x(), p.y() - c0.y(), 1.0)));
  const auto mm = std::minmax_element(h.begin(), h.end());
  const double lo = *mm.first, range = *mm.second - lo;
  *margin = 0;
  if (!(range > 0)) return h;
  for (double& x : h) x = (x - lo) / range;
  // Each interior point against the lower hull of the others: the lifted plane of the Delaunay
  // triangle (without it) that holds it.
  double weakest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < interior.size(); ++i) {
    std::vector<Vec2> others = interior;
    others.erase(others.begin() + std::ptrdiff_t(i));
    const DT dt = build(corners, others);
    const Vec2 p = interior[i];
    const auto f = dt.locate(p2(p));
    if (f == nullptr || dt.is_infinite(f)) return h;
    Eigen::Matrix3d a;
    Eigen::Vector3d hz;
    for (int j = 0; j < 3; ++j) {
      const Vec2 q = v2(f->vertex(j)->point());
      a.col(j) << q.x(), q.y(), 1.0;
      const int idx = f->vertex(j)->info();
      hz[j] = h[std::size_t(idx < int(corners.size()) ? idx : (idx < int(corners.size() + i) ? idx : idx + 1))];
    }
    const Eigen::Vector3d lambda = a.colPivHouseholderQr().solve(Eigen::Vector3d(p.x(), p.y(), 1.0));
    weakest = std::min(weakest, lambda.dot(hz) - h[corners.size() + i]);
  }
  *margin = interior.empty() ? 1.0 : std::max(0.0, weakest);
  return h;
}

}  // namespace dcshell::remesh_detail
