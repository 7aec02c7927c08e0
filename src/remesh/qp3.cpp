// The only translation unit that instantiates CGAL's QP solver (see qp3.h): the exact fallback.
#include "remesh/qp3.h"

#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>

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

std::optional<Eigen::Vector3d> extract(const Solution& s) {
  if (!s.is_optimal()) return std::nullopt;
  Eigen::Vector3d y;
  int j = 0;
  for (auto it = s.variable_values_begin(); it != s.variable_values_end() && j < 3; ++it, ++j)
    y[j] = CGAL::to_double(*it);
  return y;
}

}  // namespace

std::optional<Eigen::Vector3d> solve_lp3_exact(const Eigen::Vector3d& c, const std::vector<Row>& rows) {
  Program p = make_program(rows);
  for (int j = 0; j < 3; ++j) p.set_c(j, c[j]);
  return extract(CGAL::solve_linear_program(p, CGAL::Gmpzf()));
}

std::optional<Eigen::Vector3d> solve_qp3_exact(const Eigen::Vector3d& target, const std::vector<Row>& rows) {
  // |y - t|^2 = y·y - 2 t·y + t·t; CGAL minimises y'Dy + c'y + c0 and set_d sets 2D.
  Program p = make_program(rows);
  for (int j = 0; j < 3; ++j) {
    p.set_d(j, j, 2.0);
    p.set_c(j, -2.0 * target[j]);
  }
  p.set_c0(target.squaredNorm());
  return extract(CGAL::solve_quadratic_program(p, CGAL::Gmpzf()));
}

}  // namespace dcshell::remesh_detail
