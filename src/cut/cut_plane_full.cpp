// Joint optimisation of the normal and the offset: multi-start scan + BFGS on the sphere.
#include "dcshell/cut_plane_full.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>

#include "cut/cut_objective.h"
#include "dcshell/cut_plane_exact.h"
#include "dcshell/cut_plane_lsf.h"

namespace dcshell {

namespace {

using Best = CutObjective::Best;

// Deterministic, near-uniform spread of n directions (Fibonacci sphere).
std::vector<Eigen::Vector3d> fibonacci_sphere(std::size_t n) {
  std::vector<Eigen::Vector3d> out;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (std::size_t i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * double(i) + 1.0) / double(n), r = std::sqrt(std::max(0.0, 1 - z * z));
    out.emplace_back(r * std::cos(golden * double(i)), r * std::sin(golden * double(i)), z);
  }
  return out;
}

// BFGS on the chart n(u) = normalize(n0 + u0 e1 + u1 e2) of the function min_d g(n, d).
// The function is only piecewise smooth (events, active range ends), so steps are bounded
// and a failed line search falls back to steepest descent once before stopping.
Best polish(CutObjective& obj, const Best& start) {
  const Eigen::Vector3d n0 = start.plane.normal;
  const Eigen::Vector3d e1 = n0.unitOrthogonal(), e2 = n0.cross(e1);
  auto eval = [&](const Eigen::Vector2d& u) { return obj.best_offset(n0 + u[0] * e1 + u[1] * e2); };
  auto grad = [&](const Eigen::Vector2d& u, const Best& b) {
    const Eigen::Vector3d m = n0 + u[0] * e1 + u[1] * e2;
    const Eigen::Vector3d n = b.plane.normal, G = obj.normal_gradient(b);
    const Eigen::Vector3d Gt = (G - n * n.dot(G)) / m.norm();  // chain rule through normalize
    return Eigen::Vector2d(Gt.dot(e1), Gt.dot(e2));
  };
  constexpr double kMaxStep = 0.2;  // radians, roughly
  Eigen::Vector2d u = Eigen::Vector2d::Zero();
  Best cur = start;
  Eigen::Vector2d g = grad(u, cur);
  Eigen::Matrix2d H = Eigen::Matrix2d::Identity();
  bool scaled = false, fresh = true;
  for (int it = 0; it < 20 && g.norm() > 0; ++it) {
    Eigen::Vector2d p = -H * g;
    if (p.dot(g) >= 0) {
      H.setIdentity();
      scaled = false;
      p = -g;
    }
    if (!scaled) p *= 0.05 / p.norm();  // first step: a few degrees
    if (p.norm() > kMaxStep) p *= kMaxStep / p.norm();
    double t = 1.0;
    Best trial;
    bool ok = false;
    for (int k = 0; k < 8; ++k, t *= 0.5) {
      trial = eval(u + t * p);
      if (trial.value <= cur.value + 1e-4 * t * g.dot(p) && trial.value < cur.value) {
        ok = true;
        break;
      }
    }
    if (!ok) {
      if (fresh) break;  // steepest descent failed too: at a (possibly non-smooth) minimum
      H.setIdentity();
      scaled = false;
      fresh = true;
      continue;
    }
    const Eigen::Vector2d s = t * p, un = u + s;
    const Eigen::Vector2d gn = grad(un, trial);
    const Eigen::Vector2d yv = gn - g;
    const double sy = s.dot(yv);
    if (sy > 1e-12 * s.norm() * yv.norm()) {
      if (!scaled) {
        H = Eigen::Matrix2d::Identity() * (sy / yv.squaredNorm());
        scaled = true;
      }
      const double rho = 1.0 / sy;
      const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
      H = (I - rho * s * yv.transpose()) * H * (I - rho * yv * s.transpose()) + rho * s * s.transpose();
    }
    // Gains below 1e-8 of the objective are far below what the sweeps resolve (2e-6 of the
    // volume) and would only cost more slice-profile builds.
    const bool tiny = s.norm() < 1e-9 || (cur.value - trial.value) <= 1e-8 * std::fabs(cur.value);
    u = un;
    g = gn;
    cur = trial;
    fresh = false;
    if (tiny) break;
  }
  return cur;
}

}  // namespace

CutPlane full_cut_plane(const CutProblem& problem_in, const CutOptions& options) {
  std::optional<CutProblem> storage;
  const CutProblem& problem = with_current_overlap(problem_in, storage);
  CutObjective obj(problem, options.lambda);
  const bool warm = options.warm_start.has_value();
  // Candidate normals, each with its exactly optimal offset.
  Best best;
  std::vector<Eigen::Vector3d> dirs;
  if (warm) {
    best = obj.best_offset(options.warm_start->normal);
    dirs.push_back(best.plane.normal);
  } else {
    const CutPlane exact_plane = exact_cut_plane(problem, options);
    best = {exact_plane, obj.value(exact_plane)};
    dirs.push_back(exact_plane.normal);
    dirs.push_back(lsf_cut_plane(problem.a, problem.b, *problem.current_overlap).normal);
    const auto& pts = obj.range_points();
    if (pts.size() >= 3) {  // principal axes of the overlap
      Eigen::Vector3d m = Eigen::Vector3d::Zero();
      for (const auto& v : pts) m += v;
      m /= double(pts.size());
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (const auto& v : pts) cov += (v - m) * (v - m).transpose();
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
      for (int k = 0; k < 3; ++k) {
        dirs.push_back(es.eigenvectors().col(k));
        dirs.push_back(-es.eigenvectors().col(k));
      }
    }
  }
  for (const auto& d : fibonacci_sphere(warm ? options.warm_directions : options.full_directions)) dirs.push_back(d);
  // The scan ignores the interference terms (weight lambda, small, but one slice profile each):
  // they only re-rank nearly equal directions, and the polish below uses the full objective.
  const bool has_interference = options.lambda != 0 && (!problem.interference_a.empty() || !problem.interference_b.empty());
  std::optional<CutObjective> coarse_own;
  if (has_interference) coarse_own.emplace(problem, 0.0);
  CutObjective& coarse = coarse_own ? *coarse_own : obj;
  std::vector<Best> cands;
  cands.reserve(dirs.size());
  // A warm start is always polished first, whatever the scan says.
  if (warm) cands.push_back(best);
  for (std::size_t k = warm ? 1 : 0; k < dirs.size(); ++k)
    if (dirs[k].norm() > 0) cands.push_back(coarse.best_offset(dirs[k]));
  std::stable_sort(cands.begin() + (warm ? 1 : 0), cands.end(), [](const Best& x, const Best& y) { return x.value < y.value; });

  // Polish the best few distinct directions (at least ~15 degrees apart).
  std::vector<Eigen::Vector3d> chosen;
  for (const auto& c : cands) {
    if (chosen.size() >= options.full_starts) break;
    bool distinct = true;
    for (const auto& n : chosen) distinct &= n.dot(c.plane.normal) < std::cos(15.0 * M_PI / 180.0);
    if (!distinct) continue;
    chosen.push_back(c.plane.normal);
    const Best r = polish(obj, has_interference ? obj.best_offset(c.plane.normal) : c);
    if (r.value < best.value) best = r;
  }
  return best.plane;
}

}  // namespace dcshell
