// Continuous folding check along the straight line in configuration space (see fold_check.h and
// doc/fold_check.md for the argument).
#include "dcshell/fold_check.h"
#include "dcshell/net_overlap.h"
#include "unfold/box_sweep.h"
#include "unfold/pair_slots.h"

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace dcshell {

namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();

// (cos, sin) of k pi / 16 for k = 0..16, ends exact: the tilt grid of the separating planes,
// computed once (the planes are tried for every touching pair at every step).
struct TiltTable {
  double v[17][2];
  TiltTable() {
    for (int k = 0; k <= 16; ++k) v[k][0] = std::cos(k * M_PI / 16), v[k][1] = std::sin(k * M_PI / 16);
    v[0][1] = v[16][1] = 0, v[16][0] = -1;
  }
  const double* operator[](int k) const { return v[k]; }
};
const TiltTable kTilt;

// Folds whose angle is below this move nothing visible: the faces they join are one rigid piece
// (the motion itself treats them as rigid, so the piece is exactly planar along the path).
constexpr double kRigidAngle = 1e-4;
// Depth (x net size) by which faces must cross to count as a sure collision: rounding is far below
// it (find_sampled_collision's default margin).
constexpr double kCrossMargin = 1e-7;

struct Rigid {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Vec3 tr = Vec3::Zero();
  Vec3 operator()(const Vec3& x) const { return R * x + tr; }
};

struct Motion {
  int nf = 0;
  std::vector<int> order;  // parents before children
  std::vector<int> parent;
  std::vector<double> angle;          // fold angle of the edge to the parent (0 for the root)
  std::vector<Vec3> axis_a, axis_u;   // fold axis in net coordinates (parent on the left)
  std::vector<int> body;              // rigid piece of each face
  std::vector<int> body_root;         // the face whose fold moves the piece
  std::vector<std::vector<int>> body_faces;

  explicit Motion(const Net& net) {
    nf = static_cast<int>(net.corners.size());
    parent = net.parent;
    if (static_cast<int>(parent.size()) != nf || static_cast<int>(net.shell_faces.size()) != nf)
      throw std::invalid_argument("fold check: net arrays differ in size");
    angle.assign(nf, 0.0);
    axis_a.assign(nf, Vec3::Zero());
    axis_u.assign(nf, Vec3::UnitX());
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
        axis_a[f] = Vec3(A.x(), A.y(), 0);
        axis_u[f] = Vec3(B.x() - A.x(), B.y() - A.y(), 0).normalized();
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

  // The turn of a fold at state t: x -> a + Q (x - a), Q = rotation by t*angle about u.
  // A positive angle turns the child below the plane (the outside of the shell faces +z).
  static Rigid child_transform(const Rigid& P, const Vec3& a, const Vec3& u, double turn) {
    Eigen::Matrix3d Q = Eigen::AngleAxisd(turn, u).toRotationMatrix();
    Rigid T;
    T.R = P.R * Q;
    T.tr = P.R * (a - Q * a) + P.tr;
    return T;
  }

  // Placement of every face at time t: T_f = T_parent o rotation about the fold axis by t*angle.
  std::vector<Rigid> transforms(double t) const {
    std::vector<Rigid> T(nf);
    for (int f : order) {
      int p = parent[f];
      if (p < 0) continue;
      T[f] = body[f] == body[p] ? T[p] : child_transform(T[p], axis_a[f], axis_u[f], t * angle[f]);
    }
    return T;
  }
};

Vec3 lift(const Vec2& p) { return Vec3(p.x(), p.y(), 0); }

// Does an edge of triangle a pass through the interior of triangle b, clear of b's plane and
// of b's sides by more than m? (Rounding of the folded coordinates is far below m.)
bool edge_pierces(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b, double m) {
  Vec3 n = (b[1] - b[0]).cross(b[2] - b[0]);
  const double nn = n.norm();
  if (!(nn > 0)) return false;
  n /= nn;
  for (int k = 0; k < 3; ++k) {
    const Vec3 &p = a[k], &q = a[(k + 1) % 3];
    const double sp = n.dot(p - b[0]), sq = n.dot(q - b[0]);
    if (!((sp > m && sq < -m) || (sp < -m && sq > m))) continue;
    const Vec3 x = p + (q - p) * (sp / (sp - sq));
    bool inside = true;
    for (int i = 0; i < 3 && inside; ++i) {
      const Vec3 side = b[(i + 1) % 3] - b[i];
      const double len = side.norm();
      inside = len > 0 && n.cross(side).dot(x - b[i]) > m * len;
    }
    if (inside) return true;
  }
  return false;
}

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// A rigid piece: its faces, its place in the piece tree, and the convex hull of its net corners
// (counter-clockwise; drops corners within `eps` of the hull boundary).
struct Piece {
  std::vector<int> faces;
  int parent = -1, depth = 0;
  double angle = 0;  // fold angle of the hinge to the parent piece
  Vec3 hinge_a = Vec3::Zero(), hinge_u = Vec3::UnitX();  // hinge axis in net coordinates
  std::vector<Vec2> hull;
  std::vector<int> hull_vertex;  // shell vertex at each hull corner
  std::vector<std::pair<int, Vec2>> corners;  // (shell vertex, net position), sorted, unique
  Vec2 centre = Vec2::Zero();
  double radius = 0;
  int proved_group = -1;  // FoldCheckOptions::proved_group of all its faces, else -1
};

std::vector<int> convex_hull_2d(const std::vector<Vec2>& p, double eps) {
  std::vector<int> idx(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) idx[i] = static_cast<int>(i);
  std::sort(idx.begin(), idx.end(), [&](int a, int b) { return p[a].x() < p[b].x() || (p[a].x() == p[b].x() && p[a].y() < p[b].y()); });
  if (idx.size() < 3) return idx;
  std::vector<int> h(2 * idx.size());
  int k = 0;
  // A corner is kept only if it turns left by more than eps (distance from the chord): corners
  // dropped are within eps of the hull, which the contact tolerance covers.
  auto left = [&](int o, int a, int b) {
    Vec2 d = p[b] - p[o];
    double n = d.norm();
    return n > 0 && cross2(p[a] - p[o], d) > eps * n;
  };
  for (int i : idx) {
    while (k >= 2 && !left(h[k - 2], h[k - 1], i)) --k;
    h[k++] = i;
  }
  for (int j = static_cast<int>(idx.size()) - 2, lo = k + 1; j >= 0; --j) {
    int i = idx[j];
    while (k >= lo && !left(h[k - 2], h[k - 1], i)) --k;
    h[k++] = i;
  }
  h.resize(k - 1);
  return h;
}

// Convex polygon in 3D at the current state: corners (counter-clockwise about n), normal.
struct Poly {
  std::vector<Vec3> v;
  Vec3 n;
};

double segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) return r.norm();
  if (a <= 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    double c = d1.dot(r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      double b = d1.dot(d2), den = a * e - b * b;
      s = den > 0 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) t = 0, s = std::clamp(-c / a, 0.0, 1.0);
      else if (t > 1) t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
    }
  }
  return ((p0 + s * d1) - (q0 + t * d2)).norm();
}

bool inside_polygon(const Poly& P, const Vec3& x) {
  const int m = static_cast<int>(P.v.size());
  for (int i = 0; i < m; ++i)
    if (P.n.dot((P.v[(i + 1) % m] - P.v[i]).cross(x - P.v[i])) < 0) return false;
  return true;
}

// Distance between two convex polygons in 3D (0 when they meet): an edge of one crossing the
// other, else the least vertex-to-face or edge-to-edge distance (where disjoint convex polygons
// attain their distance). `margin` (far above the rounding of the coordinates) lets pairs of
// edges whose bounding spheres are farther apart than the least distance found plus margin be
// skipped: they cannot lower the minimum, so the result is the same as without skipping.
double polygon_distance(const Poly& A, const Poly& B, double margin) {
  auto crosses = [](const Poly& P, const Poly& Q) {
    const int m = static_cast<int>(P.v.size());
    for (int i = 0; i < m; ++i) {
      const Vec3 &s0 = P.v[i], &s1 = P.v[(i + 1) % m];
      double h0 = Q.n.dot(s0 - Q.v[0]), h1 = Q.n.dot(s1 - Q.v[0]);
      if ((h0 > 0 && h1 < 0) || (h0 < 0 && h1 > 0)) {
        Vec3 c = s0 + (s1 - s0) * (h0 / (h0 - h1));
        if (inside_polygon(Q, c)) return true;
      }
    }
    return false;
  };
  if (crosses(A, B) || crosses(B, A)) return 0;
  double d = kInf;
  auto faces = [&](const Poly& P, const Poly& Q) {
    for (const auto& x : P.v) {
      const double h = std::abs(Q.n.dot(x - Q.v[0]));
      if (!(h < d)) continue;  // min(d, h) = d whatever the inside test says
      Vec3 y = x - Q.n * Q.n.dot(x - Q.v[0]);
      if (inside_polygon(Q, y)) d = std::min(d, h);
    }
  };
  faces(A, B), faces(B, A);
  const int ma = static_cast<int>(A.v.size()), mb = static_cast<int>(B.v.size());
  // Edge midpoints and half-lengths of B (bounding spheres).
  thread_local std::vector<Vec3> mid;
  thread_local std::vector<double> half;
  mid.resize(mb), half.resize(mb);
  for (int j = 0; j < mb; ++j) {
    const Vec3 &b0 = B.v[j], &b1 = B.v[(j + 1) % mb];
    mid[j] = 0.5 * (b0 + b1), half[j] = 0.5 * (b1 - b0).norm();
  }
  for (int i = 0; i < ma; ++i) {
    const Vec3 &a0 = A.v[i], &a1 = A.v[(i + 1) % ma];
    const Vec3 ma_i = 0.5 * (a0 + a1);
    const double ha = 0.5 * (a1 - a0).norm();
    for (int j = 0; j < mb; ++j) {
      // Lower bound above the minimum (compared squared, without a root: both sides are >= 0).
      const double reach = d + margin + ha + half[j];
      if ((ma_i - mid[j]).squaredNorm() > reach * reach) continue;
      d = std::min(d, segment_distance(a0, a1, B.v[j], B.v[(j + 1) % mb]));
    }
  }
  return d;
}

// Great-circle arc on the unit sphere: from a, turning about n (unit) by alpha in [0, pi].
struct Arc {
  Vec3 a, b, n;
  double alpha = 0;
};

double angle_between(const Vec3& x, const Vec3& y) { return std::atan2(x.cross(y).norm(), x.dot(y)); }

// Does the unit vector p (on the arc's great circle) lie on the arc, widened by slack radians?
bool on_arc(const Arc& A, const Vec3& p, double slack) {
  double phi = std::atan2(A.n.dot(A.a.cross(p)), A.a.dot(p));
  if (phi < -slack) phi += 2 * M_PI;
  return phi <= A.alpha + slack;
}

double point_arc_distance(const Vec3& p, const Arc& A) {
  Vec3 q = p - A.n * A.n.dot(p);
  double qn = q.norm();
  if (qn > 1e-12 && on_arc(A, q / qn, 0)) return std::asin(std::min(1.0, std::abs(A.n.dot(p))));
  return std::min(angle_between(p, A.a), angle_between(p, A.b));
}

// Spherical distance between two arcs (0 when they meet; a slack of 1e-12 rad counts as meeting).
double arc_distance(const Arc& A, const Arc& B) {
  constexpr double kSlack = 1e-12;
  Vec3 k = A.n.cross(B.n);
  double kn = k.norm();
  if (kn > 1e-12) {
    k /= kn;
    for (const Vec3& s : {k, Vec3(-k)})
      if (on_arc(A, s, kSlack) && on_arc(B, s, kSlack)) return 0;
  } else {
    // One great circle: they overlap iff an end of one lies on the other.
    if (on_arc(A, B.a, kSlack) || on_arc(A, B.b, kSlack) || on_arc(B, A.a, kSlack) || on_arc(B, A.b, kSlack)) return 0;
  }
  return std::min({point_arc_distance(A.a, B), point_arc_distance(A.b, B), point_arc_distance(B.a, A), point_arc_distance(B.b, A)});
}


enum class PairKind { hinge, cone, general };

struct PairInfo {
  PairKind kind = PairKind::general;
  bool done = false;       // proved disjoint for the rest of the path
  double window = 0;       // proved disjoint on [1 - window, 1] (end window)
  int cone_vertex = -1;    // shell vertex kept in common (cone pairs)
  Vec2 cone_at = Vec2::Zero();
  std::vector<int> up_p, up_q;  // pieces whose hinges lie between each piece and the common ancestor
  std::vector<int> fixed;       // shell vertices the two pieces keep in common along the path
  std::vector<Vec2> fixed_at;   // and their net positions
  bool shares = false;          // the pieces share a shell vertex (they touch in the folded shell)
  double Sp = 0, Sq = 0;        // sum of |fold angles| of up_p, up_q (constant along the path)
  int flat_apart = -1;          // faces do not overlap in the flat net (1), do (0), not tested yet (-1)
  int end_touch = -1;           // hulls touch at t = 1, up to rounding (1), not (0), not tested yet (-1)
};

class Checker {
 public:
  Checker(const Net& net, const FoldCheckOptions& opt) : net_(net), opt_(opt), m_(net) {}

  FoldCheckResult run();

 private:
  // Steps the path from t0 to t_stop: 1, or where an end already proved begins (the set-up
  // done). screening: a pair proved to the end is not marked done in its slot (a later pass
  // from an earlier t0 must examine it again).
  FoldCheckResult step_path(double t0, bool screening, double t_stop = 1);

  const Net& net_;
  const FoldCheckOptions& opt_;
  Motion m_;
  std::vector<Piece> pc_;
  double scale_ = 0, tol_ = 0;
  // Candidate pairs over all steps, and their bound (FoldCheckOptions::pairs_per_work); corners
  // tested against planes by plane_advance and plane_window (corners_per_work).
  long long pair_tests_ = 0, corner_tests_ = 0;
  double pair_cap_ = 0;
  void account(FoldCheckResult& r, long long steps) const {
    r.pair_tests = pair_tests_, r.corner_tests = corner_tests_;
    r.work = steps * std::max(r.pieces, 1);
    if (opt_.pairs_per_work > 0)
      r.work = std::max(r.work, static_cast<long long>(static_cast<double>(pair_tests_) / opt_.pairs_per_work));
    if (opt_.corners_per_work > 0)
      r.work = std::max(r.work, static_cast<long long>(static_cast<double>(corner_tests_) / opt_.corners_per_work));
  }
  // Pairs examined so far (stable addresses), found through a dense p x q table while there are
  // at most kDensePieces pieces, else through per-piece sorted rows (pair_slots.h).
  static constexpr int kDensePieces = 2048;
  // The step loop skips most candidates (done, or covered beyond the step) reading only the
  // slot (kDone) and two compact arrays per pair, not the pair's record.
  static constexpr int kDone = -2;
  std::deque<PairInfo> pairs_;
  // Per pair: proved disjoint from the state it was last examined at up to safe_until_, and by
  // its end window from end_from_ = 1 - window on.
  std::vector<double> safe_until_, end_from_;
  std::vector<int> pair_slot_;
  unfold_detail::PairSlots pair_rows_;
  // Running sums of |angle| x lever of each piece about the hinges on its way to the root
  // (offset per piece), at the current state: computed once per step, so a pair's lever sum up
  // to its common ancestor is one lookup per piece (paths are tens of hinges long).
  std::vector<int> lever_off_;
  std::vector<double> lever_;
  std::vector<Rigid> T1_;             // pieces in the folded state (t = 1)
  std::vector<Vec3> aa1_, au1_;       // and their hinge axes there

  // State-dependent data (set by place()).
  std::vector<Rigid> T_;
  std::vector<Vec3> axis_w_a_, axis_w_u_;  // hinge axis of each piece in the current state
  std::vector<Poly> poly_;
  std::vector<Vec3> centre_;
  // Velocity field of each piece relative to the root: v(x) = om_ x x - cv_ (sums of
  // angle x axis and angle x axis x point over the hinges on its way to the root).
  std::vector<Vec3> om_, cv_;
  // Scratch of plane_advance.
  std::vector<Vec3> pa_vel_, pa_dirs_;
  std::vector<double> pa_L_, pa_hz_, pa_hm_, pa_dz_, pa_dm_;
  std::vector<char> pa_fixed_;
  // Scratch of plane_window.
  std::vector<Vec3> pw_xp_, pw_xq_, pw_vel_;
  std::vector<double> pw_L_;
  std::vector<char> pw_fixed_;
  unfold_detail::BoxSweep sweep_;  // broad phase

  void build_pieces();
  void place(double t);
  double lever(int piece, int joint) const {  // |angle| x distance of the piece's bounding sphere to the joint axis
    Vec3 w = centre_[piece] - axis_w_a_[joint];
    return std::abs(pc_[joint].angle) * ((w - w.dot(axis_w_u_[joint]) * axis_w_u_[joint]).norm() + pc_[piece].radius);
  }
  int& slot(int p, int q);  // kDone, or the pair's index in pairs_ (classified on first sight)
  bool flat_overlap(int p, int q) const;
  bool faces_cross(int p, int q) const;
  void classify(int p, int q, PairInfo& pi);
  double end_window(int p, int q, PairInfo& pi);
  double plane_window(int p, int q, const PairInfo& pi);
  double plane_advance(int p, int q, const PairInfo& pi);
  double taylor_step(int p, int q, double d, double L, const PairInfo& pi) const;
  bool unprovable_at_end(int p, int q, PairInfo& pi);
  // S = the sum of |fold angles| on the tree path between pieces p and q (bounds their relative
  // angular speed and acceleration).
  double path_angle(const PairInfo& pi) const { return pi.Sp + pi.Sq; }
  bool near_fixed(const Piece& Q, int i, const PairInfo& pi, double S) const;
  bool near_common_line(int p, int q, const PairInfo& pi) const;
  bool cone_arc(int p, const Vec2& at, Arc* arc) const;
  // The hull corner after corner i of piece p in direction step (+1 / -1) that is farther than
  // the contact tolerance from it: a hull side of 1e-11 has a direction made of rounding noise,
  // and what a wedge or plane built past it leaves out lies within that tolerance.
  int hull_step(int p, int i, int step) const {
    const auto& H = pc_[p].hull;
    const int m = static_cast<int>(H.size());
    for (int k = 1; k < m; ++k) {
      int j = ((i + step * k) % m + m) % m;
      if ((H[j] - H[i]).norm() > tol_) return j;
    }
    return ((i + step) % m + m) % m;
  }
  int face_near(int piece, const Vec3& world) const;
  std::vector<Vec3> hull_world(int p, const Rigid& T) const {
    std::vector<Vec3> out;
    for (const auto& h : pc_[p].hull) out.push_back(T(lift(h)));
    return out;
  }
};

void Checker::build_pieces() {
  const int nb = static_cast<int>(m_.body_root.size());
  pc_.assign(nb, {});
  if (nb > kDensePieces) pair_rows_.resize(nb);  // slot(): the dense table is too large
  double eps = 1e-12 * scale_;
  for (int b = 0; b < nb; ++b) {
    Piece& P = pc_[b];
    P.faces = m_.body_faces[b];
    int j = m_.body_root[b];
    if (m_.parent[j] >= 0) {
      P.parent = m_.body[m_.parent[j]];
      P.depth = pc_[P.parent].depth + 1;  // body ids follow the breadth-first order
      P.angle = m_.angle[j];
      P.hinge_a = m_.axis_a[j];
      P.hinge_u = m_.axis_u[j];
    }
    if (opt_.proved_group.size() == net_.shell_faces.size()) {
      P.proved_group = opt_.proved_group[P.faces.front()];
      for (int f : P.faces)
        if (opt_.proved_group[f] != P.proved_group) P.proved_group = -1;
    }
    for (int f : P.faces)
      for (int k = 0; k < 3; ++k) P.corners.emplace_back(net_.shell_faces[f][k], net_.corners[f][k]);
    std::sort(P.corners.begin(), P.corners.end(), [](const auto& x, const auto& y) {
      return x.first != y.first ? x.first < y.first : x.second.x() != y.second.x() ? x.second.x() < y.second.x() : x.second.y() < y.second.y();
    });
    P.corners.erase(std::unique(P.corners.begin(), P.corners.end(),
                                [](const auto& x, const auto& y) { return x.first == y.first && x.second == y.second; }),
                    P.corners.end());
    std::vector<Vec2> pts;
    for (auto& c : P.corners) pts.push_back(c.second);
    for (int i : convex_hull_2d(pts, eps)) P.hull.push_back(pts[i]), P.hull_vertex.push_back(P.corners[i].first);
    for (auto& h : P.hull) P.centre += h;
    P.centre /= static_cast<double>(P.hull.size());
    for (auto& c : P.corners) P.radius = std::max(P.radius, (c.second - P.centre).norm());
  }
}

void Checker::place(double t) {
  const int nb = static_cast<int>(pc_.size());
  T_.assign(nb, Rigid());
  axis_w_a_.assign(nb, Vec3::Zero());
  axis_w_u_.assign(nb, Vec3::UnitX());
  om_.assign(nb, Vec3::Zero());
  cv_.assign(nb, Vec3::Zero());
  for (int b = 1; b < nb; ++b) {  // parents first (breadth-first ids)
    const Piece& P = pc_[b];
    const Rigid& A = T_[P.parent];
    T_[b] = Motion::child_transform(A, P.hinge_a, P.hinge_u, t * P.angle);
    axis_w_a_[b] = A(P.hinge_a);
    axis_w_u_[b] = A.R * P.hinge_u;
    const Vec3 w = P.angle * axis_w_u_[b];
    om_[b] = om_[P.parent] + w;
    cv_[b] = cv_[P.parent] + w.cross(axis_w_a_[b]);
  }
  poly_.resize(nb);
  centre_.resize(nb);
  for (int b = 0; b < nb; ++b) {
    // In place: the corner arrays keep their storage from step to step.
    const auto& H = pc_[b].hull;
    auto& v = poly_[b].v;
    v.resize(H.size());
    for (std::size_t i = 0; i < H.size(); ++i) v[i] = T_[b](lift(H[i]));
    poly_[b].n = T_[b].R.col(2);
    centre_[b] = T_[b](lift(pc_[b].centre));
  }
}

int& Checker::slot(int p, int q) {
  const int nb = static_cast<int>(pc_.size());
  int* slot;
  if (nb <= kDensePieces) {
    if (pair_slot_.empty()) pair_slot_.assign(static_cast<std::size_t>(nb) * nb, -1);
    slot = &pair_slot_[static_cast<std::size_t>(p) * nb + q];
  } else {
    slot = &pair_rows_(p, q);  // valid until the next insertion: classify() inserts none
  }
  if (*slot != -1) return *slot;
  pairs_.emplace_back();
  PairInfo& pi = pairs_.back();
  classify(p, q, pi);
  safe_until_.push_back(0);
  end_from_.push_back(1 - pi.window);
  *slot = pi.done ? kDone : static_cast<int>(pairs_.size()) - 1;
  return *slot;
}

// The hull's wedge at net point `at` as an arc of directions (in net coordinates, z = 0): the
// two hull edges at that corner, or a half-plane when `at` lies on a hull edge.
bool Checker::cone_arc(int p, const Vec2& at, Arc* arc) const {
  const auto& H = pc_[p].hull;
  const int m = static_cast<int>(H.size());
  if (m < 2) return false;
  double eps = 1e-10 * scale_;
  if (m == 2) {  // a sliver narrower than the hull's tolerance: its wedge at an end is one ray
    for (int i = 0; i < 2; ++i)
      if ((H[i] - at).norm() <= eps) {
        arc->a = arc->b = lift((H[1 - i] - H[i]).normalized()), arc->n = Vec3::UnitZ(), arc->alpha = 0;
        return true;
      }
  }
  for (int i = 0; i < m; ++i)
    if ((H[i] - at).norm() <= eps) {
      Vec2 e1 = (H[hull_step(p, i, 1)] - H[i]).normalized(), e2 = (H[hull_step(p, i, -1)] - H[i]).normalized();
      arc->a = lift(e1), arc->b = lift(e2), arc->n = Vec3::UnitZ();
      arc->alpha = std::atan2(cross2(e1, e2), e1.dot(e2));
      return arc->alpha > 0;
    }
  for (int i = 0; i < m; ++i) {
    Vec2 d = H[(i + 1) % m] - H[i];
    double len = d.norm();
    double s = (at - H[i]).dot(d) / (len * len);
    if (s > 0 && s < 1 && std::abs(cross2(d, at - H[i])) / len <= eps) {
      arc->a = lift(d / len), arc->b = -arc->a, arc->n = Vec3::UnitZ(), arc->alpha = M_PI;
      return true;
    }
  }
  return false;
}

// Hinge, cone or general: which shell vertices the two pieces keep in common (same net position,
// on every hinge line between them, hence never moving apart) decides it.
void Checker::classify(int p, int q, PairInfo& pi) {
  for (int a = p, c = q; a != c;) {
    if (pc_[a].depth >= pc_[c].depth) pi.up_p.push_back(a), a = pc_[a].parent;
    else pi.up_q.push_back(c), c = pc_[c].parent;
  }
  for (int b : pi.up_p) pi.Sp += std::abs(pc_[b].angle);
  for (int b : pi.up_q) pi.Sq += std::abs(pc_[b].angle);
  if (pi.up_p.size() + pi.up_q.size() == 1) {
    // Adjacent pieces turn about one exact line l (their hinge). Their planes are distinct while
    // the turn stays in (0, pi), so they can meet only on l, where nothing moves relative to
    // either: p(t) and q(t) meet at most where the flat net's pieces meet on l. That holds on
    // whichever side of l each piece lies; it only needs the flat pieces to overlap nowhere
    // (a bend of 1e-6 in a nearly straight chain of glued fold edges puts hull corners on the
    // wrong side of the hinge, which the convex hulls cannot tell from an overlap).
    const Piece& child = pc_[pi.up_p.empty() ? pi.up_q[0] : pi.up_p[0]];
    const Vec2 a = child.hinge_a.head<2>(), u = child.hinge_u.head<2>();
    auto side = [&](int b, double sign) {  // every hull corner of b on the closed side `sign` of l
      for (const auto& h : pc_[b].hull)
        if (sign * cross2(u, h - a) < -1e-10 * scale_) return false;
      return true;
    };
    bool apart = (side(p, 1) && side(q, -1)) || (side(p, -1) && side(q, 1));
    if (std::abs(child.angle) < M_PI - 1e-9 && (apart || !flat_overlap(p, q))) {
      pi.kind = PairKind::hinge;
      pi.done = true;
      return;
    }
  }
  const double eps = 1e-10 * scale_;
  const auto &A = pc_[p].corners, &B = pc_[q].corners;
  std::vector<Vec2>& fixed_at = pi.fixed_at;
  std::vector<Vec2> strict_at;  // the fixed corners that lie on every hinge line exactly
  for (std::size_t i = 0, j = 0; i < A.size() && j < B.size();) {
    if (A[i].first < B[j].first) ++i;
    else if (B[j].first < A[i].first) ++j;
    else {
      int v = A[i].first;
      for (std::size_t i2 = i; i2 < A.size() && A[i2].first == v; ++i2)
        for (std::size_t j2 = j; j2 < B.size() && B[j2].first == v; ++j2) {
          const Vec2& x = A[i2].second;
          if ((x - B[j2].second).norm() > eps) continue;
          // On every hinge line between the pieces; or so near them that its two copies never
          // part by more than the contact tolerance: a copy's distance to a hinge's axis is the
          // same in every state, so its travel is at most sum |angle| x that distance (a corner
          // of a glued chain that rounding bends by 1e-8).
          bool on_all = true;
          double travel = 0;
          for (const auto* side : {&pi.up_p, &pi.up_q})
            for (int b : *side) {
              Vec2 a2 = pc_[b].hinge_a.head<2>(), u2 = pc_[b].hinge_u.head<2>();
              const double d = std::abs(cross2(u2, x - a2));
              on_all = on_all && d <= eps;
              travel += std::abs(pc_[b].angle) * d;
            }
          if ((on_all || travel <= tol_) && (pi.fixed.empty() || pi.fixed.back() != v)) {
            pi.fixed.push_back(v), fixed_at.push_back(x);
            if (on_all) strict_at.push_back(x);
          }
        }
      while (i < A.size() && A[i].first == v) ++i;
      while (j < B.size() && B[j].first == v) ++j;
    }
  }
  if (strict_at.size() >= 2) {
    // Both pieces turn about the line through two common fixed corners (all hinges between them
    // lie on it). Planar pieces on opposite closed sides of a common line meet only on it while
    // their relative turn stays below pi; on the line nothing moves, so they meet there as in the
    // flat net (where they only touch).
    Vec2 o = strict_at[0], d = (strict_at[1] - strict_at[0]).normalized();
    double lo_p = kInf, hi_p = -kInf, lo_q = kInf, hi_q = -kInf;
    for (auto& h : pc_[p].hull) lo_p = std::min(lo_p, cross2(d, h - o)), hi_p = std::max(hi_p, cross2(d, h - o));
    for (auto& h : pc_[q].hull) lo_q = std::min(lo_q, cross2(d, h - o)), hi_q = std::max(hi_q, cross2(d, h - o));
    bool opposite = (hi_p <= eps && lo_q >= -eps) || (hi_q <= eps && lo_p >= -eps);
    double turn = 0;
    for (int b : pi.up_p) turn -= pc_[b].angle * (pc_[b].hinge_u.head<2>().dot(d) > 0 ? 1 : -1);
    for (int b : pi.up_q) turn += pc_[b].angle * (pc_[b].hinge_u.head<2>().dot(d) > 0 ? 1 : -1);
    if (opposite && std::abs(turn) < M_PI - 1e-9) {
      pi.kind = PairKind::hinge;
      pi.done = true;
      return;
    }
  }
  if (near_common_line(p, q, pi)) {
    pi.kind = PairKind::hinge;
    pi.done = true;
    return;
  }
  if (fixed_at.size() == 1 && strict_at.size() == 1) {  // the cone needs the exact apex
    Arc arc;
    if (cone_arc(p, fixed_at[0], &arc) && cone_arc(q, fixed_at[0], &arc)) {
      pi.kind = PairKind::cone;
      pi.cone_vertex = pi.fixed[0];
      pi.cone_at = fixed_at[0];
    }
  }
  pi.window = end_window(p, q, pi);
}

// Pieces joined through a sliver (a shell face 1e-10 wide between them, or along their hinge)
// turn about several hinges on nearly one line, so no two common corners lie on every hinge
// exactly and their hulls touch along it in the flat net. The line argument above holds up to a
// bound. Let l be the hinge line with the largest turn and x a point on it. A hinge b's rotation
// and the same rotation about l differ at y by at most |angle_b| (delta_b + (1 + |angle_b|)
// theta_b |y - x|) (delta_b: distance of x to b's line; theta_b: the angle between the lines;
// Rodrigues' formula), and rotations about l keep |y - x|, so along the chain of hinges between
// the pieces the errors add. When their sum, over the corners of the piece that moves, stays
// within the contact tolerance, that piece stays within the tolerance of its rotation about l,
// which meets the other only on l while the two lie on opposite closed sides of l in the flat net
// and the summed turn stays below pi: they come that close only along l, as hinged pieces do.
bool Checker::near_common_line(int p, int q, const PairInfo& pi) const {
  const double eps = 1e-10 * scale_;
  int best = -1;
  for (const auto* side : {&pi.up_p, &pi.up_q})
    for (int b : *side)
      if (best < 0 || std::abs(pc_[b].angle) > std::abs(pc_[best].angle)) best = b;
  if (best < 0 || pc_[best].hinge_u.head<2>().norm() == 0) return false;
  const Vec2 a = pc_[best].hinge_a.head<2>(), d = pc_[best].hinge_u.head<2>().normalized();
  auto extent = [&](int piece, double& lo, double& hi) {
    lo = kInf, hi = -kInf;
    for (const auto& h : pc_[piece].hull) lo = std::min(lo, cross2(d, h - a)), hi = std::max(hi, cross2(d, h - a));
  };
  double lo_p, hi_p, lo_q, hi_q;
  extent(p, lo_p, hi_p);
  extent(q, lo_q, hi_q);
  if (!((hi_p <= eps && lo_q >= -eps) || (hi_q <= eps && lo_p >= -eps))) return false;
  // Measured from the foot of the smaller piece's centre on l: the relative motion of either
  // piece against the other is made of the same rotations.
  const int m = pc_[p].radius <= pc_[q].radius ? p : q;
  const Vec2 x = a + d * d.dot(pc_[m].centre - a);
  double reach = 0;
  for (const auto& h : pc_[m].hull) reach = std::max(reach, (h - x).norm());
  double dev = 0, turn = 0;
  for (const auto* side : {&pi.up_p, &pi.up_q})
    for (int b : *side) {
      const Vec2 u = pc_[b].hinge_u.head<2>().normalized(), ab = pc_[b].hinge_a.head<2>();
      const double alpha = std::abs(pc_[b].angle);
      const double theta = std::asin(std::min(1.0, std::abs(cross2(u, d))));
      dev += alpha * (std::abs(cross2(u, x - ab)) + (1 + alpha) * theta * reach);
      turn += (side == &pi.up_q ? 1 : -1) * pc_[b].angle * (u.dot(d) > 0 ? 1 : -1);
    }
  return dev <= tol_ && std::abs(turn) < M_PI - 1e-9;
}

// Plane advancement for a pair at (nearly) zero distance, from the current state t: the largest
// tau such that a plane fixed to piece p keeps p on one closed side and q strictly on the other on
// (t, t + tau]; 0 when none is found. Distance stepping crawls there (two corners 1e-6 off a
// common hinge stay ~1e-6 apart the whole way; t = 0 touches stop it at once), while the first
// order motion separates them: the mirror of plane_window. Planes pass through the support point
// c of p's hull in direction m (p's outward edge normals, q's inward ones, in p's plane), normal
// n = cos(phi) n_p + sin(phi) m, phi on a grid in [0, pi]: p lies in its plane on the side
// m.(y - c) <= 0, so n.(y - c) <= 0 on all of p. For q's hull corners x: h = n.(x - c) >= -tol,
// h' = n . w(x) with w the velocity of x relative to p, and h(t + s) >= max(h, 0) + s h' - s^2 M / 2
// with M = 4 S L(x) as in the end window (s <= 1/(2S)): positive up to the positive root. A
// corner within tol of the plane needs h' > 0 by a margin over rounding. Corners kept in common
// on every hinge are excluded (they never move apart).

// Hull corner i of Q counts as kept in common when it is a fixed corner, or lies so close to one
// (a sliver's corners 1e-11 apart merge into one hull corner) that its whole travel relative to
// the other piece, at most S x that distance, stays within the contact tolerance.
bool Checker::near_fixed(const Piece& Q, int i, const PairInfo& pi, double S) const {
  if (std::find(pi.fixed.begin(), pi.fixed.end(), Q.hull_vertex[i]) != pi.fixed.end()) return true;
  for (const Vec2& x : pi.fixed_at)
    if ((Q.hull[i] - x).norm() * std::max(S, 1.0) <= tol_) return true;
  return false;
}

// A general pair without an end window or common fixed corners whose hulls touch at t = 1 (up
// to rounding) can never be proved up to t = 1: distance advancement needs a distance above the
// tolerance there (its step from t never reaches 1 - t: the travel to t = 1 is at least the
// distance), and plane advancement a plane with all of q's corners strictly on its side at
// t = 1, where a point of q's hull lies on p. Such a net is not verified whatever the steps
// before, so the check stops once the pair crawls (run()) instead of taking thousands of
// shrinking steps towards t = 1 until min_step.
bool Checker::unprovable_at_end(int p, int q, PairInfo& pi) {
  if (pi.kind != PairKind::general || pi.window > 0 || !pi.fixed.empty()) return false;
  if (pi.end_touch < 0) {
    Poly A{hull_world(p, T1_[p]), T1_[p].R.col(2)}, B{hull_world(q, T1_[q]), T1_[q].R.col(2)};
    pi.end_touch = polygon_distance(A, B, tol_) <= 1e-3 * tol_;
  }
  return pi.end_touch == 1;
}

// Distance advancement to second order (every pair apart; the step taken is the larger of this
// and the lever bound): pieces that move together, or slide along each other, travel far less
// than their levers allow, and a longer proof is re-examined fewer times. The velocity of q
// relative to p is the affine field w(x) = W x x - C, exact at the state, so its largest norm
// over q's hull is at a corner (V). A point driven by a chain of
// rotations accelerates by at most 2 S L(x) (transport, centripetal and Coriolis terms; S, L
// over all hinges between the pieces); L(x) <= L + Sp (|c_p - c_q| + r_q) for x in q (q's sphere
// about p's hinges), and grows at most to 2 L(x) for s <= 1/(2S). So q's points travel at most
// s V + 2 S L s^2 relative to p; the same holds with the roles swapped. d: distance minus tolerance.
double Checker::taylor_step(int p, int q, double d, double L, const PairInfo& pi) const {
  const Vec3 W = om_[q] - om_[p], C = cv_[q] - cv_[p];
  const double S = pi.Sp + pi.Sq, cc = (centre_[p] - centre_[q]).norm();
  if (!(S > 0)) return kInf;
  double best = 0;
  for (int b : {q, p}) {
    double V = 0;
    for (const Vec3& x : poly_[b].v) V = std::max(V, (W.cross(x) - C).norm());
    const double a = 2 * S * (L + (b == q ? pi.Sp : pi.Sq) * (cc + pc_[b].radius));
    best = std::max(best, 2 * d / (V + std::sqrt(V * V + 4 * a * d)));
  }
  return std::min(best, 0.5 / S);
}

double Checker::plane_advance(int p, int q, const PairInfo& pi) {
  const bool swapped = p > q;
  const std::vector<int>& up_p = swapped ? pi.up_q : pi.up_p;
  const std::vector<int>& up_q = swapped ? pi.up_p : pi.up_q;
  const double S = path_angle(pi);
  if (S <= 0) return 0;
  const Piece& Q = pc_[q];
  const std::vector<Vec3>&xp = poly_[p].v, &xq = poly_[q].v;
  const int mp = static_cast<int>(xp.size()), mq = static_cast<int>(xq.size());
  if (mp < 2 || mq < 2) return 0;  // a sliver narrower than the hull's tolerance is a segment
  const Vec3 np = poly_[p].n;
  // Scratch arrays of the checker (no allocation per call once they have grown).
  std::vector<Vec3>& vel = pa_vel_;
  std::vector<double>& L = pa_L_;
  std::vector<char>& fixed = pa_fixed_;
  vel.assign(mq, Vec3::Zero());
  L.assign(mq, 0.0);
  fixed.assign(mq, 0);
  // Velocity relative to p: the difference of the two pieces' fields (common hinges cancel).
  const Vec3 W = om_[q] - om_[p], C = cv_[q] - cv_[p];
  for (int i = 0; i < mq; ++i) {
    const Vec3& x = xq[i];
    fixed[i] = near_fixed(Q, i, pi, S);
    vel[i] = W.cross(x) - C;
    for (const auto* side : {&up_q, &up_p})
      for (int b : *side) {
        Vec3 w = x - axis_w_a_[b];
        const Vec3& u = axis_w_u_[b];
        L[i] += std::abs(pc_[b].angle) * (w - w.dot(u) * u).norm();
      }
  }
  std::vector<Vec3>& dirs = pa_dirs_;
  dirs.clear();
  for (int i = 0; i < mp; ++i) {
    Vec3 m = (xp[(i + 1) % mp] - xp[i]).cross(np);  // outward: hull counter-clockwise about n_p
    if (m.norm() > 0) dirs.push_back(m.normalized());
  }
  if (mp == 2)  // a segment's ends are supported by its own direction
    for (const Vec3& m : {Vec3(xp[1] - xp[0]), Vec3(xp[0] - xp[1])})
      if (m.norm() > 0) dirs.push_back(m.normalized());
  for (int i = 0; i < mq; ++i) {
    Vec3 m = (xq[(i + 1) % mq] - xq[i]).cross(poly_[q].n);
    m -= m.dot(np) * np;  // q's inward edge normal, projected into p's plane
    if (m.norm() > 1e-12) dirs.push_back(-m.normalized());
  }
  double best = 0;
  std::vector<double>&hz = pa_hz_, &hm = pa_hm_, &dz = pa_dz_, &dm = pa_dm_;
  hz.resize(mq), hm.resize(mq), dz.resize(mq), dm.resize(mq);
  for (int i = 0; i < mq; ++i) hz[i] = np.dot(xq[i] - xp[0]), dz[i] = np.dot(vel[i]);
  for (const Vec3& m : dirs) {
    if (best >= 0.5 / S) break;  // no window exceeds 0.5 / S: the rest cannot change the result
    double c = -kInf;
    for (const auto& y : xp) c = std::max(c, m.dot(y));
    for (int i = 0; i < mq; ++i) hm[i] = m.dot(xq[i]) - c, dm[i] = m.dot(vel[i]);
    corner_tests_ += mp + mq;
    for (int k = 0; k <= 16 && best < 0.5 / S; ++k) {
      const double sn = kTilt[k][1], cs = kTilt[k][0];
      double window = 0.5 / S;
      corner_tests_ += mq;
      for (int i = 0; i < mq && window > best; ++i) {
        if (fixed[i]) continue;
        const double h = cs * hz[i] + sn * hm[i], dh = cs * dz[i] + sn * dm[i], M = 4 * S * L[i];
        double root;
        if (h < -tol_) {
          window = 0;
        } else if (h <= tol_) {  // on the plane: must leave it towards q's side
          if (!(dh > 1e-9 * (L[i] + scale_))) window = 0;
          root = M > 0 ? 2 * dh / M : kInf;
        } else {
          root = M > 0 ? (dh + std::sqrt(dh * dh + 2 * M * h)) / M : dh >= 0 ? kInf : h / -dh;
        }
        if (window == 0) break;
        window = std::min(window, root);
      }
      best = std::max(best, window);
    }
  }
  return best;
}

// Do the two pieces' faces overlap in the flat net (interiors, exact on the net's doubles)?
bool Checker::flat_overlap(int p, int q) const {
  using Box2 = CGAL::Box_intersection_d::Box_with_info_d<double, 2, int>;
  auto boxes = [&](int b) {
    std::vector<Box2> out;
    for (int f : pc_[b].faces) {
      const auto& c = net_.corners[f];
      double lo[2] = {std::min({c[0].x(), c[1].x(), c[2].x()}), std::min({c[0].y(), c[1].y(), c[2].y()})};
      double hi[2] = {std::max({c[0].x(), c[1].x(), c[2].x()}), std::max({c[0].y(), c[1].y(), c[2].y()})};
      out.emplace_back(lo, hi, f);
    }
    return out;
  };
  auto bp = boxes(p), bq = boxes(q);
  bool overlap = false;
  CGAL::box_intersection_d(bp.begin(), bp.end(), bq.begin(), bq.end(), [&](const Box2& a, const Box2& b) {
    overlap = overlap || triangle_interiors_overlap(net_.corners[a.info()], net_.corners[b.info()]);
  });
  return overlap;
}

// Does a face of p cross a face of q in the current state, clear of its plane and sides by the
// margin of find_sampled_collision? Then no check of this net can verify it, from whatever start.
bool Checker::faces_cross(int p, int q) const {
  using Box3 = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;
  const double margin = kCrossMargin * scale_;
  auto placed = [&](int b, std::vector<std::array<Vec3, 3>>& x, std::vector<Box3>& boxes) {
    for (int f : pc_[b].faces) {
      std::array<Vec3, 3> c;
      for (int k = 0; k < 3; ++k) c[k] = T_[b](lift(net_.corners[f][k]));
      Vec3 lo = c[0].cwiseMin(c[1]).cwiseMin(c[2]), hi = c[0].cwiseMax(c[1]).cwiseMax(c[2]);
      boxes.emplace_back(lo.data(), hi.data(), static_cast<int>(x.size()));
      x.push_back(c);
    }
  };
  std::vector<std::array<Vec3, 3>> xp, xq;
  std::vector<Box3> bp, bq;
  placed(p, xp, bp), placed(q, xq, bq);
  bool cross = false;
  CGAL::box_intersection_d(bp.begin(), bp.end(), bq.begin(), bq.end(), [&](const Box3& a, const Box3& b) {
    const auto &A = xp[a.info()], &B = xq[b.info()];
    cross = cross || edge_pierces(A, B, margin) || edge_pierces(B, A, margin);
  });
  return cross;
}

// End window for a pair that touches in the folded shell: the largest s such that the pair is
// proved disjoint (but for fixed common corners) on [1 - s, 1]; 0 when none.
double Checker::end_window(int p, int q, PairInfo& pi) {
  // Only pairs that share a shell vertex can touch at t = 1 on a convex shell; others are
  // advanced to t = 1 by distance, which stays positive there.
  bool share = !pi.fixed.empty();
  {
    const auto &A = pc_[p].corners, &B = pc_[q].corners;
    for (std::size_t i = 0, j = 0; i < A.size() && j < B.size() && !share;) {
      if (A[i].first < B[j].first) ++i;
      else if (B[j].first < A[i].first) ++j;
      else share = true;
    }
  }
  pi.shares = share;
  if (!share) return 0;
  return std::max(plane_window(p, q, pi), plane_window(q, p, pi));
}

// Window near t = 1 in which a plane fixed to piece p keeps p on one side and piece q strictly on
// the other, but for the fixed common corners; then p and q meet at most there. Candidate planes
// pass through a corner c of p shared with q: normal n = cos(phi) (-n_p) + sin(phi) m, with m an
// outward normal of p's hull at c (edge normals and their bisector), phi on a grid in [0, pi):
// phi = 0 is p's own plane; tilting about p's edge lets one plane separate a pair whose common
// edge closes with a twist. h(x) = n . (x - c) for q's corners x, in p's frame. A corner with
// h > 0 at t = 1 stays on q's side while its travel relative to p is below h. A corner on the
// plane at t = 1 needs h'(1) < 0 (it arrives from q's side); then h(1 - s) >= s |h'(1)| - s^2 M / 2
// with M >= |h''| = |relative acceleration| <= 2 S L (S = sum of |angles| between the pieces,
// L = sum of |angle| x lever), so s <= |h'(1)| / M is safe.
double Checker::plane_window(int p, int q, const PairInfo& pi) {
  const auto& T1 = T1_;
  const auto &aa = aa1_, &au = au1_;
  const bool swapped = p > q;
  const std::vector<int>& up_p = swapped ? pi.up_q : pi.up_p;
  const std::vector<int>& up_q = swapped ? pi.up_p : pi.up_q;
  const double S = path_angle(pi);
  const Piece &P = pc_[p], &Q = pc_[q];
  const int mp = static_cast<int>(P.hull.size()), mq = static_cast<int>(Q.hull.size());
  // Scratch arrays of the checker (every pair met is given its window: no allocation per pair).
  std::vector<Vec3>&xp = pw_xp_, &xq = pw_xq_, &vel = pw_vel_;
  std::vector<double>& L = pw_L_;
  std::vector<char>& fixed = pw_fixed_;
  xp.resize(mp), xq.resize(mq), vel.resize(mq);
  L.assign(mq, 0.0);
  fixed.assign(mq, 0);
  for (int i = 0; i < mp; ++i) xp[i] = T1[p](lift(P.hull[i]));
  for (int i = 0; i < mq; ++i) {
    const Vec3 x = xq[i] = T1[q](lift(Q.hull[i]));
    fixed[i] = near_fixed(Q, i, pi, S);
    // Velocity of x relative to p (world frame at t = 1): joints towards q count +, towards p -.
    vel[i].setZero();
    for (const auto* side : {&up_q, &up_p})
      for (int b : *side) {
        Vec3 w = x - aa[b];
        vel[i] += (side == &up_q ? 1 : -1) * pc_[b].angle * au[b].cross(w);
        L[i] += std::abs(pc_[b].angle) * (w - w.dot(au[b]) * au[b]).norm();
      }
  }
  corner_tests_ += static_cast<long long>(mq) * (up_p.size() + up_q.size());  // the velocities
  auto window_for = [&](const Vec3& n, const Vec3& c) {
    corner_tests_ += mp + mq;
    for (int i = 0; i < mp; ++i)
      if (n.dot(xp[i] - c) > tol_) return 0.0;
    double window = 1;
    for (int i = 0; i < mq; ++i) {
      if (fixed[i]) continue;
      double h = n.dot(xq[i] - c);
      if (h > tol_) {
        // Travel over s is at most s L / (1 - s S) (levers grow with the travel).
        window = std::min(window, (h - tol_) / (L[i] + (h - tol_) * S));
        continue;
      }
      if (h < -tol_) return 0.0;
      double rate = -n.dot(vel[i]);  // = -h'(1): how fast h grows as t goes back from 1
      if (!(rate > 1e-9 * (L[i] + scale_))) return 0.0;
      // Levers over the window grow to at most L / (1 - s S); s <= 1 / (2 S) keeps that below 2 L.
      double M = 2 * S * 2 * L[i];
      double s = M > 0 ? rate / M : 1;
      if (S > 0) s = std::min(s, 0.5 / S);
      window = std::min(window, s);
    }
    return window;
  };
  const Vec3 inward = -T1[p].R.col(2);
  double best = 0;
  for (int i = 0; i < mp; ++i) {
    int v = P.hull_vertex[i];
    bool shared = false;
    for (int j = 0; j < mq && !shared; ++j) shared = Q.hull_vertex[j] == v;
    if (!shared) continue;
    // Outward normals (in p's plane) of the hull edges at corner i, and their bisector.
    Vec3 e_next = xp[hull_step(p, i, 1)] - xp[i], e_prev = xp[i] - xp[hull_step(p, i, -1)];
    Vec3 m1 = e_next.cross(-inward).normalized(), m0 = e_prev.cross(-inward).normalized();
    // And the bisector; a two-corner hull (sliver) tilts about its end instead.
    const Vec3 bisector = (m0 + m1).norm() > 1e-12 ? Vec3((m0 + m1).normalized()) : Vec3(e_next.normalized());
    const Vec3 ms[3] = {m0, m1, bisector};
    for (const Vec3& m : ms)
      for (int k = 0; k < 16; ++k) {
        best = std::max(best, window_for(kTilt[k][0] * inward + kTilt[k][1] * m, xp[i]));
      }
  }
  return best;
}

// The face of a piece nearest to a point (for reporting).
int Checker::face_near(int piece, const Vec3& world) const {
  Vec3 local = T_[piece].R.transpose() * (world - T_[piece].tr);
  Vec2 x = local.head<2>();
  int best = pc_[piece].faces.front();
  double bd = kInf;
  for (int f : pc_[piece].faces) {
    Vec2 c = (net_.corners[f][0] + net_.corners[f][1] + net_.corners[f][2]) / 3;
    double d = (c - x).norm();
    if (d < bd) bd = d, best = f;
  }
  return best;
}

FoldCheckResult Checker::run() {
  FoldCheckResult res;
  const int nb = static_cast<int>(m_.body_root.size());
  res.pieces = nb;
  if (opt_.max_pieces > 0 && nb > opt_.max_pieces) {
    res.out_of_budget = true;
    res.t = 0;
    res.message = "folding not checked: " + std::to_string(nb) + " rigid pieces (the check is limited to " +
                  std::to_string(opt_.max_pieces) + ")";
    return res;
  }
  {
    Vec2 lo(1e300, 1e300), hi(-1e300, -1e300);
    for (auto& c : net_.corners)
      for (auto& p : c) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    scale_ = (hi - lo).norm();
  }
  tol_ = opt_.tolerance * scale_;
  build_pieces();
  T1_.assign(nb, Rigid());
  aa1_.assign(nb, Vec3::Zero());
  au1_.assign(nb, Vec3::UnitX());
  for (int b = 1; b < nb; ++b) {
    const Piece& P = pc_[b];
    T1_[b] = Motion::child_transform(T1_[P.parent], P.hinge_a, P.hinge_u, P.angle);
    aa1_[b] = T1_[P.parent](P.hinge_a);
    au1_[b] = T1_[P.parent].R * P.hinge_u;
  }
  if (nb <= 1) {  // one rigid piece: nothing moves
    res.verified = true;
    return res;
  }
  pair_cap_ = opt_.max_work > 0 && opt_.pairs_per_work > 0 ? opt_.pairs_per_work * static_cast<double>(opt_.max_work) : kInf;
  lever_off_.assign(nb + 1, 0);
  for (int b = 0; b < nb; ++b) lever_off_[b + 1] = lever_off_[b] + pc_[b].depth;
  lever_.assign(lever_off_[nb], 0.0);
  const double begin = std::isfinite(opt_.t_begin) ? std::clamp(opt_.t_begin, 0.0, 1.0) : 0.0;
  int end_steps = 0;
  double stop = 1;
  const double end_window = opt_.end_first > 0 ? opt_.end_first : std::max(opt_.end_proof, 0.0);
  if (end_window > 0 && begin < 1 - end_window) {
    // The end first: most straight-line folds that fail do so there, and the pairs' set-up
    // (classes, end windows) is path-independent, so the pass from begin reuses it.
    FoldCheckResult end = step_path(1 - end_window, true);
    account(end, end.steps);
    if (opt_.end_first > 0 && !end.verified && end.conclusive) {
      end.refuted_at_end = true;
      return end;
    }
    if (opt_.end_first > 0 && !end.verified && opt_.end_first_defers) {
      end.undecided_at_end = true;
      return end;
    }
    end_steps = end.steps;
    std::fill(safe_until_.begin(), safe_until_.end(), 0.0);
    // Proved from the state at 1 - end_window on: the pass from begin only has to reach it.
    if (end.verified) stop = 1 - end_window;
  }
  res = step_path(begin, false, stop);
  res.end_first_steps = end_steps;
  account(res, res.steps + end_steps);
  return res;
}

FoldCheckResult Checker::step_path(double t0, bool screening, double t_stop) {
  FoldCheckResult res;
  const int nb = static_cast<int>(pc_.size());
  res.pieces = nb;
  // Per step, no point moves farther than this (absolute): keeps the candidate boxes local.
  const double max_travel = 0.05 * scale_;
  auto travel = [](double h, double L, double S) { return h * L / (1 - h * S); };
  // conclusive: no check of this net, from whatever start and with whatever steps, can verify it.
  auto fail = [&](double t, int p, int q, const Vec3& at_p, const Vec3& at_q, const std::string& why, bool conclusive) {
    res.t = t;
    res.conclusive = conclusive || faces_cross(p, q);
    res.face_a = face_near(p, at_p), res.face_b = face_near(q, at_q);
    if (res.face_a > res.face_b) std::swap(res.face_a, res.face_b);
    std::ostringstream os;
    os << "faces " << res.face_a << " and " << res.face_b << " " << why << " at t = " << t;
    res.message = os.str();
    res.pairs = static_cast<int>(pairs_.size());
  };

  std::vector<double> abs_lever(nb), abs_theta(nb), box_lo(3 * nb), box_hi(3 * nb), box_r(nb);
  std::vector<std::pair<int, int>> cand;
  // Steps allowed: max_steps, and max_work / pieces when a work budget is given.
  const long long step_cap =
      opt_.max_work > 0 ? std::min<long long>(opt_.max_steps, std::max<long long>(1, opt_.max_work / nb)) : opt_.max_steps;
  bool out_of_pairs = false;  // stopped by the pair bound (FoldCheckOptions::pairs_per_work)
  // Plane advancement, either piece's plane; at t = 0 only when the flat faces do not overlap.
  double t = t0, dt = 1.0 / 16;
  auto advance = [&](int p, int q, PairInfo& pi) {
    if (t == 0) {
      if (pi.flat_apart < 0) pi.flat_apart = !flat_overlap(p, q);
      if (!pi.flat_apart) return 0.0;
    }
    // min(1 - t, max(a, b)): b cannot change it once a reaches 1 - t.
    const double a = plane_advance(p, q, pi);
    return a >= 1 - t ? 1 - t : std::min(1 - t, std::max(a, plane_advance(q, p, pi)));
  };
  int last_p = -1, last_q = -1, same_limit = 0;  // steps in a row limited by the pair last_p, last_q
  // Proved for the rest of the path: skipped from now on (when screening, through its proof's
  // end, so that the slot keeps the pair for the pass from an earlier start).
  auto mark_done = [&](int& id) {
    if (screening)
      safe_until_[id] = kInf;
    else
      id = kDone;
  };
  for (res.steps = 0; res.steps < step_cap; ++res.steps) {
    place(t);
    double max_lever = 0, max_theta = 0;
    for (int b = 0; b < nb; ++b) {
      abs_lever[b] = abs_theta[b] = 0;
      double* lev = &lever_[lever_off_[b]];
      for (int a = b; pc_[a].parent >= 0; a = pc_[a].parent) {
        *lev++ = abs_lever[b] += lever(b, a);
        abs_theta[b] += std::abs(pc_[a].angle);
      }
      max_lever = std::max(max_lever, abs_lever[b]);
      max_theta = std::max(max_theta, abs_theta[b]);
    }
    // The step tried grows by 1.25 over the last one (it was 2): every pair whose proof ends
    // before t + dt is re-examined and the boxes grow with dt, while the steps of large nets are
    // set by their pairs anyway (the same steps, 30% fewer pairs examined on Pikachu's hulls).
    dt = std::min({1.25 * dt, t_stop - t, 0.5 / std::max(max_theta, 1e-300)});
    if (travel(dt, max_lever, max_theta) > max_travel) dt = max_travel / (max_lever + max_travel * max_theta);
    // Candidate pairs: pieces whose boxes, inflated by how far they can travel in dt, meet
    // (closed boxes: touching counts).
    for (int b = 0; b < nb; ++b) {
      double r = travel(dt, abs_lever[b], abs_theta[b]) + tol_;
      box_r[b] = r;
      double* lo = &box_lo[3 * b];
      double* hi = &box_hi[3 * b];
      lo[0] = lo[1] = lo[2] = kInf, hi[0] = hi[1] = hi[2] = -kInf;
      for (auto& v : poly_[b].v)
        for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], v[d] - r), hi[d] = std::max(hi[d], v[d] + r);
    }
    sweep_.pairs(box_lo, box_hi, cand);  // sorted: deterministic
    pair_tests_ += static_cast<long long>(cand.size());
    if (static_cast<double>(pair_tests_) > pair_cap_) {
      out_of_pairs = true;
      break;
    }
    double step = dt;
    int limit_p = -1, limit_q = -1;  // the pair that limits the step (reported at the step limit)
    for (auto [p, q] : cand) {
      if (pc_[p].proved_group >= 0 && pc_[p].proved_group == pc_[q].proved_group) continue;
      int& id = slot(p, q);
      if (id == kDone) continue;
      if (t >= end_from_[id]) {
        mark_done(id);
        continue;
      }
      // Still covered by the proof made when it was last examined, beyond this step: skip.
      if (safe_until_[id] >= t + dt) continue;
      PairInfo& pi = pairs_[id];
      double h;  // how long from t this pair is proved apart
      if (pi.kind == PairKind::cone) {
        Arc A, B;
        cone_arc(p, pi.cone_at, &A), cone_arc(q, pi.cone_at, &B);
        for (Arc* arc : {&A, &B}) {
          const Rigid& T = arc == &A ? T_[p] : T_[q];
          arc->a = T.R * arc->a, arc->b = T.R * arc->b, arc->n = T.R * arc->n;
        }
        double d = arc_distance(A, B) - 1e-10;
        const double S = pi.Sp + pi.Sq;
        double hc = d / S;  // directions turn at most S rad per unit t relative to each other
        if (d > 0 && hc < dt && opt_.second_order) {
          // Second order: the relative turn is the exact angular velocity W now, plus at most
          // the integral of |W'| <= S^2 / 2 (each axis turns with the hinges before it).
          const double W = (om_[q] - om_[p]).norm();
          hc = std::max(hc, 2 * d / (W + std::sqrt(W * W + S * S * d)));
        }
        double hp = hc < dt ? advance(p, q, pi) : 0;
        if (d <= 0 && hp > 0) {
          h = hp;
        } else if (d <= 0) {
          Vec3 at = T_[p](lift(pi.cone_at));
          fail(t, p, q, at, at, t == 0 ? "touch beside their common corner in the flat net" : "cross at their common corner", false);
          return res;
        } else {
          h = std::max(hc, hp);
        }
      } else {
        // up_p is the start of p's way to the root: its levers are this step's first ones.
        const std::size_t kp = pi.up_p.size(), kq = pi.up_q.size();
        const double L = (kp ? lever_[lever_off_[p] + kp - 1] : 0) + (kq ? lever_[lever_off_[q] + kq - 1] : 0);
        double S = std::max(pi.Sp, pi.Sq);
        // The gap between the pieces' boxes (their travel boxes shrunk back) is a lower bound on
        // their distance. When it already proves the pair over the whole step tried, the exact
        // distance is skipped; the shorter proof only brings the pair back sooner. It is never
        // used to cut the step: then the steps collapse (8x slower on Squirtle).
        {
          double g2 = 0;
          for (int k = 0; k < 3; ++k) {
            const double gap = std::max(box_lo[3 * q + k] + box_r[q] - (box_hi[3 * p + k] - box_r[p]),
                                        box_lo[3 * p + k] + box_r[p] - (box_hi[3 * q + k] - box_r[q]));
            if (gap > 0) g2 += gap * gap;
          }
          const double lb = std::sqrt(g2) - tol_;
          const double hl = lb > 0 ? lb / (L + lb * S) : 0;  // travel(hl, L, S) = lb
          if (hl >= dt) {
            if (t + hl >= end_from_[id]) mark_done(id);
            else safe_until_[id] = t + hl;
            continue;
          }
        }
        double d = polygon_distance(poly_[p], poly_[q], tol_) - tol_;
        double hd = d > 0 ? d / (L + d * S) : 0;  // travel(h, L, S) = d
        if (d > 0 && opt_.second_order) hd = std::max(hd, taylor_step(p, q, d, L, pi));
        double hp = hd < dt ? advance(p, q, pi) : 0;
        if (d <= 0 && hp > 0) {
          h = hp;
        } else if (d <= 0) {
          fail(t, p, q, centre_[p], centre_[q], t == 0 ? "touch in the flat net" : (t >= 1 ? "touch in the folded shell" : "collide"),
               unprovable_at_end(p, q, pi));
          if (t >= 1) res.message += " (no separating plane proves the approach)";
          return res;
        } else {
          h = std::max(hd, hp);
        }
      }
      if (t + h >= end_from_[id]) {
        mark_done(id);
        continue;
      }
      // Such a pair is reported once it crawls: it has limited the last 100 steps, each below
      // 1% of the way left. No verified outcome depends on when; a pair approaching a real
      // contact gets there in a few steps and is reported at it, as before.
      if (opt_.second_order && same_limit >= 100 && p == last_p && q == last_q && h < 1e-2 * (1 - t) &&
          unprovable_at_end(p, q, pi)) {
        fail(t, p, q, centre_[p], centre_[q], "touch in the folded shell where no end window proves the approach free; stopped", true);
        return res;
      }
      if (h < opt_.min_step) {
        // The pair is (numerically) in contact, or approaches a contact of the folded shell that
        // no separating plane proves free.
        std::ostringstream why;
        why << "come into contact (step " << h << " below " << opt_.min_step << ")";
        if (pi.shares && t > 0.5) why << "; they touch in the folded shell and no separating plane proves the approach free";
        fail(t, p, q, centre_[p], centre_[q], why.str(), unprovable_at_end(p, q, pi));
        return res;
      }
      safe_until_[id] = t + h;
      if (h < step) step = h, limit_p = p, limit_q = q;
    }
    dt = step;
    same_limit = limit_p == last_p && limit_q == last_q ? same_limit + 1 : 0;
    last_p = limit_p, last_q = limit_q;
    t += dt;
    if (t >= t_stop) {
      res.verified = true;
      res.t = 1;
      ++res.steps;
      res.pairs = static_cast<int>(pairs_.size());
      return res;
    }
  }
  res.t = t;
  res.out_of_budget = true;
  res.message = (out_of_pairs ? "pair limit reached at t = " : "step limit reached at t = ") + std::to_string(t);
  if (last_p >= 0) {
    res.face_a = pc_[last_p].faces.front(), res.face_b = pc_[last_q].faces.front();
    res.message += " (steps limited by faces " + std::to_string(res.face_a) + " and " + std::to_string(res.face_b) + ")";
  }
  res.pairs = static_cast<int>(pairs_.size());
  return res;
}

}  // namespace

std::vector<std::array<Eigen::Vector3d, 3>> folded_faces(const Net& net, double t) {
  Motion m(net);
  auto T = m.transforms(t);
  std::vector<std::array<Eigen::Vector3d, 3>> out(m.nf);
  for (int f = 0; f < m.nf; ++f)
    for (int k = 0; k < 3; ++k) out[f][k] = T[f](lift(net.corners[f][k]));
  return out;
}

int rigid_pieces(const Net& net) { return static_cast<int>(Motion(net).body_root.size()); }

std::optional<FoldCheckResult> find_sampled_collision(const Net& net, int samples, double margin, long long* pair_tests) {
  long long pairs_dummy = 0;
  long long& pairs = pair_tests ? *pair_tests : pairs_dummy;
  pairs = 0;
  Motion m(net);
  if (m.nf == 0 || samples < 2) return std::nullopt;
  Eigen::AlignedBox2d box;
  for (const auto& c : net.corners)
    for (const auto& p : c) box.extend(p);
  const double mg = margin * box.diagonal().norm();
  std::vector<std::array<Vec3, 3>> x(m.nf);
  std::vector<double> lo(3 * m.nf), hi(3 * m.nf);
  std::vector<std::pair<int, int>> cand;
  unfold_detail::BoxSweep sweep;
  FoldCheckResult res;
  res.pieces = static_cast<int>(m.body_root.size());
  // t = 1 - (k / samples)^2, latest first: straight-line folds mostly collide late, where the
  // pieces close up, often only for a short while before the end (Pikachu's largest DC-shell
  // from t = 0.953 to 0.97), so the states are densest there.
  for (int k = 1; k < samples; ++k) {
    const double s = static_cast<double>(k) / samples, t = 1 - s * s;
    const auto T = m.transforms(t);
    ++res.steps;
    for (int f = 0; f < m.nf; ++f)
      for (int d = 0; d < 3; ++d) {
        x[f][d] = T[f](lift(net.corners[f][d]));
        const double* v = x[f][d].data();
        for (int i = 0; i < 3; ++i) {
          double& l = lo[3 * f + i];
          double& h = hi[3 * f + i];
          l = d == 0 ? v[i] : std::min(l, v[i]);
          h = d == 0 ? v[i] : std::max(h, v[i]);
        }
      }
    sweep.pairs(lo, hi, cand);
    pairs += static_cast<long long>(cand.size());
    for (const auto& [f, g] : cand) {
      if (m.body[f] == m.body[g]) continue;
      if (!edge_pierces(x[f], x[g], mg) && !edge_pierces(x[g], x[f], mg)) continue;
      res.t = t, res.face_a = f, res.face_b = g, res.pairs = static_cast<int>(cand.size());
      res.message = "faces " + std::to_string(f) + " and " + std::to_string(g) + " intersect at t = " + std::to_string(t) +
                    " (a sampled state: the first contact is at or before it)";
      return res;
    }
  }
  return std::nullopt;
}

FoldCheckResult check_folding(const Net& net, const FoldCheckOptions& options) {
  Checker c(net, options);
  return c.run();
}

}  // namespace dcshell
