// Private to the remesh module: the small LPs and QPs of the progressive hull and of the
// constrained smoothing, in three variables. CGAL's QP solver is instantiated only in qp3.cpp
// (template-heavy); this header is plain data.
#pragma once
#include <Eigen/Core>
#include <optional>
#include <vector>

namespace dcshell::remesh_detail {

/// The halfspace a·y <= b.
struct Row {
  Eigen::Vector3d a;
  double b;
};

/// argmin c·y subject to every row; nullopt when infeasible or unbounded.
/// Solved exactly (CGAL::Gmpzf) on the double coefficients and rounded to doubles: the caller
/// re-checks the rounded point exactly against what it actually needs.
std::optional<Eigen::Vector3d> solve_lp3(const Eigen::Vector3d& c, const std::vector<Row>& rows);

/// argmin |y - target|^2 subject to every row; nullopt when infeasible. Same exactness note.
std::optional<Eigen::Vector3d> solve_qp3(const Eigen::Vector3d& target, const std::vector<Row>& rows);

}  // namespace dcshell::remesh_detail
