// Remesh driver: alternating progressive-hull simplification and constrained smoothing, and the
// constraints a set of existing shells imposes on each other (see dcshell/remesh.h).
#include "dcshell/remesh.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "dcshell/certify.h"
#include "dcshell/convex_hull.h"
#include "dcshell/error.h"
#include "dcshell/fatness.h"
#include "dcshell/flat_facets.h"
#include "dcshell/regularise.h"
#include "remesh/passes.h"

namespace dcshell {
namespace {

using namespace remesh_detail;

// Share of the volume budget simplification may spend (smoothing may use all of it). Measured on
// the shared models: per unit of volume, collapses raise fatness far more than smoothing does
// (smoothing must move original hull vertices outward), so simplification may use it all.
constexpr double kSimplifyShare = 1.0;
// Share of the volume kept back for the flat-facet domes (fatten_flat_facets), which add about
// 1e-9 of the volume where they bulge outward.
constexpr double kDomeReserve = 1e-7;
// Flip passes per iteration (each an independent set). Measured on the shared models: 3 rounds
// beat 1 on Squirtle and Yoshi (paper pipeline +25.3% -> +26.1%, +23.0% either way) and on every
// post-only set of the three.
constexpr int kFlipRounds = 3;
// A point this close to a constraint plane (relative to the shell's size) may be cut off by the
// sinking of a facet on that plane (at most 1e-8 of the facet's size, FlatFacetOptions::max_sink).
constexpr double kNearConstraint = 1e-7;
// At most one exact LP/QP solve per this many faces of the input (see ExactFallbackBudget).
constexpr std::size_t kFacesPerExactSolve = 8;

std::size_t triangle_count(const Mesh& m) {
  std::size_t n = 0;
  for (auto f : m.faces()) n += m.degree(f) - 2;
  return n;
}

// The points farther than kNearConstraint (relative to their spread) from every constraint plane.
std::vector<Point3> points_off_constraints(const std::vector<Point3>& pts, const ShellConstraints& c) {
  if (pts.empty() || c.empty()) return pts;
  Eigen::Vector3d lo = vec(pts[0]), hi = lo;
  for (const Point3& p : pts) lo = lo.cwiseMin(vec(p)), hi = hi.cwiseMax(vec(p));
  const Frame frame{0.5 * (lo + hi), std::max((hi - lo).norm(), 1e-300)};
  std::vector<Row> rows;  // unit normals, local units
  add_constraint_rows(c, frame, 0, rows);
  std::vector<Point3> out;
  for (const Point3& p : pts) {
    const Eigen::Vector3d y = frame.to_local(vec(p));
    if (std::all_of(rows.begin(), rows.end(), [&](const Row& r) { return r.b - r.a.dot(y) > kNearConstraint; }))
      out.push_back(p);
  }
  return out;
}

}  // namespace

Mesh remesh_convex_shell(const Mesh& shell, const ShellConstraints& constraints, const RemeshOptions& options,
                         RemeshStats* stats) {
  if (options.iterations < 0) throw InputError("remesh: iterations must be >= 0");
  if (!(options.max_volume_increase >= 0) || !std::isfinite(options.max_volume_increase))
    throw InputError("remesh: max volume increase must be a finite number >= 0");
  const ConvexityVerdict verdict = check_convexity(shell);
  if (!verdict.ok()) throw InputError("remesh: shell is not a closed outward convex polyhedron: " + verdict.reason);
  std::vector<Point3> original = mesh_points(shell);
  for (const Point3& p : original)
    if (!constraints.satisfied_by(p)) throw InputError("remesh: shell does not satisfy its own constraint planes");

  // The hull of the vertices is the same polytope, triangulated and without non-extreme points.
  Mesh m = convex_hull_mesh(original);
  const double v0 = mesh_volume(m);
  const std::size_t faces0 = triangle_count(shell);
  const std::size_t allowed = options.max_faces > 0 ? options.max_faces : faces0;
  const int n = options.iterations;
  const double r = options.max_volume_increase;
  RemeshStats st;
  // The exact solver (about 1 ms a program) settles what the floating-point certificates cannot,
  // mostly the thin slabs along cut faces; capped per face so that it cannot dominate the run.
  const ExactFallbackBudget budget(std::max<std::size_t>(16, faces0 / kFacesPerExactSolve));
  FlatFacetOptions fo;
  fo.max_volume = v0 * (1 + r) * (1 - kDomeReserve);
  if (options.fatten_flat_facets && n > 0) {
    // Domed first too: a cut face then lies ~1e-9 below its plane instead of a rounding unit,
    // so collapses along its boundary find room between the two (the progressive hull's new
    // point must be above the faces it replaces and below the plane). What is enclosed from here
    // on is the domed shell.
    m = fatten_flat_facets(m, constraints, fo, &st.flat);
    original = mesh_points(m);
  }
  {
    Workspace ws(m);
    SimplifyStats sst;
    RegulariseStats rst;
    SimplifyOptions so;
    so.max_volume = v0 * (1 + kSimplifyShare * r) * (1 - kDomeReserve);
    so.target_faces = options.target_faces;
    so.single_pass = true;
    so.fatter_only = true;
    so.order_by_gain = options.order_by_gain;
    const double max_volume = v0 * (1 + r) * (1 - kDomeReserve);
    for (int it = 1; it <= n; ++it) {
      const std::size_t c = ws.simplify_pass(constraints, so, sst);
      // Splits after the collapses, which pay for them (up to the input's face count: max_faces is
      // the Steiner points'), and before smoothing, which then moves the new points and their
      // neighbours.
      const std::size_t now = m.number_of_faces();
      const std::size_t sp =
          options.edge_splits && faces0 > now ? ws.split_pass(constraints, max_volume, (faces0 - now) / 2) : 0;
      // Flips after the splits (free in faces), a few independent sets in a row: a flip often
      // makes its neighbour's worth flipping.
      std::size_t fl = 0;
      for (int k = 0; k < kFlipRounds && options.edge_flips; ++k) {
        const std::size_t f1 = ws.flip_pass(constraints, max_volume);
        fl += f1;
        if (f1 == 0) break;
      }
      const std::size_t mv = ws.regularise_sweep(original, constraints, max_volume, rst);
      st.splits += sp;
      st.flips += fl;
      if (options.on_iteration) options.on_iteration(it, m);
      if (c == 0 && mv == 0 && sp == 0 && fl == 0) {  // converged: later iterations would change nothing
        if (options.on_iteration)
          for (int k = it + 1; k <= n; ++k) options.on_iteration(k, m);
        break;
      }
    }
    st.collapses = sst.collapses;
    st.moves = rst.moves;
  }
  m.collect_garbage();

  // Exactly convex whatever happened above; every invariant is re-checked on the final doubles,
  // and the input is returned unchanged (as its hull) if one fails.
  Mesh out = convex_hull_mesh(mesh_points(m));
  bool ok = !out.is_empty() && triangle_count(out) <= std::max(faces0, triangle_count(m)) &&
            mesh_volume(out) <= v0 * (1 + r) * (1 + 1e-12) && mesh_encloses(out, original);
  for (auto v : out.vertices()) ok = ok && constraints.satisfied_by(out.point(v));
  if (!ok) {
    out = convex_hull_mesh(original);
    st.collapses = st.moves = st.splits = st.flips = 0;
  }
  if (options.fatten_flat_facets && n > 0) {
    // Last, so that no collapse or move undoes it; it spends ~1e-9 of the volume, so the
    // loop above left that much of the budget.
    const double first_sink = st.flat.max_inward;
    fo.max_volume = v0 * (1 + r) * (1 + 1e-12);
    // The input's points away from every constraint plane stay enclosed exactly: the loop above
    // may have left one on a face beside a facet that now sinks, whose tilt would cut it off.
    fo.enclose = points_off_constraints(original, constraints);
    // The faces collapses saved may buy Steiner points inside large facets (cut faces above all).
    const std::size_t now = triangle_count(out);
    fo.extra_faces = options.steiner_points && allowed > now ? allowed - now : 0;
    out = fatten_flat_facets(out, constraints, fo, &st.flat);
    st.flat.max_inward += first_sink;  // the two sinks add up at most
  }
  if (stats) {
    st.faces_before = faces0;
    st.faces_after = triangle_count(out);
    st.fatness_before = weighted_fatness(shell);
    st.fatness_after = weighted_fatness(out);
    st.volume_before = verdict.volume;
    st.volume_after = mesh_volume(out);
    *stats = st;
  }
  return out;
}

Mesh remesh_convex_shell(const Mesh& shell, const std::vector<CutPlane>& keep_inside, const RemeshOptions& options,
                         RemeshStats* stats) {
  ShellConstraints c;
  c.cut_planes = keep_inside;
  return remesh_convex_shell(shell, c, options, stats);
}

namespace {

struct Separator {
  bool found = false;
  double gap = -1;          // smallest distance of the other shell's vertices to the plane
  std::size_t contact = 0;  // vertices of the other shell exactly on the plane (a shared face)
  std::array<Point3, 3> face;
};

// The best face plane of `owner` with every vertex of `other` on or above it (exact).
Separator best_face_separator(const Mesh& owner, const std::vector<Point3>& other) {
  Separator best;
  for (auto f : owner.faces()) {
    auto h = owner.halfedge(f);
    const Point3 &a = owner.point(owner.source(h)), &b = owner.point(owner.target(h)),
                 &c = owner.point(owner.target(owner.next(h)));
    const Eigen::Vector3d na = (vec(b) - vec(a)).cross(vec(c) - vec(a));
    if (!(na.norm() > 0)) continue;
    const Eigen::Vector3d u = na.normalized();
    double gap = std::numeric_limits<double>::infinity();
    std::size_t contact = 0;
    bool sep = true;
    for (const Point3& q : other) {
      const CGAL::Orientation o = CGAL::orientation(a, b, c, q);
      if (o == CGAL::NEGATIVE) { sep = false; break; }
      contact += o == CGAL::COPLANAR;
      gap = std::min(gap, u.dot(vec(q) - vec(a)));
    }
    if (!sep) continue;
    gap = std::max(gap, 0.0);
    if (!best.found || gap > best.gap || (gap == best.gap && contact > best.contact))
      best = {true, gap, contact, {a, b, c}};
  }
  return best;
}

// n·x <= d for every point, exactly.
bool all_on_side(const std::vector<Point3>& pts, const CutPlane& p) {
  for (const Point3& x : pts)
    if (!on_or_below(p, x)) return false;
  return true;
}

// Shells far apart (a box gap along some axis of more than twice the larger box diagonal) are
// separated by the axis-aligned plane half-way across the gap: exact in doubles (a coordinate
// compared with the plane's offset), never within reach of a shell remeshed within its volume
// bound in practice, and found without testing every face of one against every vertex of the
// other (a set of hundreds of shells has mostly such pairs).
std::optional<CutPlane> far_apart_plane(const CGAL::Bbox_3& a, const CGAL::Bbox_3& b) {
  auto diag = [](const CGAL::Bbox_3& x) {
    return std::hypot(x.xmax() - x.xmin(), x.ymax() - x.ymin(), x.zmax() - x.zmin());
  };
  const double need = 2 * std::max(diag(a), diag(b));
  for (int k = 0; k < 3; ++k) {
    for (int side : {1, -1}) {
      const double hi = side > 0 ? a.max(k) : b.max(k), lo = side > 0 ? b.min(k) : a.min(k);
      if (!(lo - hi > need)) continue;
      const double mid = 0.5 * (hi + lo);
      if (!(hi < mid && mid < lo)) continue;
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      n[k] = side;  // a keeps n·x <= side * mid
      return CutPlane{n, side * mid};
    }
  }
  return std::nullopt;
}

}  // namespace

std::vector<ShellConstraints> neighbour_constraints(const std::vector<Mesh>& shells,
                                                    std::vector<std::pair<std::size_t, std::size_t>>* unseparated) {
  std::vector<ShellConstraints> out(shells.size());
  std::vector<std::vector<Point3>> pts;
  std::vector<CGAL::Bbox_3> box;
  for (const Mesh& m : shells) {
    pts.push_back(mesh_points(m));
    box.push_back(CGAL::bbox_3(pts.back().begin(), pts.back().end()));
  }
  for (std::size_t i = 0; i < shells.size(); ++i)
    for (std::size_t j = i + 1; j < shells.size(); ++j) {
      if (const auto far = far_apart_plane(box[i], box[j])) {
        out[i].cut_planes.push_back(*far);
        out[j].cut_planes.push_back(far->flipped());
        continue;
      }
      Separator si = best_face_separator(shells[i], pts[j]), sj = best_face_separator(shells[j], pts[i]);
      std::size_t owner = i, other = j;
      if (!si.found && !sj.found) {
        // No face plane separates them (an edge-edge contact, or a shared cut face rounded
        // differently on the two sides): an exact plane from the separating LP.
        Eigen::Vector3d ci = Eigen::Vector3d::Zero(), cj = Eigen::Vector3d::Zero();
        for (const Point3& p : pts[i]) ci += vec(p);
        for (const Point3& p : pts[j]) cj += vec(p);
        const Eigen::Vector3d n0 = cj / double(pts[j].size()) - ci / double(pts[i].size());
        const auto plane = n0.norm() > 0 ? separating_plane_exact(pts[i], pts[j], n0) : std::nullopt;
        if (plane) {
          out[i].exact_planes.push_back(*plane);
          out[j].exact_planes.push_back(plane->opposite());
        } else if (unseparated) {
          unseparated->push_back({i, j});
        }
        continue;
      }
      if (!si.found || (sj.found && (sj.gap > si.gap || (sj.gap == si.gap && sj.contact > si.contact)))) {
        std::swap(si, sj);
        std::swap(owner, other);
      }
      // With a gap, the plane half-way across it (double coefficients) leaves both shells room
      // to grow; it is used only if both shells are exactly on their sides of it.
      if (si.gap > 0) {
        const auto& f = si.face;
        const Eigen::Vector3d u = (vec(f[1]) - vec(f[0])).cross(vec(f[2]) - vec(f[0])).normalized();
        const CutPlane mid{u, u.dot(vec(f[0])) + 0.5 * si.gap};
        if (all_on_side(pts[owner], mid) && all_on_side(pts[other], mid.flipped())) {
          out[owner].cut_planes.push_back(mid);
          out[other].cut_planes.push_back(mid.flipped());
          continue;
        }
      }
      out[owner].face_planes.push_back(si.face);
      out[other].face_planes.push_back({si.face[0], si.face[2], si.face[1]});
    }
  return out;
}

}  // namespace dcshell
