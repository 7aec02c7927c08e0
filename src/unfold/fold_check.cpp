// Continuous folding check along the straight line in configuration space (see fold_check.h).
#include "dcshell/fold_check.h"

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <CGAL/squared_distance_3.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

#include "dcshell/kernel.h"

namespace dcshell {

namespace {

// Folds whose angle is below this move nothing visible: the faces they join are one rigid piece.
constexpr double kRigidAngle = 1e-6;

struct Motion {
  int nf = 0;
  std::vector<int> order;        // parents before children
  std::vector<int> parent;
  std::vector<double> angle;     // fold angle of the edge to the parent (0 for the root)
  std::vector<Eigen::Vector3d> axis_a, axis_u;  // fold axis in net coordinates (parent on the left)
  std::vector<int> body;         // rigid piece of each face
  std::vector<int> body_root;    // the face whose joint moves the piece
  std::vector<std::vector<int>> body_faces;

  explicit Motion(const Net& net) {
    nf = static_cast<int>(net.corners.size());
    parent = net.parent;
    angle.assign(nf, 0.0);
    axis_a.assign(nf, Eigen::Vector3d::Zero());
    axis_u.assign(nf, Eigen::Vector3d::UnitX());
    std::map<std::pair<int, int>, double> fold_angle;
    for (const auto& e : net.edges)
      if (e.fold) fold_angle.emplace(std::make_pair(std::min(e.f0, e.f1), std::max(e.f0, e.f1)), e.fold_angle);
    std::vector<std::vector<int>> children(nf);
    int root = -1;
    for (int f = 0; f < nf; ++f) {
      int p = parent[f];
      if (p < 0) {
        root = f;
        continue;
      }
      children[p].push_back(f);
      auto it = fold_angle.find({std::min(f, p), std::max(f, p)});
      if (it == fold_angle.end()) throw std::invalid_argument("fold check: parent of a face is not across a fold edge");
      angle[f] = it->second;
      // The shared edge as it runs counter-clockwise in the parent (parent on its left).
      for (int k = 0; k < 3; ++k) {
        int a = net.shell_faces[p][k], b = net.shell_faces[p][(k + 1) % 3];
        const auto& t = net.shell_faces[f];
        bool shared = (std::find(t.begin(), t.end(), a) != t.end()) && (std::find(t.begin(), t.end(), b) != t.end());
        if (!shared) continue;
        const auto &A = net.corners[p][k], &B = net.corners[p][(k + 1) % 3];
        axis_a[f] = Eigen::Vector3d(A.x(), A.y(), 0);
        axis_u[f] = Eigen::Vector3d(B.x() - A.x(), B.y() - A.y(), 0).normalized();
        break;
      }
    }
    if (root < 0) throw std::invalid_argument("fold check: the cut tree has no root");
    order.push_back(root);
    for (std::size_t i = 0; i < order.size(); ++i)
      for (int c : children[order[i]]) order.push_back(c);
    if (static_cast<int>(order.size()) != nf) throw std::invalid_argument("fold check: parent[] is not a tree");
    body.assign(nf, -1);
    for (int f : order) {
      if (parent[f] >= 0 && std::abs(angle[f]) < kRigidAngle) {
        body[f] = body[parent[f]];
      } else {
        body[f] = static_cast<int>(body_root.size());
        body_root.push_back(f);
      }
    }
    body_faces.resize(body_root.size());
    for (int f : order) body_faces[body[f]].push_back(f);
  }

  struct Rigid {
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d tr = Eigen::Vector3d::Zero();
    Eigen::Vector3d operator()(const Eigen::Vector3d& x) const { return R * x + tr; }
  };

  // Placement of every face at time t: T_f = T_parent o rotation about the fold axis by t*angle.
  // A positive angle turns the child below the plane (the outside of the shell faces +z).
  std::vector<Rigid> transforms(double t) const {
    std::vector<Rigid> T(nf);
    for (int f : order) {
      int p = parent[f];
      if (p < 0) continue;
      if (std::abs(angle[f]) < kRigidAngle && body[f] == body[p]) {
        T[f] = T[p];
        continue;
      }
      Eigen::Matrix3d Q = Eigen::AngleAxisd(t * angle[f], axis_u[f]).toRotationMatrix();
      T[f].R = T[p].R * Q;
      T[f].tr = T[p].R * (axis_a[f] - Q * axis_a[f]) + T[p].tr;
    }
    return T;
  }
};

Eigen::Vector3d lift(const Eigen::Vector2d& p) { return Eigen::Vector3d(p.x(), p.y(), 0); }
Point3 cgal(const Eigen::Vector3d& p) { return Point3(p.x(), p.y(), p.z()); }
using Tri3 = std::array<Eigen::Vector3d, 3>;

double triangle_distance(const Tri3& a, const Tri3& b) {
  Epick::Triangle_3 ta(cgal(a[0]), cgal(a[1]), cgal(a[2])), tb(cgal(b[0]), cgal(b[1]), cgal(b[2]));
  if (CGAL::do_intersect(ta, tb)) return 0;
  double d2 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    d2 = std::min(d2, CGAL::to_double(CGAL::squared_distance(cgal(a[k]), tb)));
    d2 = std::min(d2, CGAL::to_double(CGAL::squared_distance(cgal(b[k]), ta)));
    Epick::Segment_3 sa(cgal(a[k]), cgal(a[(k + 1) % 3]));
    for (int j = 0; j < 3; ++j)
      d2 = std::min(d2, CGAL::to_double(CGAL::squared_distance(sa, Epick::Segment_3(cgal(b[j]), cgal(b[(j + 1) % 3])))));
  }
  return std::sqrt(d2);
}

// Faces sharing shell vertices: shrink each away from the shared corners (towards its centroid)
// and test the rest for contact. Catches a face swinging through its neighbour.
bool touching_pair_collides(const Tri3& a, const Tri3& b, const std::array<int, 3>& va, const std::array<int, 3>& vb) {
  constexpr double kShrink = 1e-3;
  auto shrink = [&](const Tri3& t, const std::array<int, 3>& v, const std::array<int, 3>& other) {
    Eigen::Vector3d c = (t[0] + t[1] + t[2]) / 3;
    Tri3 s = t;
    for (int k = 0; k < 3; ++k)
      if (std::find(other.begin(), other.end(), v[k]) != other.end()) s[k] = t[k] + kShrink * (c - t[k]);
    return s;
  };
  Tri3 sa = shrink(a, va, vb), sb = shrink(b, vb, va);
  Epick::Triangle_3 ta(cgal(sa[0]), cgal(sa[1]), cgal(sa[2])), tb(cgal(sb[0]), cgal(sb[1]), cgal(sb[2]));
  return CGAL::do_intersect(ta, tb);
}

bool share_vertex(const std::array<int, 3>& a, const std::array<int, 3>& b) {
  for (int x : a)
    if (std::find(b.begin(), b.end(), x) != b.end()) return true;
  return false;
}

using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

}  // namespace

std::vector<std::array<Eigen::Vector3d, 3>> folded_faces(const Net& net, double t) {
  Motion m(net);
  auto T = m.transforms(t);
  std::vector<Tri3> out(m.nf);
  for (int f = 0; f < m.nf; ++f)
    for (int k = 0; k < 3; ++k) out[f][k] = T[f](lift(net.corners[f][k]));
  return out;
}

FoldCheckResult check_folding(const Net& net, const FoldCheckOptions& options) {
  FoldCheckResult res;
  Motion m(net);
  const int nf = m.nf, nb = static_cast<int>(m.body_root.size());
  if (nb <= 1) {  // one rigid piece: nothing moves
    res.verified = true;
    return res;
  }
  // Pieces form a tree: parent piece, depth, the joint (body root face) that moves each piece.
  std::vector<int> body_parent(nb, -1), body_depth(nb, 0);
  for (int b = 0; b < nb; ++b) {
    int j = m.body_root[b];
    if (m.parent[j] >= 0) body_parent[b] = m.body[m.parent[j]];
  }
  for (int f : m.order) {
    int b = m.body[f];
    if (m.body_root[b] == f && body_parent[b] >= 0) body_depth[b] = body_depth[body_parent[b]] + 1;
  }
  double scale = 0;
  {
    Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
    for (auto& c : net.corners)
      for (auto& p : c) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    scale = (hi - lo).norm();
  }
  // Per step, no point moves farther than this (absolute): keeps the candidate boxes local.
  const double max_travel = 0.05 * scale;

  double t = 0, dt = 1.0 / 64;
  std::vector<Tri3> tri(nf);
  std::vector<Eigen::Vector3d> centre(nf), axis_a(nb), axis_u(nb);
  std::vector<double> rad(nf), lever_abs(nb), theta_abs(nb);
  for (res.steps = 0; res.steps < options.max_steps; ++res.steps) {
    auto T = m.transforms(t);
    for (int f = 0; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) tri[f][k] = T[f](lift(net.corners[f][k]));
      centre[f] = (tri[f][0] + tri[f][1] + tri[f][2]) / 3;
      rad[f] = std::max({(tri[f][0] - centre[f]).norm(), (tri[f][1] - centre[f]).norm(), (tri[f][2] - centre[f]).norm()});
    }
    for (int b = 0; b < nb; ++b) {
      int j = m.body_root[b];
      if (m.parent[j] < 0) continue;
      const auto& P = T[m.parent[j]];
      axis_a[b] = P(m.axis_a[j]);
      axis_u[b] = P.R * m.axis_u[j];
    }
    // Lever of face f about the joint of piece b: distance of its bounding sphere to the axis.
    auto lever = [&](int f, int b) {
      Eigen::Vector3d w = centre[f] - axis_a[b];
      return std::abs(m.angle[m.body_root[b]]) * ((w - w.dot(axis_u[b]) * axis_u[b]).norm() + rad[f]);
    };
    // Absolute bound per face (all joints above it), for the candidate boxes.
    double max_lever = 0, max_theta = 0;
    std::vector<double> face_lever(nf, 0), face_theta(nf, 0);
    for (int f = 0; f < nf; ++f) {
      for (int b = m.body[f]; body_parent[b] >= 0; b = body_parent[b]) {
        face_lever[f] += lever(f, b);
        face_theta[f] += std::abs(m.angle[m.body_root[b]]);
      }
      max_lever = std::max(max_lever, face_lever[f]);
      max_theta = std::max(max_theta, face_theta[f]);
    }
    // Travel over [t, t + h] with lever L and angle sum S: the lever grows with the travel
    // itself, so h*L/(1 - h*S) (valid for h*S < 1).
    auto travel = [](double h, double L, double S) { return h * L / (1 - h * S); };
    dt = std::min({2 * dt, 1 - t, 0.5 / std::max(max_theta, 1e-300)});
    if (travel(dt, max_lever, max_theta) > max_travel) dt = max_travel / (max_lever + max_travel * max_theta);
    // Candidate pairs in two stages: pieces whose (inflated) boxes meet, then their faces. Faces
    // of one rigid piece never move relative to each other and are never paired.
    std::vector<std::vector<Box>> piece_boxes(nb);
    std::vector<Box> piece_box;
    {
      std::vector<std::array<double, 6>> ext(nb, {1e300, 1e300, 1e300, -1e300, -1e300, -1e300});
      for (int f = 0; f < nf; ++f) {
        double r = travel(dt, face_lever[f], face_theta[f]);
        double lo[3], hi[3];
        for (int d = 0; d < 3; ++d) {
          lo[d] = std::min({tri[f][0][d], tri[f][1][d], tri[f][2][d]}) - r;
          hi[d] = std::max({tri[f][0][d], tri[f][1][d], tri[f][2][d]}) + r;
        }
        auto& e = ext[m.body[f]];
        for (int d = 0; d < 3; ++d) e[d] = std::min(e[d], lo[d]), e[3 + d] = std::max(e[3 + d], hi[d]);
        piece_boxes[m.body[f]].emplace_back(lo, hi, f);
      }
      for (int b = 0; b < nb; ++b) {
        double lo[3] = {ext[b][0], ext[b][1], ext[b][2]}, hi[3] = {ext[b][3], ext[b][4], ext[b][5]};
        piece_box.emplace_back(lo, hi, b);
      }
    }
    bool hit = false;
    double hit_distance = 0;
    auto check_pair = [&](int f0, int g0) {
      if (hit) return;
      int f = std::min(f0, g0), g = std::max(f0, g0);
      int bf = m.body[f], bg = m.body[g];
      const auto &vf = net.shell_faces[f], &vg = net.shell_faces[g];
      if (share_vertex(vf, vg)) {
        if (touching_pair_collides(tri[f], tri[g], vf, vg)) hit = true, res.face_a = f, res.face_b = g;
        return;
      }
      // Relative motion: only the joints between the two pieces and their common ancestor count.
      double L = 0, S_f = 0, S_g = 0;
      for (int a = bf, c = bg; a != c;) {
        if (body_depth[a] >= body_depth[c]) {
          L += lever(f, a), S_f += std::abs(m.angle[m.body_root[a]]), a = body_parent[a];
        } else {
          L += lever(g, c), S_g += std::abs(m.angle[m.body_root[c]]), c = body_parent[c];
        }
      }
      double S = std::max(S_f, S_g);
      double lower = (centre[f] - centre[g]).norm() - rad[f] - rad[g];
      if (travel(dt, L, S) < lower) return;
      double d = triangle_distance(tri[f], tri[g]);
      if (d <= 0) {
        hit = true, res.face_a = f, res.face_b = g;
        return;
      }
      if (travel(dt, L, S) < d) return;
      double h = 0.9 * d / (L + d * S);
      if (h < dt) {
        dt = h;
        res.face_a = f, res.face_b = g, hit_distance = d;
      }
    };
    std::vector<std::pair<int, int>> piece_pairs;
    CGAL::box_self_intersection_d(piece_box.begin(), piece_box.end(),
                                  [&](const Box& a, const Box& b) { piece_pairs.emplace_back(a.info(), b.info()); });
    std::sort(piece_pairs.begin(), piece_pairs.end());
    auto overlap = [](const Box& a, const Box& b) {
      for (int d = 0; d < 3; ++d)
        if (a.max_coord(d) < b.min_coord(d) || b.max_coord(d) < a.min_coord(d)) return false;
      return true;
    };
    for (auto [pa, pb] : piece_pairs) {
      if (hit) break;
      auto &A = piece_boxes[pa], &B = piece_boxes[pb];
      if (A.size() * B.size() <= 256) {
        for (auto& a : A)
          for (auto& b : B)
            if (overlap(a, b)) check_pair(a.info(), b.info());
      } else {
        std::vector<Box> a(A), b(B);
        CGAL::box_intersection_d(a.begin(), a.end(), b.begin(), b.end(),
                                 [&](const Box& x, const Box& y) { check_pair(x.info(), y.info()); });
      }
    }
    if (hit) {
      res.t = t;
      std::ostringstream os;
      os << "faces " << res.face_a << " and " << res.face_b << " collide at t = " << t;
      res.message = os.str();
      return res;
    }
    if (dt < options.min_step) {
      res.t = t;
      std::ostringstream os;
      os << "faces " << res.face_a << " and " << res.face_b << " come within " << hit_distance << " at t = " << t
         << " (step below " << options.min_step << ")";
      res.message = os.str();
      return res;
    }
    res.face_a = res.face_b = -1;
    t += dt;
    if (t >= 1) {
      res.verified = true;
      res.t = 1;
      ++res.steps;
      return res;
    }
  }
  res.t = t;
  res.message = "step limit reached at t = " + std::to_string(t);
  return res;
}

}  // namespace dcshell
