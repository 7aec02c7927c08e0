// Floating-point solver of the three-variable LPs and QPs (see qp3.h). In three variables an
// optimum is fixed by at most three active rows; a candidate is accepted only with its own
// optimality certificate (feasible, KKT multipliers >= 0), and the exact solver is kept for what
// the certificate cannot settle (unbounded, degenerate, ill-conditioned).
#include <Eigen/Geometry>

#include <array>
#include <atomic>
#include <cmath>
#include <limits>

#include "remesh/qp3.h"

namespace dcshell::remesh_detail {
namespace {

// Tolerances in the rows' units (unit normals, O(1) offsets). Callers keep margins >= 1e-9 off
// every plane that matters and re-check the rounded answer exactly, so 1e-12 costs nothing.
constexpr double kFeasTol = 1e-12;
constexpr double kMulTol = 1e-12;
// Triples of unit normals spanning less volume than this give vertices too ill-conditioned to
// trust in doubles; pairs likewise (Gram determinant).
constexpr double kDetTol = 1e-9;
// Local units: a solution this far from the frame's origin (a thousand times the size of the
// star) is of no use to any caller; the working sets start with this box, so they are bounded.
constexpr double kBox = 1e3;

std::vector<Row> box_rows() {
  std::vector<Row> box;
  for (int k = 0; k < 3; ++k)
    for (double s : {-1.0, 1.0}) box.push_back({s * Eigen::Vector3d::Unit(k), kBox});
  return box;
}

std::atomic<std::size_t> exact_count{0}, all_count{0};

// Row violation relative to the magnitudes involved (rounding in a·y grows with |y|).
double violation(const Row& r, const Eigen::Vector3d& y) {
  return (r.a.dot(y) - r.b) / (1 + std::abs(r.b) + y.lpNorm<Eigen::Infinity>());
}

bool feasible(const std::vector<Row>& rows, const Eigen::Vector3d& y) {
  for (const Row& r : rows)
    if (violation(r, y) > kFeasTol) return false;
  return true;
}

// The vertex where rows i, j, k are active and the dual basis of their normals (d_m·a_n = δ_mn),
// which gives the multipliers of any vector expressed in those normals.
struct Vertex {
  bool ok = false;
  Eigen::Vector3d y, dual[3];
};

Vertex vertex(const Row& ri, const Row& rj, const Row& rk) {
  Vertex v;
  const Eigen::Vector3d jk = rj.a.cross(rk.a), ki = rk.a.cross(ri.a), ij = ri.a.cross(rj.a);
  const double det = ri.a.dot(jk);
  if (!(std::abs(det) > kDetTol)) return v;
  v.ok = true;
  v.dual[0] = jk / det;
  v.dual[1] = ki / det;
  v.dual[2] = ij / det;
  v.y = ri.b * v.dual[0] + rj.b * v.dual[1] + rk.b * v.dual[2];
  return v;
}

// After no certified candidate was found: true when the rows certainly have no common point
// (their normals span space, so a non-empty intersection would have a vertex, and none is
// feasible); false when the exact solver must decide.
bool certainly_infeasible(const std::vector<Row>& rows) {
  const std::size_t n = rows.size();
  bool spans = false;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        const Vertex v = vertex(rows[i], rows[j], rows[k]);
        if (!v.ok) continue;
        spans = true;
        if (feasible(rows, v.y)) return false;
      }
  return spans;
}

// Most violated row at y (index, violation), or (n, <= tol) when y is feasible.
std::pair<std::size_t, double> most_violated(const std::vector<Row>& rows, const Eigen::Vector3d& y) {
  std::size_t p = rows.size();
  double worst = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double v = violation(rows[i], y);
    if (v > kFeasTol && v > worst) worst = v, p = i;
  }
  return {p, worst};
}

// Both programs are solved by constraint generation: optimise over a working set W of rows, add
// the row the optimum violates most, repeat. When the optimum of W violates row p, the optimum of
// W + p lies on p's plane, so only active sets holding p are searched first (Seidel's argument).
// The QP keeps every row that ever bound (each step costs |W|^2 candidate checks). The LP keeps
// only the three rows of its last certificate: their vertex is optimal for them alone (KKT), and
// three independent normals keep W pointed, so the vertex arguments below still hold; the
// objective never decreases, so dropping rows only costs steps (bounded: past the cap the exact
// solver decides), and a step costs a constant instead of |W|^3.
// `used` collects the indices of the rows W took in, in order (the Farkas test below, and the
// exact fallback starts from them).
template <class Certify>
std::optional<Eigen::Vector3d> generate(const std::vector<Row>& rows, std::vector<Row> w, Eigen::Vector3d y,
                                        bool with_singles_and_pairs, const Eigen::Vector3d& t, Certify certified,
                                        bool& undecided, std::vector<std::size_t>& used) {
  undecided = false;
  const bool prune = !with_singles_and_pairs;
  const std::vector<Row> start = w;  // with rows[used]: every row W ever held
  const std::size_t max_iter = prune ? 4 * rows.size() + 16 : rows.size();
  for (std::size_t iter = 0; iter <= max_iter; ++iter) {
    const auto [p, viol] = most_violated(rows, y);
    if (p == rows.size()) return y;
    // Farkas with a box: rows i and p with nearly opposite normals leave no point within
    // |y| <= kBox when b_i + b_p + kBox |a_i + a_p|_1 < 0 (their sum is <= that bound there).
    // Catches the thin slabs of nearly flat neighbourhoods, whose vertices are too
    // ill-conditioned to enumerate; a solution beyond kBox would be useless to the caller.
    auto opposite = [&](const Row& r) { return r.b + rows[p].b + kBox * (r.a + rows[p].a).lpNorm<1>() < -kFeasTol; };
    for (const Row& r : start)
      if (opposite(r)) return std::nullopt;
    for (std::size_t i : used)
      if (opposite(rows[i])) return std::nullopt;
    w.push_back(rows[p]);
    used.push_back(p);
    const std::size_t m = w.size(), q = m - 1;
    bool found = false;
    if (with_singles_and_pairs) {  // QP: projections onto p's plane and onto its lines with others
      const Eigen::Vector3d& ap = w[q].a;
      const double app = ap.squaredNorm(), vp = ap.dot(t) - w[q].b;
      if (app > 0 && vp > 0) {
        const Eigen::Vector3d c = t - (vp / app) * ap;
        if (feasible(w, c)) y = c, found = true;
      }
      for (std::size_t i = 0; i < q && !found; ++i) {
        const Eigen::Vector3d& ai = w[i].a;
        const double gii = ai.squaredNorm(), gip = ai.dot(ap), det = gii * app - gip * gip;
        if (!(det > kDetTol * kDetTol)) continue;
        const double ri = ai.dot(t) - w[i].b, rp = vp;
        const double li = (app * ri - gip * rp) / det, lp = (gii * rp - gip * ri) / det;
        if (li < -kMulTol || lp < -kMulTol) continue;
        const Eigen::Vector3d c = t - li * ai - lp * ap;
        if (feasible(w, c)) y = c, found = true;
      }
    }
    // Also decides infeasibility: were W + p feasible, the part of p's plane inside W (bounded by
    // the box) would be a non-empty polygon, one of whose vertices is such a triple.
    bool any_feasible = false, skipped = false;
    std::array<std::size_t, 3> active{};  // the certificate's rows (set with `found`)
    for (std::size_t i = 0; i < q && !found; ++i)
      for (std::size_t j = i + 1; j < q && !found; ++j) {
        const Vertex v = vertex(w[i], w[j], w[q]);
        if (!v.ok) {  // parallel i and j have parallel lines on p's plane: no vertex lost
          skipped = skipped || w[i].a.cross(w[j].a).norm() > kDetTol;
          continue;
        }
        if (!feasible(w, v.y)) continue;
        any_feasible = true;
        if (certified(v)) y = v.y, found = true, active = {i, j, q};
      }
    if (!found && !any_feasible && !skipped) return std::nullopt;
    // Degenerate optimum certified without p: any active set of W + p.
    for (std::size_t i = 0; i < m && !found; ++i)
      for (std::size_t j = i + 1; j < m && !found; ++j)
        for (std::size_t k = j + 1; k < m && !found; ++k) {
          const Vertex v = vertex(w[i], w[j], w[k]);
          if (v.ok && certified(v) && feasible(w, v.y)) y = v.y, found = true, active = {i, j, k};
        }
    if (!found) {
      if (!certainly_infeasible(w)) undecided = true;
      return std::nullopt;
    }
    if (prune) w = {w[active[0]], w[active[1]], w[active[2]]};
  }
  undecided = true;
  return std::nullopt;
}

// Exact fallbacks left on this thread (see ExactFallbackBudget); unlimited outside a budget.
thread_local std::size_t exact_left = std::numeric_limits<std::size_t>::max();

bool take_exact() {
  if (exact_left == 0) return false;
  if (exact_left != std::numeric_limits<std::size_t>::max()) --exact_left;
  ++exact_count;
  return true;
}

}  // namespace

ExactFallbackBudget::ExactFallbackBudget(std::size_t solves) : outer_(exact_left) { exact_left = std::min(solves, outer_); }
ExactFallbackBudget::~ExactFallbackBudget() { exact_left = outer_; }

std::size_t exact_solves() { return exact_count.load(); }
std::size_t all_solves() { return all_count.load(); }

std::optional<Eigen::Vector3d> solve_lp3(const Eigen::Vector3d& c, const std::vector<Row>& rows) {
  // An optimum on the box means the program is unbounded (or its optimum is absurdly far):
  // the exact solver decides.
  ++all_count;
  constexpr double R = kBox;
  Eigen::Vector3d y;
  for (int k = 0; k < 3; ++k) y[k] = c[k] > 0 ? -R : R;  // the box corner minimising c
  // A vertex is optimal for its rows when -c lies in the cone of their normals (KKT).
  auto certified = [&](const Vertex& v) {
    return -c.dot(v.dual[0]) >= -kMulTol && -c.dot(v.dual[1]) >= -kMulTol && -c.dot(v.dual[2]) >= -kMulTol;
  };
  bool undecided = false;
  std::vector<std::size_t> used;
  auto r = generate(rows, box_rows(), y, false, c, certified, undecided, used);
  if (r && r->lpNorm<Eigen::Infinity>() < 0.5 * R) return r;
  if (!r && !undecided) return std::nullopt;
  if (!take_exact()) return std::nullopt;
  return solve_lp3_exact(c, rows, used);
}

std::optional<Eigen::Vector3d> solve_qp3(const Eigen::Vector3d& t, const std::vector<Row>& rows) {
  ++all_count;
  // KKT for the projection of t: t - y = sum of lambda_s a_s over the active rows, lambda >= 0.
  auto certified = [&](const Vertex& v) {
    const Eigen::Vector3d d = t - v.y;
    return d.dot(v.dual[0]) >= -kMulTol && d.dot(v.dual[1]) >= -kMulTol && d.dot(v.dual[2]) >= -kMulTol;
  };
  bool undecided = false;
  std::vector<std::size_t> used;
  std::optional<Eigen::Vector3d> r;
  if (t.lpNorm<Eigen::Infinity>() < 0.5 * kBox) {
    r = generate(rows, box_rows(), t, true, t, certified, undecided, used);
    if (r && r->lpNorm<Eigen::Infinity>() < 0.5 * kBox) return r;
    if (!r && !undecided) return std::nullopt;
  }
  if (!take_exact()) return std::nullopt;
  return solve_qp3_exact(t, rows, used);
}

}  // namespace dcshell::remesh_detail
