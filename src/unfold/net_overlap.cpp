// Exact 2D overlap test of net faces and the net validity checks.
#include "dcshell/net_overlap.h"

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "dcshell/kernel.h"

namespace dcshell {

namespace {

using Point2 = Epick::Point_2;
Point2 p2(const Eigen::Vector2d& v) { return Point2(v.x(), v.y()); }

// Separating-axis theorem for convex polygons with closed half-planes: the interiors are disjoint
// iff some edge line of one triangle has the whole other triangle on its outer closed side.
// For a counter-clockwise triangle the outer side of edge (p,q) is "not left of p->q".
bool separated_by_edges_of(const std::array<Point2, 3>& a, CGAL::Orientation a_orient,
                           const std::array<Point2, 3>& b) {
  for (int k = 0; k < 3; ++k) {
    const Point2 &p = a[k], &q = a[(k + 1) % 3];
    if (p == q) continue;
    bool all_outside = true;
    if (a_orient == CGAL::COLLINEAR) {
      // A segment: its line separates when b lies in one closed half-plane (either one).
      bool any_left = false, any_right = false;
      for (auto& r : b) {
        auto o = CGAL::orientation(p, q, r);
        any_left |= o == CGAL::LEFT_TURN;
        any_right |= o == CGAL::RIGHT_TURN;
      }
      all_outside = !(any_left && any_right);
    } else {
      const CGAL::Orientation inner = a_orient;  // the side the triangle's interior is on
      for (auto& r : b)
        if (CGAL::orientation(p, q, r) == inner) {
          all_outside = false;
          break;
        }
    }
    if (all_outside) return true;
  }
  return false;
}

// Shewchuk's static filter for orient2d: the sign of the rounded determinant when its error
// bound certifies it (+1 left, -1 right), 0 when it does not. A corner equal to an end of the
// edge is on its line for certain (-2).
int sure_orientation(const Point2& p, const Point2& q, const Point2& r) {
  if (r == p || r == q) return -2;
  constexpr double eps = 0x1p-53, bound = (3 + 16 * eps) * eps;
  const double l = (q.x() - p.x()) * (r.y() - p.y()), rr = (q.y() - p.y()) * (r.x() - p.x());
  const double det = l - rr, size = std::abs(l) + std::abs(rr), err = bound * size;
  if (!(size > 1e-280) || !(size < 1e300)) return 0;  // the bound assumes no underflow or overflow
  return det > err ? 1 : det < -err ? -1 : 0;
}

// An edge line of triangle a (oriented oa, not collinear) that the static filter proves has all
// of b on its outer closed side: then the interiors are disjoint, as the exact test would find
// (this only spares it the exact arithmetic of nearly collinear corners elsewhere).
bool surely_separated_by_edges_of(const std::array<Point2, 3>& a, CGAL::Orientation oa, const std::array<Point2, 3>& b) {
  const int inner = oa == CGAL::LEFT_TURN ? 1 : -1;
  for (int k = 0; k < 3; ++k) {
    bool outside = true;
    for (int j = 0; j < 3 && outside; ++j) {
      const int o = sure_orientation(a[k], a[(k + 1) % 3], b[j]);
      outside = o == -2 || o == -inner;
    }
    if (outside) return true;
  }
  return false;
}

using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, int>;

struct StopSearch {};

}  // namespace

bool triangle_interiors_overlap(const Triangle2& ta, const Triangle2& tb) {
  std::array<Point2, 3> a{p2(ta[0]), p2(ta[1]), p2(ta[2])}, b{p2(tb[0]), p2(tb[1]), p2(tb[2])};
  auto oa = CGAL::orientation(a[0], a[1], a[2]), ob = CGAL::orientation(b[0], b[1], b[2]);
  if (oa == CGAL::COLLINEAR && ob == CGAL::COLLINEAR) return false;  // two segments: no area
  if ((oa != CGAL::COLLINEAR && surely_separated_by_edges_of(a, oa, b)) ||
      (ob != CGAL::COLLINEAR && surely_separated_by_edges_of(b, ob, a)))
    return false;
  return !separated_by_edges_of(a, oa, b) && !separated_by_edges_of(b, ob, a);
}

std::vector<std::pair<int, int>> find_net_overlaps(const Net& net, std::size_t max_pairs) {
  std::vector<std::pair<int, int>> pairs;
  if (max_pairs == 0) return pairs;
  std::vector<Box> boxes;
  boxes.reserve(net.corners.size());
  for (int f = 0; f < static_cast<int>(net.corners.size()); ++f) {
    const auto& c = net.corners[f];
    double lo[2] = {std::min({c[0].x(), c[1].x(), c[2].x()}), std::min({c[0].y(), c[1].y(), c[2].y()})};
    double hi[2] = {std::max({c[0].x(), c[1].x(), c[2].x()}), std::max({c[0].y(), c[1].y(), c[2].y()})};
    boxes.emplace_back(lo, hi, f);
  }
  auto callback = [&](const Box& a, const Box& b) {
    int f = a.info(), g = b.info();
    if (triangle_interiors_overlap(net.corners[f], net.corners[g])) {
      pairs.emplace_back(std::min(f, g), std::max(f, g));
      if (pairs.size() >= max_pairs) throw StopSearch{};
    }
  };
  try {
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), callback);
  } catch (const StopSearch&) {
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

bool any_overlap(const std::vector<Triangle2>& corners) {
  // The pairs of closed boxes that meet (those box_self_intersection_d reports), found in the
  // order of a sweep over low x; the answer does not depend on that order.
  const int n = static_cast<int>(corners.size());
  thread_local std::vector<std::pair<double, int>> by_low_x;
  thread_local std::vector<double> lx, hx, ly, hy;
  by_low_x.resize(n);
  for (int f = 0; f < n; ++f) {
    const auto& c = corners[f];
    by_low_x[f] = {std::min({c[0].x(), c[1].x(), c[2].x()}), f};
  }
  std::sort(by_low_x.begin(), by_low_x.end());
  lx.resize(n), hx.resize(n), ly.resize(n), hy.resize(n);
  for (int i = 0; i < n; ++i) {
    const auto& c = corners[by_low_x[i].second];
    lx[i] = by_low_x[i].first;
    hx[i] = std::max({c[0].x(), c[1].x(), c[2].x()});
    ly[i] = std::min({c[0].y(), c[1].y(), c[2].y()});
    hy[i] = std::max({c[0].y(), c[1].y(), c[2].y()});
  }
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n && lx[j] <= hx[i]; ++j)
      if (ly[j] <= hy[i] && hy[j] >= ly[i] &&
          triangle_interiors_overlap(corners[by_low_x[i].second], corners[by_low_x[j].second]))
        return true;
  return false;
}

NetCheck check_net(const Net& net, double tol) {
  NetCheck r;
  const int nf = static_cast<int>(net.shell_faces.size());
  auto fail = [&](const std::string& what) {
    if (r.problem.empty()) r.problem = what;
  };
  if (static_cast<int>(net.corners.size()) != nf || static_cast<int>(net.parent.size()) != nf) {
    fail("corners/parent sizes differ from the shell's face count");
    return r;
  }

  r.congruent = r.oriented = true;
  for (int f = 0; f < nf; ++f) {
    const auto& t = net.shell_faces[f];
    const auto& c = net.corners[f];
    for (int k = 0; k < 3; ++k) {
      double l3 = (net.shell_vertices[t[(k + 1) % 3]] - net.shell_vertices[t[k]]).norm();
      double l2 = (c[(k + 1) % 3] - c[k]).norm();
      double err = std::abs(l2 - l3) / std::max(l3, 1e-300);
      r.max_length_error = std::max(r.max_length_error, err);
    }
    if (CGAL::orientation(p2(c[0]), p2(c[1]), p2(c[2])) != CGAL::LEFT_TURN) {
      r.oriented = false;
      fail("face " + std::to_string(f) + " is mirrored or degenerate in the net");
    }
  }
  if (r.max_length_error > tol) {
    r.congruent = false;
    fail("net edge lengths differ from the shell's (relative error " + std::to_string(r.max_length_error) + ")");
  }

  // Fold edges: both faces place the edge's ends at the same points; they join all faces.
  auto corner_of = [&](int f, int v) {
    for (int k = 0; k < 3; ++k)
      if (net.shell_faces[f][k] == v) return k;
    return -1;
  };
  std::vector<int> uf(nf);
  std::iota(uf.begin(), uf.end(), 0);
  auto find = [&](int x) {
    while (uf[x] != x) x = uf[x] = uf[uf[x]];
    return x;
  };
  r.folds_shared = true;
  std::map<std::pair<int, int>, bool> fold_between;
  for (const auto& e : net.edges) {
    if (e.f0 < 0 || e.f1 < 0 || e.f0 >= nf || e.f1 >= nf) {
      fail("edge with a face index out of range");
      r.folds_shared = false;
      continue;
    }
    if (!e.fold) continue;
    fold_between[{std::min(e.f0, e.f1), std::max(e.f0, e.f1)}] = true;
    for (int v : {e.v0, e.v1}) {
      int k0 = corner_of(e.f0, v), k1 = corner_of(e.f1, v);
      if (k0 < 0 || k1 < 0 || net.corners[e.f0][k0] != net.corners[e.f1][k1]) {
        r.folds_shared = false;
        fail("fold edge " + std::to_string(e.v0) + "-" + std::to_string(e.v1) + " is not shared in the net");
      }
    }
    uf[find(e.f0)] = find(e.f1);
  }
  int pieces = 0;
  for (int f = 0; f < nf; ++f) pieces += find(f) == f;
  r.one_piece = pieces == 1;
  if (!r.one_piece) fail("the net has " + std::to_string(pieces) + " pieces");

  // parent[] is a spanning tree over fold edges: one root, every other face reaches it.
  r.tree = true;
  int roots = 0;
  for (int f = 0; f < nf; ++f) {
    int p = net.parent[f];
    if (p < 0) {
      ++roots;
      continue;
    }
    if (p >= nf || !fold_between.count({std::min(f, p), std::max(f, p)})) {
      r.tree = false;
      fail("parent of face " + std::to_string(f) + " is not across a fold edge");
    }
  }
  if (roots != 1) r.tree = false, fail("the cut tree has " + std::to_string(roots) + " roots");
  if (r.tree) {
    std::vector<int> state(nf, 0);  // 0 unknown, 1 on the current path, 2 reaches the root
    for (int f = 0; f < nf && r.tree; ++f) {
      std::vector<int> path;
      int x = f;
      while (x >= 0 && state[x] == 0) state[x] = 1, path.push_back(x), x = net.parent[x];
      if (x >= 0 && state[x] == 1) r.tree = false, fail("the parent links form a cycle");
      for (int y : path) state[y] = 2;
    }
  }

  // Faces that share a net point must share the shell vertex there: the net glues nothing
  // that the shell does not glue. Exact coordinates, grouped by position.
  r.meets_only_along_shell_edges = true;
  std::map<std::pair<double, double>, int> vertex_at;
  for (int f = 0; f < nf && r.meets_only_along_shell_edges; ++f)
    for (int k = 0; k < 3; ++k) {
      auto [it, fresh] = vertex_at.emplace(std::make_pair(net.corners[f][k].x(), net.corners[f][k].y()),
                                           net.shell_faces[f][k]);
      if (!fresh && it->second != net.shell_faces[f][k]) {
        r.meets_only_along_shell_edges = false;
        fail("shell vertices " + std::to_string(it->second) + " and " + std::to_string(net.shell_faces[f][k]) +
             " meet at one net point");
        break;
      }
    }

  auto overlaps = find_net_overlaps(net, 1);
  r.overlap_free = overlaps.empty();
  if (!r.overlap_free)
    fail("net faces " + std::to_string(overlaps[0].first) + " and " + std::to_string(overlaps[0].second) + " overlap");
  return r;
}

}  // namespace dcshell
