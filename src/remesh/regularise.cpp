// Constrained Laplacian smoothing of a convex shell (see dcshell/regularise.h).
#include "dcshell/regularise.h"

#include <algorithm>

#include "remesh/passes.h"

namespace dcshell {
namespace {

using namespace remesh_detail;

constexpr double kMargin = 1e-9;   // local units; see simplify.cpp
constexpr int kActiveSetRounds = 6;

// The rows "point o of `enclose` stays on or below cone face i" that the QP is given lazily:
// only those violated at the target or at the last solution (a cutting-plane loop), since a
// vertex's box holds many points of which few ever bind.
struct EncloseRows {
  std::vector<std::pair<std::size_t, std::size_t>> active;  // (point, ring index)
  // Per (position in `near`, ring index): taken in. A flat neighbourhood (a cap of hundreds of
  // points on its plane) takes in nearly every pair, and a search of `active` made that quadratic.
  std::vector<char> taken;
};

}  // namespace

namespace remesh_detail {

std::size_t Workspace::regularise_sweep(const std::vector<Point3>& enclose, const ShellConstraints& constraints,
                                        double max_volume, RegulariseStats& st) {
  std::size_t moves = 0;
  {
    for (V v : mesh.vertices()) {
      if (settled_[v] == stamp_[v]) continue;  // nothing around it changed since it last stayed put
      const Star s = vertex_star(mesh, v);
      settled_[v] = stamp_[v];
      if (!s.valid) continue;
      const std::size_t n = s.ring.size();
      const Eigen::Vector3d x = vec(mesh.point(v));
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      Frame frame{x, 0.0};
      for (V r : s.ring) {
        centroid += vec(mesh.point(r));
        frame.scale += (vec(mesh.point(r)) - x).norm();
      }
      centroid /= double(n);
      frame.scale /= double(n);
      if (!(frame.scale > 0)) continue;
      const Eigen::Vector3d target = frame.to_local(centroid);
      if (target.norm() < 1e-9) continue;  // already at its centroid
      const double margin = std::max(kMargin, 1e-13 * x.lpNorm<Eigen::Infinity>() / frame.scale);
      auto P = [&](std::size_t i) -> const Point3& { return mesh.point(s.ring[i % n]); };

      // Convexity rows: at every spoke x' stays on or above the plane of three consecutive ring
      // vertices; at every ring edge on or below the face across. Their margin never exceeds half
      // the current slack, so a flat neighbourhood keeps its (zero-margin) current position feasible.
      std::vector<Row> convex_rows;
      for (std::size_t i = 0; i < n; ++i) {
        add_below_row(P(i + n - 1), P(i + 1), P(i), frame, 0, convex_rows);
        add_below_row(P(i + 1), P(i), mesh.point(s.across[i]), frame, 0, convex_rows);
      }
      // Points to enclose near the star (outside the star's box they cannot leave; see star.cpp).
      double lo[3], hi[3];
      for (int k = 0; k < 3; ++k) lo[k] = hi[k] = x[k];
      for (V r : s.ring)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], mesh.point(r)[k]), hi[k] = std::max(hi[k], mesh.point(r)[k]);
      std::vector<std::size_t> near;
      for (std::size_t o = 0; o < enclose.size(); ++o) {
        bool in = true;
        for (int k = 0; k < 3; ++k) in = in && enclose[o][k] >= lo[k] && enclose[o][k] <= hi[k];
        if (in) near.push_back(o);
      }
      // Volume row: the volume is linear in x' with the ring fixed.
      Eigen::Vector3d grad = Eigen::Vector3d::Zero();
      for (std::size_t i = 0; i < n; ++i)
        grad += (vec(P(i)) - x).cross(vec(P(i + 1)) - x) / 6.0;
      const double room = max_volume - volume;

      // The cone-face row for point o and ring edge i, as a·y <= b in local units.
      auto enclose_row = [&](std::size_t o, std::size_t i, double mg) {
        std::vector<Row> r;
        add_below_row(P(i), enclose[o], P(i + 1), frame, mg, r);
        return r;
      };
      auto value = [](const Row& r, const Eigen::Vector3d& y) { return r.a.dot(y) - r.b; };

      bool moved = false, solved = false, stays = false;
      for (double scale_margin : {1.0, 100.0}) {
        const double mg = margin * scale_margin;
        std::vector<Row> base;
        for (const Row& r : convex_rows) base.push_back({r.a, r.b - std::clamp(r.b / 2, 0.0, mg)});
        // Constraint rows likewise: a cut-face vertex lies within rounding of its cut plane, and a
        // full margin would pin it (nothing in the thin slab left feasible).
        std::vector<Row> con;
        add_constraint_rows(constraints, frame, 0, con);
        Eigen::Vector3d tight = Eigen::Vector3d::Zero();  // normal of a constraint the vertex nearly touches
        for (const Row& r : con) {
          if (r.b < mg) tight = r.a;
          base.push_back({r.a, r.b - std::clamp(r.b / 2, 0.0, mg)});
        }
        if (std::isfinite(room)) {
          const Eigen::Vector3d a = grad * frame.scale;
          const double len = a.norm();
          if (len > 0) base.push_back({a / len, room / len - mg});
        }
        EncloseRows er;
        er.taken.assign(near.size() * n, 0);
        auto add_violated = [&](const Eigen::Vector3d& y) {
          bool added = false;
          for (std::size_t j = 0; j < near.size(); ++j)
            for (std::size_t i = 0; i < n; ++i) {
              if (er.taken[j * n + i]) continue;
              auto r = enclose_row(near[j], i, mg);
              if (!r.empty() && value(r[0], y) > -mg) {
                er.taken[j * n + i] = 1;
                er.active.push_back({near[j], i});
                added = true;
              }
            }
          return added;
        };
        add_violated(target);
        std::optional<Eigen::Vector3d> y;
        for (int round = 0; round < kActiveSetRounds; ++round) {
          std::vector<Row> rows = base;
          for (auto [o, i] : er.active) {
            auto r = enclose_row(o, i, mg);
            rows.insert(rows.end(), r.begin(), r.end());
          }
          y = solve_qp3(target, rows);
          if (!y || !add_violated(*y)) break;
        }
        if (!y) break;  // infeasible: a bigger margin will not help
        solved = true;
        const Point3 w = pt(frame.to_world(*y));
        if (y->norm() < 1e-12 || w == mesh.point(v)) { stays = true; break; }  // already where it should be
        const double dv = volume_change(mesh, s, w);
        if (volume + dv > max_volume && dv > 0) continue;
        // Against a nearly touched constraint, the slab is about one rounding unit thick: nearby
        // doubles across it are tried too, each checked exactly.
        Point3 ok_w = w;
        bool valid = replacement_is_valid(mesh, s, w, enclose, constraints);
        if (!valid && tight.squaredNorm() > 0) {
          const double ulp = std::ldexp(1.0, -52) * vec(w).lpNorm<Eigen::Infinity>();
          for (double k : {-1.0, -2.0, 1.0, -4.0}) {
            ok_w = pt(vec(w) + k * ulp * tight);
            if ((valid = replacement_is_valid(mesh, s, ok_w, enclose, constraints))) break;
          }
        }
        if (!valid) continue;
        const double dv_applied = ok_w == w ? dv : volume_change(mesh, s, ok_w);
        if (volume + dv_applied > max_volume && dv_applied > 0) continue;
        mesh.point(v) = ok_w;
        volume += dv_applied;
        moved = true;
        touched(s, v);
        // A small step means it has (nearly) converged: leave it until its neighbourhood changes.
        if ((*y).norm() < 1e-3) settled_[v] = stamp_[v];
        break;
      }
      if (moved) ++moves;
      else if (!solved) ++st.infeasible;
      else if (!stays) ++st.rejected;
    }
  }
  st.moves += moves;
  return moves;
}

}  // namespace remesh_detail

std::size_t regularise_convex(Mesh& mesh, const std::vector<Point3>& enclose, const ShellConstraints& constraints,
                              const RegulariseOptions& options, RegulariseStats* stats) {
  RegulariseStats local;
  remesh_detail::Workspace ws(mesh);
  std::size_t moves = 0;
  for (int sweep = 0; sweep < options.sweeps; ++sweep)
    moves += ws.regularise_sweep(enclose, constraints, options.max_volume, stats ? *stats : local);
  return moves;
}

}  // namespace dcshell
