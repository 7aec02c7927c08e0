// The only translation unit that instantiates CGAL's QP solver (see qp3.h): the exact fallback.
#include "remesh/qp3.h"

#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>

#include <algorithm>
#include <type_traits>
#include <utility>

namespace dcshell::remesh_detail {
namespace {

using Program = CGAL::Quadratic_program<double>;
using Solution = CGAL::Quadratic_program_solution<CGAL::Gmpzf>;

// Free variables (no bounds), one SMALLER row per constraint.
Program make_program(const std::vector<Row>& rows) {
  Program p(CGAL::SMALLER, false, 0, false, 0);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (int j = 0; j < 3; ++j)
      if (rows[i].a[j] != 0.0) p.set_a(j, static_cast<int>(i), rows[i].a[j]);
    p.set_b(static_cast<int>(i), rows[i].b);
  }
  return p;
}

std::optional<Eigen::Vector3d> extract(const Solution& s, bool* infeasible = nullptr) {
  if (infeasible) *infeasible = s.is_infeasible();
  if (!s.is_optimal()) return std::nullopt;
  Eigen::Vector3d y;
  int j = 0;
  for (auto it = s.variable_values_begin(); it != s.variable_values_end() && j < 3; ++it, ++j)
    y[j] = CGAL::to_double(*it);
  return y;
}

Program make_lp(const Eigen::Vector3d& c, const std::vector<Row>& rows) {
  Program p = make_program(rows);
  for (int j = 0; j < 3; ++j) p.set_c(j, c[j]);
  return p;
}

Program make_qp(const Eigen::Vector3d& target, const std::vector<Row>& rows) {
  // |y - t|^2 = y·y - 2 t·y + t·t; CGAL minimises y'Dy + c'y + c0 and set_d sets 2D.
  Program p = make_program(rows);
  for (int j = 0; j < 3; ++j) {
    p.set_d(j, j, 2.0);
    p.set_c(j, -2.0 * target[j]);
  }
  p.set_c0(target.squaredNorm());
  return p;
}

// Constraint generation (qp3.h). A row joins when the rounded optimum violates it at all (no
// tolerance): a near-duplicate of a row already in, off by 1e-17, then joins too, so the answer
// is the one the whole program gives.
template <class Solve>
std::optional<Eigen::Vector3d> by_generation(const std::vector<Row>& rows, const std::vector<std::size_t>& start,
                                             Solve solve) {
  constexpr int kRounds = 8;
  std::vector<char> in(rows.size(), 0);
  std::vector<std::size_t> idx;
  for (std::size_t i : start)
    if (i < rows.size() && !in[i]) in[i] = 1, idx.push_back(i);
  for (int round = 0; round < kRounds && idx.size() < rows.size(); ++round) {
    std::sort(idx.begin(), idx.end());  // the program's own row order
    std::vector<Row> sub;
    for (std::size_t i : idx) sub.push_back(rows[i]);
    bool infeasible = false;
    const std::optional<Eigen::Vector3d> y = solve(sub, &infeasible);
    if (!y) {
      if (infeasible) return std::nullopt;
      break;  // unbounded on these rows (an LP): all of them decide
    }
    bool added = false;
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (!in[i] && rows[i].a.dot(*y) > rows[i].b) in[i] = 1, idx.push_back(i), added = true;
    if (!added) return y;
  }
  return solve(rows, nullptr);
}

}  // namespace

std::optional<Eigen::Vector3d> solve_lp3_exact(const Eigen::Vector3d& c, const std::vector<Row>& rows,
                                               const std::vector<std::size_t>& start) {
  return by_generation(rows, start, [&](const std::vector<Row>& sub, bool* infeasible) {
    const Program p = make_lp(c, sub);  // alive while the solution is read
    return extract(CGAL::solve_linear_program(p, CGAL::Gmpzf()), infeasible);
  });
}

std::optional<Eigen::Vector3d> solve_qp3_exact(const Eigen::Vector3d& target, const std::vector<Row>& rows,
                                               const std::vector<std::size_t>& start) {
  return by_generation(rows, start, [&](const std::vector<Row>& sub, bool* infeasible) {
    const Program p = make_qp(target, sub);
    return extract(CGAL::solve_quadratic_program(p, CGAL::Gmpzf()), infeasible);
  });
}

std::optional<Eigen::Vector3d> solve_lp3_exact(const Eigen::Vector3d& c, const std::vector<Row>& rows) {
  const Program p = make_lp(c, rows);
  return extract(CGAL::solve_linear_program(p, CGAL::Gmpzf()));
}

std::optional<Eigen::Vector3d> solve_qp3_exact(const Eigen::Vector3d& target, const std::vector<Row>& rows) {
  const Program p = make_qp(target, rows);
  return extract(CGAL::solve_quadratic_program(p, CGAL::Gmpzf()));
}

static std::optional<Epeck::Plane_3> separating_plane_within(const std::vector<Point3>& below,
                                                              const std::vector<Point3>& above,
                                                              const Eigen::Vector3d& n0, double bound);

std::optional<Epeck::Plane_3> separating_plane_exact(const std::vector<Point3>& below, const std::vector<Point3>& above,
                                                     const Eigen::Vector3d& n0) {
  // |n| = 1/|n0| along n0. The bound keeps the LP bounded (a gap grows without end along normals
  // that tilt away from n0); the wider one admits separating normals up to ~89.9 degrees from n0
  // (two long shells side by side, whose centres differ mostly along their length).
  for (const double tilt : {4.0, 4096.0})
    if (auto plane = separating_plane_within(below, above, n0, tilt / n0.norm())) return plane;
  return std::nullopt;
}

static std::optional<Epeck::Plane_3> separating_plane_within(const std::vector<Point3>& below,
                                                              const std::vector<Point3>& above,
                                                              const Eigen::Vector3d& n0, double bound) {
  // Variables n (0..2), d_below (3), d_above (4): n·x - d_below <= 0 below, d_above - n·x <= 0
  // above, n·n0 = 1, |n_j| <= bound, minimise d_below - d_above.
  Program p(CGAL::SMALLER, false, 0, false, 0);
  for (int j = 0; j < 3; ++j) {
    p.set_l(j, true, -bound);
    p.set_u(j, true, bound);
  }
  int row = 0;
  for (const Point3& x : below) {
    for (int j = 0; j < 3; ++j) p.set_a(j, row, x[j]);
    p.set_a(3, row, -1.0);
    ++row;
  }
  for (const Point3& x : above) {
    for (int j = 0; j < 3; ++j) p.set_a(j, row, -x[j]);
    p.set_a(4, row, 1.0);
    ++row;
  }
  for (int j = 0; j < 3; ++j) p.set_a(j, row, n0[j]);
  p.set_r(row, CGAL::EQUAL);
  p.set_b(row, 1.0);
  p.set_c(3, 1.0);
  p.set_c(4, -1.0);
  const Solution s = CGAL::solve_linear_program(p, CGAL::Gmpzf());
  if (!s.is_optimal()) return std::nullopt;
  // Exact values: Gmpzf quotients to the rationals of Epeck.
  using ET = std::decay_t<decltype(std::declval<const Epeck::FT&>().exact())>;
  auto rational = [](const CGAL::Gmpzf& z) {
    mpq_t q;
    mpq_init(q);
    mpq_set_z(q, z.man());
    if (z.exp() >= 0)
      mpq_mul_2exp(q, q, static_cast<mp_bitcnt_t>(z.exp()));
    else
      mpq_div_2exp(q, q, static_cast<mp_bitcnt_t>(-z.exp()));
    ET r(q);
    mpq_clear(q);
    return r;
  };
  std::vector<ET> v;
  for (auto it = s.variable_values_begin(); it != s.variable_values_end(); ++it)
    v.push_back(rational(it->numerator()) / rational(it->denominator()));
  if (v.size() != 5 || v[3] > v[4]) return std::nullopt;  // the sets overlap
  using FT = Epeck::FT;
  // n·x - (d_below + d_above) / 2 = 0.
  return Epeck::Plane_3(FT(v[0]), FT(v[1]), FT(v[2]), FT(-(v[3] + v[4]) / 2));
}

}  // namespace dcshell::remesh_detail
