// Private to the remesh module: the small LPs and QPs of the progressive hull and of the
// constrained smoothing, in three variables, and the separating-plane LP between two neighbours.
// CGAL's QP solver is instantiated only in qp3.cpp (template-heavy, so every exact program of the
// module is solved there); the floating-point solver is in solve3.cpp.
#pragma once
#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

#include "dcshell/kernel.h"

namespace dcshell::remesh_detail {

/// The halfspace a·y <= b.
struct Row {
  Eigen::Vector3d a;
  double b;
};

/// argmin c·y subject to every row; nullopt when infeasible or unbounded. Rows are expected with
/// unit normals and O(1) coefficients (a local frame). Solved in floating point by enumerating
/// the candidate active sets (three variables: at most three active rows), the answer accepted
/// only with its optimality certificate (feasible within 1e-12, KKT multipliers >= 0); anything
/// else goes to the exact solver below. Either way the caller re-checks the rounded point
/// exactly against what it actually needs, so the floating-point path costs no guarantee.
std::optional<Eigen::Vector3d> solve_lp3(const Eigen::Vector3d& c, const std::vector<Row>& rows);

/// argmin |y - target|^2 subject to every row; nullopt when infeasible. Same method and note.
std::optional<Eigen::Vector3d> solve_qp3(const Eigen::Vector3d& target, const std::vector<Row>& rows);

/// The same programs solved exactly (CGAL::Gmpzf, about 1 ms each) on the double coefficients
/// and rounded to doubles: the fallback of the two above.
std::optional<Eigen::Vector3d> solve_lp3_exact(const Eigen::Vector3d& c, const std::vector<Row>& rows);
std::optional<Eigen::Vector3d> solve_qp3_exact(const Eigen::Vector3d& target, const std::vector<Row>& rows);

/// The same, by constraint generation from the rows `start` (indices): the exact optimum of those
/// rows alone, then of those plus every row it violates, and so on (at most 8 rounds, then all
/// rows). An optimum of some of the rows that satisfies all of them is the program's own (the
/// same answer), and some rows with no common point make it infeasible. The exact solver's cost
/// grows fast with the rows, while few ever bind: a shell among hundreds of neighbours has a
/// constraint plane for each (400 rows: 2.9 ms a program solved whole, 0.5 ms by generation).
/// The fallback of solve_lp3 / solve_qp3 starts from the rows their floating-point search took in.
std::optional<Eigen::Vector3d> solve_lp3_exact(const Eigen::Vector3d& c, const std::vector<Row>& rows,
                                               const std::vector<std::size_t>& start);
std::optional<Eigen::Vector3d> solve_qp3_exact(const Eigen::Vector3d& target, const std::vector<Row>& rows,
                                               const std::vector<std::size_t>& start);

/// An exact plane with every point of `below` on or below it and every point of `above` on or
/// above it, if there is one: the LP "maximise the gap" over normals n with n·n0 = 1 (|n| bounded,
/// first to 4/|n0|, then to 4096/|n0| for normals nearly perpendicular to n0), solved exactly
/// (Gmpzf); the plane lies half-way across the gap. nullopt when the sets overlap.
std::optional<Epeck::Plane_3> separating_plane_exact(const std::vector<Point3>& below, const std::vector<Point3>& above,
                                                     const Eigen::Vector3d& n0);

/// While alive, caps how many programs solve_lp3 / solve_qp3 hand to the exact solver on this
/// thread; past the cap an undecided program is answered "no solution", which only drops that
/// candidate move (every move is re-checked exactly anyway). Deterministic: the caller's own
/// sequence of programs decides which ones get the exact solver. Nested budgets restore the outer one.
class ExactFallbackBudget {
 public:
  explicit ExactFallbackBudget(std::size_t solves);
  ~ExactFallbackBudget();
  ExactFallbackBudget(const ExactFallbackBudget&) = delete;
  ExactFallbackBudget& operator=(const ExactFallbackBudget&) = delete;

 private:
  std::size_t outer_;
};

/// How many programs were solved, and how many took the exact fallback (process-wide; for benchmarks).
std::size_t all_solves();
std::size_t exact_solves();

}  // namespace dcshell::remesh_detail
