// The DC-shell pipeline (see build_shells.h).
#include "dcshell/build_shells.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include "dcshell/convex_hull.h"
#include "dcshell/exact_polytope.h"
#include "dcshell/mesh_volume.h"
#include "dcshell/overlaps.h"
#include "dcshell/parallel_for.h"
#include "dcshell/polytope_clip.h"
#include "dcshell/volume_loss.h"

namespace dcshell {

namespace {

class StageClock {
 public:
  explicit StageClock(std::vector<StageTime>& out) : out_(out), t_(std::chrono::steady_clock::now()) {}
  void lap(const std::string& stage) {
    auto now = std::chrono::steady_clock::now();
    out_.push_back({stage, std::chrono::duration<double>(now - t_).count()});
    t_ = now;
  }

 private:
  std::vector<StageTime>& out_;
  std::chrono::steady_clock::time_point t_;
};

// Parts whose hull lies (almost) entirely inside another's are absorbed by it. Smaller parts are
// decided first; a container that is itself absorbed later passes its parts on.
std::vector<AbsorbedPart> absorb_nested(const std::vector<Overlap>& overlaps, const std::vector<double>& vol,
                                        double fraction) {
  const std::size_t n = vol.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  // Ascending volume; among equal volumes (duplicates) the later part goes first, so the
  // earlier one is kept.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return vol[a] != vol[b] ? vol[a] < vol[b] : a > b;
  });
  std::vector<long> container(n, -1);
  std::vector<double> inside(n, 0.0);
  std::vector<char> decided(n, 0);
  for (std::size_t i : order) {
    decided[i] = 1;
    double best = 0;
    long best_j = -1;
    for (const auto& o : overlaps) {
      if (o.i != i && o.j != i) continue;
      std::size_t j = o.i == i ? o.j : o.i;
      if (decided[j] || vol[i] <= 0) continue;  // only a part not yet absorbed can contain i
      double f = o.volume / vol[i];
      if (f > best) best = f, best_j = long(j);
    }
    if (best_j >= 0 && best >= fraction) container[i] = best_j, inside[i] = std::min(best, 1.0);
  }
  std::vector<AbsorbedPart> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (container[i] < 0) continue;
    std::size_t c = std::size_t(container[i]);
    while (container[c] >= 0) c = std::size_t(container[c]);
    out.push_back({i, c, inside[i]});
  }
  return out;
}

}  // namespace

ShellResult build_shells(const std::vector<Part>& parts, const ShellOptions& opt) {
  ShellResult res;
  StageClock clock(res.times);
  auto progress = [&](const std::string& s, std::size_t d, std::size_t t) {
    if (opt.progress) opt.progress(s, d, t);
  };
  const std::size_t n = parts.size();

  // --- hulls (optionally simplified/regularised before cutting, as the paper does)
  std::vector<ExactPolytope> original(n), hull(n);
  std::vector<Mesh> hull_mesh(n);
  RemeshOptions remesh_opt;
  remesh_opt.iterations = opt.simplify_iterations;
  remesh_opt.fatten_flat_facets = opt.fatten_flat_facets;
  remesh_opt.edge_splits = opt.edge_splits;
  remesh_opt.edge_flips = opt.edge_flips;
  // Hulls are remeshed before cutting and shells after; the paper's 5% is one bound for both.
  // A hull may grow by sqrt(1 + R) - 1; each shell then gets what is left of (1 + R) x the
  // volume of its part's original hull cut by the same planes (below).
  remesh_opt.max_volume_increase = std::sqrt(1.0 + opt.max_volume_increase) - 1.0;
  // Input points within rounding of the hull of the others (a vertex 1e-11 off the line of an
  // edge) make sliver faces that no net can fold along; the hulls that are cut leave them out.
  // They lie within kMergeDistance of the part's size inside the original hulls, against which
  // the volume loss is measured.
  std::vector<std::size_t> pruned(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    progress("hulls", i, n);
    original[i] = exact_hull(parts[i].points, int(i));
    hull_mesh[i] = pruned_convex_hull_mesh(parts[i].points, kMergeDistance * bbox_diagonal(parts[i].points), {}, &pruned[i]);
  }
  if (opt.simplify_iterations > 0) {
    // Steiner points in a hull's facets would mostly be cut away, and they spend the faces the
    // shells may use on their cut faces. Collapses least volume first here: ordered by gain, the
    // hulls come out fatter but the shells cut from them less fat (measured on the shared models).
    // Edge splits stay on: within the hull's own face count they made the paper pipeline's shells
    // fatter on 7 of the 8 shared models (not Pikachu).
    RemeshOptions hull_opt = remesh_opt;
    hull_opt.steiner_points = false;
    hull_opt.order_by_gain = false;
    parallel_for(n, [&](std::size_t i) {
      hull_mesh[i] = remesh_convex_shell(hull_mesh[i], std::vector<CutPlane>{}, hull_opt);
    });
  }
  for (std::size_t i = 0; i < n; ++i)
    hull[i] = opt.simplify_iterations > 0 || pruned[i] > 0 ? exact_hull(mesh_points(hull_mesh[i]), int(i)) : original[i];
  clock.lap("hulls");

  // --- overlaps and nesting
  std::vector<Overlap> overlaps = find_overlaps(hull);
  std::vector<double> vol(n);
  for (std::size_t i = 0; i < n; ++i) vol[i] = approximate_volume(hull[i]);
  res.absorbed = absorb_nested(overlaps, vol, opt.absorb_fraction);
  std::vector<char> active(n, 1);
  for (const auto& a : res.absorbed) active[a.part] = 0;
  std::vector<HullPair> pairs;
  for (const auto& o : overlaps)
    if (active[o.i] && active[o.j]) pairs.push_back({o.i, o.j, to_double(o.region)});
  res.overlapping_pairs = pairs.size();
  // An absorbed part takes part in no pair: the cut-plane stage sees its hull empty.
  std::vector<ConvexPolytope> hull_d(n);
  for (std::size_t i = 0; i < n; ++i)
    if (active[i]) hull_d[i] = to_double(hull[i]);
  clock.lap("overlaps");

  // --- cut planes, one per overlapping pair, then the refinement sweeps
  std::vector<CutPlane> planes = fit_pair_planes(hull_d, pairs, opt.cut, opt.progress);
  clock.lap("cut planes");
  planes = refine_cut_planes(hull_d, pairs, std::move(planes), opt.cut, opt.sweep, &res.sweep, opt.progress);
  clock.lap("sweeps");

  // --- exact trim and certified rounding
  for (std::size_t i = 0; i < n; ++i) {
    if (!active[i]) continue;
    progress("trim", i, n);
    Shell sh;
    sh.part = i;
    std::vector<CutPlane> keep;
    for (std::size_t q = 0; q < pairs.size(); ++q) {
      if (pairs[q].i == i) sh.cuts.push_back({planes[q], pairs[q].j});
      else if (pairs[q].j == i) sh.cuts.push_back({planes[q].flipped(), pairs[q].i});
      else continue;
      keep.push_back(sh.cuts.back().plane);
    }
    sh.mesh = trim_shell(hull[i], keep, &sh.trim);
    sh.trim.flat_vertices += pruned[i];  // the hull's, left out above, and the cut's
    if (sh.mesh.number_of_faces() == 0) {
      res.vanished.push_back(i);
      continue;
    }
    for (const auto& a : res.absorbed)
      if (a.container == i) sh.absorbed.push_back(a.part);
    res.shells.push_back(std::move(sh));
  }
  clock.lap("trim");

  // --- simplify and regularise the shells, keeping cut planes and every contact
  if (opt.simplify_iterations > 0) {
    std::vector<Mesh> meshes;
    for (const auto& s : res.shells) meshes.push_back(s.mesh);
    std::vector<std::pair<std::size_t, std::size_t>> unseparated;
    std::vector<ShellConstraints> cons = neighbour_constraints(meshes, &unseparated);
    for (std::size_t k = 0; k < res.shells.size(); ++k)
      for (const auto& c : res.shells[k].cuts) cons[k].cut_planes.push_back(c.plane);
    // Two shells no plane was found between could grow into each other: they stay as trimmed
    // (certified disjoint), rather than the whole result failing its certification.
    std::vector<char> keep_as_is(res.shells.size(), 0);
    for (auto [a, b] : unseparated) keep_as_is[a] = keep_as_is[b] = 1;
    progress("remesh", 0, res.shells.size());
    // Shells are independent once their constraints are fixed: one per core.
    parallel_for(res.shells.size(), [&](std::size_t k) {
      if (keep_as_is[k]) return;
      auto& s = res.shells[k];
      // The faces the hull's simplification saved may buy Steiner points in the shell: up to the
      // faces of the same cuts through the part's original hull (what the plain shell would have).
      RemeshOptions o = remesh_opt;
      std::vector<CutPlane> keep;
      for (const auto& c : s.cuts) keep.push_back(c.plane);
      const Mesh plain = trim_shell(original[s.part], keep);
      if (remesh_opt.steiner_points) o.max_faces = plain.number_of_faces();
      // The bound holds per shell against the part's own hull cut by the same planes: what the
      // hull stage left of it is this stage's (where the hull grew less than its share, the
      // shell may use the rest; where its growth went into what the cuts keep, less).
      const double v_plain = CGAL::to_double(six_signed_volume(plain));
      const double v_now = CGAL::to_double(six_signed_volume(s.mesh));
      if (v_plain > 0 && v_now > 0)
        o.max_volume_increase = std::max(0.0, (1.0 + opt.max_volume_increase) * v_plain / v_now - 1.0);
      s.mesh = remesh_convex_shell(s.mesh, cons[k], o, &s.remesh);
      s.remeshed = true;
    });
  }
  clock.lap("remesh");

  // --- certification of exactly what will be written, and the metric
  std::vector<Mesh> meshes;
  for (const auto& s : res.shells) meshes.push_back(s.mesh);
  res.certification = certify(meshes);
  for (std::size_t k = 0; k < res.shells.size(); ++k) {
    res.shells[k].volume = res.certification.meshes[k].volume;
    res.shells_volume += res.shells[k].volume;
  }
  clock.lap("certify");
  // Without remeshing the overlaps are those of the original hulls: reuse them.
  const VolumeLoss loss = volume_loss(original, meshes, opt.simplify_iterations > 0 ? nullptr : &overlaps);
  res.union_volume = loss.union_volume;
  res.shells_volume = loss.shells_volume;  // the exact sum, rounded once
  res.volume_loss = loss.value;
  res.volume_loss_error_bound = loss.error_bound;
  res.volume_loss_exact = loss.exact;
  clock.lap("volume");
  return res;
}

}  // namespace dcshell
