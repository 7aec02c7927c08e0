// The DC-shell pipeline (see build_shells.h).
#include "dcshell/build_shells.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <numeric>

#include "dcshell/convex_hull.h"
#include "dcshell/exact_polytope.h"
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

struct Pair {
  std::size_t i, j;          // part indices, i < j
  const Overlap* overlap;    // C_i ∩ C_j
  ConvexPolytope region;     // the same in doubles
  CutPlane plane;            // part i keeps normal·x <= offset
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

const char* to_string(SweepStart start) {
  switch (start) {
    case SweepStart::pairwise: break;
    case SweepStart::refit_reshaped: return "refit-reshaped";
    case SweepStart::constructive: return "constructive";
  }
  return "pairwise";
}

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
  // Hulls are remeshed before cutting and shells after: each stage may grow its input by
  // sqrt(1 + R) - 1, so the two together stay near R (the paper's 5% is one bound).
  remesh_opt.max_volume_increase = std::sqrt(1.0 + opt.max_volume_increase) - 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    progress("hulls", i, n);
    original[i] = exact_hull(parts[i].points, int(i));
    hull_mesh[i] = convex_hull_mesh(parts[i].points);
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
    hull[i] = opt.simplify_iterations > 0 ? exact_hull(mesh_points(hull_mesh[i]), int(i)) : original[i];
  clock.lap("hulls");

  // --- overlaps and nesting
  std::vector<Overlap> overlaps = find_overlaps(hull);
  std::vector<double> vol(n);
  for (std::size_t i = 0; i < n; ++i) vol[i] = approximate_volume(hull[i]);
  res.absorbed = absorb_nested(overlaps, vol, opt.absorb_fraction);
  std::vector<char> active(n, 1);
  for (const auto& a : res.absorbed) active[a.part] = 0;
  std::vector<Pair> pairs;
  for (const auto& o : overlaps)
    if (active[o.i] && active[o.j]) pairs.push_back({o.i, o.j, &o, to_double(o.region), CutPlane{}});
  res.overlapping_pairs = pairs.size();
  std::vector<ConvexPolytope> hull_d(n);
  for (std::size_t i = 0; i < n; ++i) hull_d[i] = to_double(hull[i]);
  // Pair indices touching each part, for the interference terms and the sweeps.
  std::vector<std::vector<std::size_t>> pairs_of(n);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    pairs_of[pairs[p].i].push_back(p);
    pairs_of[pairs[p].j].push_back(p);
  }
  clock.lap("overlaps");

  // --- cut planes, one per overlapping pair
  auto other = [&](const Pair& p, std::size_t part) { return p.i == part ? p.j : p.i; };
  auto oriented_for = [&](const Pair& p, std::size_t part) { return p.i == part ? p.plane : p.plane.flipped(); };
  auto make_problem = [&](std::size_t p, ConvexPolytope a, ConvexPolytope b) {
    CutProblem prob;
    prob.a = std::move(a);
    prob.b = std::move(b);
    prob.overlap = pairs[p].region;
    // Interference (Eq. 7): the regions each side shares with its other neighbours.
    for (std::size_t q : pairs_of[pairs[p].i])
      if (q != p) prob.interference_a.push_back(pairs[q].region);
    for (std::size_t q : pairs_of[pairs[p].j])
      if (q != p) prob.interference_b.push_back(pairs[q].region);
    return prob;
  };
  auto pair_options = [&](std::size_t p) {
    CutOptions c = opt.cut;
    c.seed = opt.cut.seed * 1000003u + p;  // independent, reproducible streams per pair
    return c;
  };
  {
    // Each pair's fit reads only the hulls and the overlap regions and has its own seed: the
    // pairs run side by side, with the same planes as one after the other.
    std::mutex progress_lock;
    std::size_t done = 0;
    parallel_for(pairs.size(), [&](std::size_t p) {
      pairs[p].plane = fit_cut_plane(make_problem(p, hull_d[pairs[p].i], hull_d[pairs[p].j]), pair_options(p)).plane;
      std::lock_guard<std::mutex> guard(progress_lock);
      progress("cut planes", ++done, pairs.size());
    });
  }
  clock.lap("cut planes");

  // --- refinement sweeps: independently optimal planes over-trim where 3+ hulls meet
  const bool volume_driven = opt.cut.method == CutMethod::exact || opt.cut.method == CutMethod::full;
  if (volume_driven) {
    double scale = 0;
    for (std::size_t i = 0; i < n; ++i) scale += active[i] ? vol[i] : 0;
    auto oriented = [&](const std::vector<CutPlane>& planes, std::size_t q, std::size_t part) {
      return pairs[q].i == part ? planes[q] : planes[q].flipped();
    };
    // The part's hull clipped by its planes other than `skip` (and, while a start places its
    // planes one by one, only by those already placed).
    auto trimmed_except = [&](const std::vector<CutPlane>& planes, std::size_t part, std::size_t skip,
                              const std::vector<char>* placed = nullptr) {
      ConvexPolytope c = hull_d[part];
      for (std::size_t q : pairs_of[part])
        if (q != skip && (!placed || (*placed)[q]) && !c.empty()) c = clip(c, oriented(planes, q, part), -2);
      return c;
    };
    struct SweepRun {
      std::vector<CutPlane> planes;
      int sweeps = 0;
      std::vector<double> gains;
      std::size_t refits = 0;  // pairs re-fitted from scratch
    };
    // A hull that the other planes have cut by more than this fraction no longer resembles the
    // one its pairwise plane was fitted to; polishing that plane can stay in the wrong basin.
    constexpr double kReshaped = 0.3;
    // Runs f(p) for the pairs in `order` as if one after the other, but side by side where
    // that cannot change anything: f(p) reads and writes only the planes (and the per-part
    // state) of p's two parts, so p must wait only for the pairs before it that share a part.
    // Each pair goes into the first wave after all of those; a wave's pairs share no part.
    auto in_waves = [&](const std::vector<std::size_t>& order, const std::function<void(std::size_t)>& f,
                        const std::function<void(std::size_t)>& done = {}) {
      std::vector<std::vector<std::size_t>> waves;
      std::vector<std::size_t> last(n, 0);  // per part: 1 + the wave of its latest pair so far
      for (std::size_t p : order) {
        const std::size_t w = std::max(last[pairs[p].i], last[pairs[p].j]);
        if (waves.size() <= w) waves.resize(w + 1);
        waves[w].push_back(p);
        last[pairs[p].i] = last[pairs[p].j] = w + 1;
      }
      std::size_t count = 0;
      for (const auto& wave : waves) {
        parallel_for(wave.size(), [&](std::size_t k) { f(wave[k]); });
        if (done) done(count += wave.size());
      }
    };
    std::vector<std::size_t> index_order(pairs.size());
    std::iota(index_order.begin(), index_order.end(), 0);
    auto run_sweeps = [&](std::vector<CutPlane> planes, SweepStart start) {
      SweepRun run;
      const bool refit_reshaped = start == SweepStart::refit_reshaped;
      if (start == SweepStart::constructive) {
        // Planes placed one pair at a time, each fitted from scratch against its two hulls as
        // trimmed by the planes placed before it: a part's later planes then keep the side its
        // earlier ones kept, where independent pairwise planes may each keep another side
        // (many hulls through one region; doc/shell.md, "Three starts").
        std::vector<char> placed(pairs.size(), 0), trimmed(n, 0), fitted(pairs.size(), 0);
        // The larger hulls' pairs first: the smaller hulls then fit around their planes.
        std::vector<std::size_t> order = index_order;
        auto larger = [&](std::size_t q) { return std::max(vol[pairs[q].i], vol[pairs[q].j]); };
        std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return larger(x) > larger(y); });
        in_waves(order, [&](std::size_t p) {
          const std::size_t i = pairs[p].i, j = pairs[p].j;
          if (trimmed[i] || trimmed[j]) {
            ConvexPolytope a = trimmed_except(planes, i, p, &placed), b = trimmed_except(planes, j, p, &placed);
            if (!a.empty() && !b.empty()) {
              // Even a hull the placed planes barely trimmed gets a new fit: between two equal
              // hulls, that trim is what decides which one the plane cuts.
              planes[p] = fit_cut_plane(make_problem(p, std::move(a), std::move(b)), pair_options(p)).plane;
              fitted[p] = 1;
            } else if (!a.empty() || !b.empty()) {
              // One side is gone already: the plane keeps the whole overlap for the other.
              const Eigen::Vector3d nrm = planes[p].normal;
              double lo = std::numeric_limits<double>::infinity(), hi = -lo;
              for (const auto& v : pairs[p].region.vertices) lo = std::min(lo, nrm.dot(v)), hi = std::max(hi, nrm.dot(v));
              if (lo <= hi) planes[p].offset = a.empty() ? lo : hi;
            }
          }  // else both hulls are still whole: the pairwise plane is that fit already
          placed[p] = 1;
          trimmed[i] = trimmed[j] = 1;
        });
        run.refits = static_cast<std::size_t>(std::count(fitted.begin(), fitted.end(), 1));
      }
      // A pair's refit depends only on the planes of its two parts: skip it while none of them
      // changed since its last fit (the fit is deterministic, so the answer would be the same).
      std::vector<std::size_t> version(n, 0);
      std::vector<std::pair<std::size_t, std::size_t>> fitted_at(pairs.size(),
                                                                   {~std::size_t(0), ~std::size_t(0)});
      for (int s = 0; s < opt.max_sweeps; ++s) {
        // Per pair, summed in pair order afterwards: the same bits as one pair after the other.
        std::vector<double> pair_gain(pairs.size(), 0.0);
        std::vector<char> refit(pairs.size(), 0);
        const std::string stage = "sweep " + std::to_string(s + 1);
        in_waves(index_order, [&](std::size_t p) {
          const std::size_t i = pairs[p].i, j = pairs[p].j;
          if (pairs_of[i].size() + pairs_of[j].size() <= 2) return;  // nothing else trims them
          const std::pair<std::size_t, std::size_t> now{version[i], version[j]};
          if (fitted_at[p] == now) return;
          fitted_at[p] = now;
          ConvexPolytope a = trimmed_except(planes, i, p), b = trimmed_except(planes, j, p);
          if (a.empty() || b.empty()) return;
          const bool reshaped = s == 0 && (volume(a) < (1 - kReshaped) * vol[i] ||
                                           volume(b) < (1 - kReshaped) * vol[j]);
          CutProblem prob = make_problem(p, std::move(a), std::move(b));
          prob.current_overlap = tagged_intersection(prob.a, prob.b);  // once for both calls
          CutResult cur = evaluate_cut_plane(prob, planes[p], opt.cut.lambda);
          CutOptions o = pair_options(p);
          const bool from_scratch = opt.global_sweeps || (refit_reshaped && reshaped);
          if (!from_scratch) o.warm_start = planes[p];
          refit[p] = refit_reshaped && reshaped;
          CutResult cand = fit_cut_plane(prob, o);
          if (cand.objective < cur.objective - 1e-12 * scale) {
            pair_gain[p] = cur.objective - cand.objective;
            planes[p] = cand.plane;
            ++version[i];
            ++version[j];
            fitted_at[p] = {version[i], version[j]};
          }
        }, [&](std::size_t done) {
          if (start == SweepStart::pairwise) progress(stage, done, pairs.size());  // one start reports
        });
        double gain = 0;
        for (double g : pair_gain) gain += g;
        run.refits += static_cast<std::size_t>(std::count(refit.begin(), refit.end(), 1));
        run.sweeps = s + 1;
        run.gains.push_back(scale > 0 ? gain / scale : 0.0);
        if (gain <= opt.sweep_tolerance * scale) break;
      }
      run.planes = std::move(planes);
      return run;
    };
    // What the shells keep: each hull clipped by all its planes.
    auto kept_volume = [&](const std::vector<CutPlane>& planes) {
      double v = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (active[i]) v += volume(trimmed_except(planes, i, pairs.size()));
      return v;
    };
    std::vector<CutPlane> initial(pairs.size());
    for (std::size_t p = 0; p < pairs.size(); ++p) initial[p] = pairs[p].plane;
    // Warm-started polishing keeps each plane near its pairwise fit. Where the other planes
    // reshape a pair's hulls, a second start re-fits those pairs from scratch in its first
    // sweep; the start that keeps more volume wins (doc/shell.md, "Two starts"). The starts are
    // independent, so they run side by side.
    bool two_starts = false;
    if (opt.second_start && opt.cut.method == CutMethod::full && !opt.global_sweeps)
      for (std::size_t p = 0; p < pairs.size() && !two_starts; ++p)
        for (std::size_t part : {pairs[p].i, pairs[p].j})
          if (pairs_of[part].size() > 1 && volume(trimmed_except(initial, part, p)) < (1 - kReshaped) * vol[part])
            two_starts = true;
    std::vector<SweepStart> starts = {SweepStart::pairwise};
    if (two_starts) starts.push_back(SweepStart::refit_reshaped);
    // The constructive start costs a from-scratch fit per pair, in waves; it runs where the
    // pairwise planes together cut a fifth or more off the hulls (the shared composite models
    // and ACD sets: 0.1-14%, where it changed no loss by more than 0.003 points; the random boxes
    // of doc/results.md: 8-57%; plank stars: 77-97%).
    constexpr double kConstructive = 0.2;
    if (two_starts && opt.constructive_start) {
      double cut = 0, total = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (active[i]) cut += vol[i] - volume(trimmed_except(initial, i, pairs.size())), total += vol[i];
      if (cut >= kConstructive * total) starts.push_back(SweepStart::constructive);
    }
    std::vector<SweepRun> runs(starts.size());
    // The costliest start first: with three starts on two threads, the other two share a thread.
    parallel_for(runs.size(), [&](std::size_t k) {
      const std::size_t r = runs.size() - 1 - k;
      runs[r] = run_sweeps(initial, starts[r]);
    });
    std::size_t win = 0;
    double win_kept = kept_volume(runs[0].planes);
    for (std::size_t k = 1; k < runs.size(); ++k) {
      if (runs[k].refits == 0) continue;  // the same planes as the first start
      const double kept = kept_volume(runs[k].planes);
      if (kept > win_kept) win = k, win_kept = kept;
    }
    if (win > 0) res.sweep_refits = runs[win].refits;
    res.sweep_start = starts[win];
    SweepRun& best = runs[win];
    for (std::size_t p = 0; p < pairs.size(); ++p) pairs[p].plane = best.planes[p];
    res.sweeps_run = best.sweeps;
    res.sweep_gains = best.gains;
  }
  clock.lap("sweeps");

  // --- exact trim and certified rounding
  for (std::size_t i = 0; i < n; ++i) {
    if (!active[i]) continue;
    progress("trim", i, n);
    Shell sh;
    sh.part = i;
    std::vector<CutPlane> keep;
    for (std::size_t q : pairs_of[i]) {
      sh.cuts.push_back({oriented_for(pairs[q], i), other(pairs[q], i)});
      keep.push_back(sh.cuts.back().plane);
    }
    sh.mesh = trim_shell(hull[i], keep, &sh.trim);
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
    std::vector<ShellConstraints> cons = neighbour_constraints(meshes);
    for (std::size_t k = 0; k < res.shells.size(); ++k)
      for (const auto& c : res.shells[k].cuts) cons[k].cut_planes.push_back(c.plane);
    progress("remesh", 0, res.shells.size());
    // Shells are independent once their constraints are fixed: one per core.
    parallel_for(res.shells.size(), [&](std::size_t k) {
      auto& s = res.shells[k];
      // The faces the hull's simplification saved may buy Steiner points in the shell: up to the
      // faces of the same cuts through the part's original hull (what the plain shell would have).
      RemeshOptions o = remesh_opt;
      std::vector<CutPlane> keep;
      for (const auto& c : s.cuts) keep.push_back(c.plane);
      if (remesh_opt.steiner_points) o.max_faces = trim_shell(original[s.part], keep).number_of_faces();
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
