// Cut planes of a composite: pairwise fits, then refinement sweeps (see refine_cut_planes.h).
#include "dcshell/refine_cut_planes.h"

#include <algorithm>
#include <limits>
#include <mutex>
#include <numeric>

#include "dcshell/parallel_for.h"
#include "dcshell/polytope_clip.h"

namespace dcshell {

const char* to_string(SweepStart start) {
  switch (start) {
    case SweepStart::pairwise: break;
    case SweepStart::refit_reshaped: return "refit-reshaped";
    case SweepStart::constructive: return "constructive";
  }
  return "pairwise";
}

namespace {

// The hulls, their pairs and what a fit of one pair needs; shared read-only by the fits.
class PairSet {
 public:
  PairSet(const std::vector<ConvexPolytope>& hulls, const std::vector<HullPair>& pairs, const CutOptions& cut)
      : hulls_(hulls), pairs_(pairs), cut_(cut), pairs_of_(hulls.size()) {
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      pairs_of_[pairs[p].i].push_back(p);
      pairs_of_[pairs[p].j].push_back(p);
    }
  }

  std::size_t parts() const { return hulls_.size(); }
  std::size_t size() const { return pairs_.size(); }
  const HullPair& operator[](std::size_t p) const { return pairs_[p]; }
  const ConvexPolytope& hull(std::size_t part) const { return hulls_[part]; }
  const std::vector<std::size_t>& pairs_of(std::size_t part) const { return pairs_of_[part]; }

  // Pair p's problem for the given (possibly trimmed) hulls, with the interference (Eq. 7) of
  // the regions each side shares with its other neighbours.
  CutProblem problem(std::size_t p, ConvexPolytope a, ConvexPolytope b) const {
    CutProblem prob;
    prob.a = std::move(a);
    prob.b = std::move(b);
    prob.overlap = pairs_[p].region;
    for (std::size_t q : pairs_of_[pairs_[p].i])
      if (q != p) prob.interference_a.push_back(pairs_[q].region);
    for (std::size_t q : pairs_of_[pairs_[p].j])
      if (q != p) prob.interference_b.push_back(pairs_[q].region);
    return prob;
  }

  CutOptions options(std::size_t p) const {
    CutOptions c = cut_;
    c.seed = cut_.seed * 1000003u + p;  // independent, reproducible streams per pair
    return c;
  }

  // The part's hull clipped by its planes other than `skip` (and, while a start places its
  // planes one by one, only by those already placed).
  ConvexPolytope trimmed_except(const std::vector<CutPlane>& planes, std::size_t part, std::size_t skip,
                                const std::vector<char>* placed = nullptr) const {
    ConvexPolytope c = hulls_[part];
    for (std::size_t q : pairs_of_[part])
      if (q != skip && (!placed || (*placed)[q]) && !c.empty())
        c = clip(c, pairs_[q].i == part ? planes[q] : planes[q].flipped(), -2);
    return c;
  }

  // What the shells keep: each hull clipped by all its planes.
  double kept_volume(const std::vector<CutPlane>& planes) const {
    double v = 0;
    for (std::size_t i = 0; i < parts(); ++i) v += volume(trimmed_except(planes, i, size()));
    return v;
  }

  // Runs f(p) for the pairs in `order` as if one after the other, but side by side where that
  // cannot change anything: f(p) reads and writes only the planes (and the per-part state) of
  // p's two parts, so p must wait only for the pairs before it that share a part. Each pair goes
  // into the first wave after all of those; a wave's pairs share no part.
  void in_waves(const std::vector<std::size_t>& order, const std::function<void(std::size_t)>& f,
                const std::function<void(std::size_t)>& done = {}) const {
    std::vector<std::vector<std::size_t>> waves;
    std::vector<std::size_t> last(parts(), 0);  // per part: 1 + the wave of its latest pair so far
    for (std::size_t p : order) {
      const std::size_t w = std::max(last[pairs_[p].i], last[pairs_[p].j]);
      if (waves.size() <= w) waves.resize(w + 1);
      waves[w].push_back(p);
      last[pairs_[p].i] = last[pairs_[p].j] = w + 1;
    }
    std::size_t count = 0;
    for (const auto& wave : waves) {
      parallel_for(wave.size(), [&](std::size_t k) { f(wave[k]); });
      if (done) done(count += wave.size());
    }
  }

 private:
  const std::vector<ConvexPolytope>& hulls_;
  const std::vector<HullPair>& pairs_;
  const CutOptions& cut_;
  std::vector<std::vector<std::size_t>> pairs_of_;
};

// A hull that the other planes have cut by more than this fraction no longer resembles the one
// its pairwise plane was fitted to; polishing that plane can stay in the wrong basin.
constexpr double kReshaped = 0.3;

// The constructive start costs a from-scratch fit per pair, in waves; it runs where the pairwise
// planes together cut a fifth or more off the hulls (the shared composite models and ACD sets:
// 0.1-14%, where it changed no loss by more than 0.003 points; the random boxes of
// doc/results.md: 8-57%; plank stars: 77-97%).
constexpr double kConstructive = 0.2;

struct SweepRun {
  std::vector<CutPlane> planes;
  SweepReport report;
};

// Planes placed one pair at a time, each fitted from scratch against its two hulls as trimmed by
// the planes placed before it: a part's later planes then keep the side its earlier ones kept,
// where independent pairwise planes may each keep another side (many hulls through one region;
// doc/shell.md, "Three starts"). Returns the number of pairs fitted.
std::size_t place_constructively(const PairSet& set, const std::vector<double>& vol, std::vector<CutPlane>& planes) {
  std::vector<char> placed(set.size(), 0), trimmed(set.parts(), 0), fitted(set.size(), 0);
  // The larger hulls' pairs first: the smaller hulls then fit around their planes.
  std::vector<std::size_t> order(set.size());
  std::iota(order.begin(), order.end(), 0);
  auto larger = [&](std::size_t q) { return std::max(vol[set[q].i], vol[set[q].j]); };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return larger(x) > larger(y); });
  set.in_waves(order, [&](std::size_t p) {
    const std::size_t i = set[p].i, j = set[p].j;
    if (trimmed[i] || trimmed[j]) {
      ConvexPolytope a = set.trimmed_except(planes, i, p, &placed), b = set.trimmed_except(planes, j, p, &placed);
      if (!a.empty() && !b.empty()) {
        // Even a hull the placed planes barely trimmed gets a new fit: between two equal
        // hulls, that trim is what decides which one the plane cuts.
        planes[p] = fit_cut_plane(set.problem(p, std::move(a), std::move(b)), set.options(p)).plane;
        fitted[p] = 1;
      } else if (!a.empty() || !b.empty()) {
        // One side is gone already: the plane keeps the whole overlap for the other.
        const Eigen::Vector3d nrm = planes[p].normal;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const auto& v : set[p].region.vertices) lo = std::min(lo, nrm.dot(v)), hi = std::max(hi, nrm.dot(v));
        if (lo <= hi) planes[p].offset = a.empty() ? lo : hi;
      }
    }  // else both hulls are still whole: the pairwise plane is that fit already
    placed[p] = 1;
    trimmed[i] = trimmed[j] = 1;
  });
  return static_cast<std::size_t>(std::count(fitted.begin(), fitted.end(), 1));
}

SweepRun run_sweeps(const PairSet& set, const std::vector<double>& vol, double scale, std::vector<CutPlane> planes,
                    SweepStart start, const SweepOptions& opt, const StageProgress& progress) {
  SweepRun run;
  run.report.start = start;
  const bool refit_reshaped = start == SweepStart::refit_reshaped;
  if (start == SweepStart::constructive) run.report.refits = place_constructively(set, vol, planes);
  std::vector<std::size_t> index_order(set.size());
  std::iota(index_order.begin(), index_order.end(), 0);
  // A pair's refit depends only on the planes of its two parts: skip it while none of them
  // changed since its last fit (the fit is deterministic, so the answer would be the same).
  std::vector<std::size_t> version(set.parts(), 0);
  std::vector<std::pair<std::size_t, std::size_t>> fitted_at(set.size(), {~std::size_t(0), ~std::size_t(0)});
  for (int s = 0; s < opt.max_sweeps; ++s) {
    // Per pair, summed in pair order afterwards: the same bits as one pair after the other.
    std::vector<double> pair_gain(set.size(), 0.0);
    std::vector<char> refit(set.size(), 0);
    const std::string stage = "sweep " + std::to_string(s + 1);
    set.in_waves(index_order, [&](std::size_t p) {
      const std::size_t i = set[p].i, j = set[p].j;
      if (set.pairs_of(i).size() + set.pairs_of(j).size() <= 2) return;  // nothing else trims them
      const std::pair<std::size_t, std::size_t> now{version[i], version[j]};
      if (fitted_at[p] == now) return;
      fitted_at[p] = now;
      ConvexPolytope a = set.trimmed_except(planes, i, p), b = set.trimmed_except(planes, j, p);
      if (a.empty() || b.empty()) return;
      const bool reshaped = s == 0 && (volume(a) < (1 - kReshaped) * vol[i] || volume(b) < (1 - kReshaped) * vol[j]);
      CutProblem prob = set.problem(p, std::move(a), std::move(b));
      prob.current_overlap = tagged_intersection(prob.a, prob.b);  // once for both calls
      CutResult cur = evaluate_cut_plane(prob, planes[p], set.options(p).lambda);
      CutOptions o = set.options(p);
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
      if (start == SweepStart::pairwise && progress) progress(stage, done, set.size());  // one start reports
    });
    double gain = 0;
    for (double g : pair_gain) gain += g;
    run.report.refits += static_cast<std::size_t>(std::count(refit.begin(), refit.end(), 1));
    run.report.sweeps = s + 1;
    run.report.gains.push_back(scale > 0 ? gain / scale : 0.0);
    if (gain <= opt.tolerance * scale) break;
  }
  run.planes = std::move(planes);
  return run;
}

}  // namespace

std::vector<CutPlane> fit_pair_planes(const std::vector<ConvexPolytope>& hulls, const std::vector<HullPair>& pairs,
                                      const CutOptions& cut, const StageProgress& progress) {
  const PairSet set(hulls, pairs, cut);
  std::vector<CutPlane> planes(pairs.size());
  // Each fit reads only the hulls and the overlap regions and has its own seed.
  std::mutex progress_lock;
  std::size_t done = 0;
  parallel_for(pairs.size(), [&](std::size_t p) {
    planes[p] = fit_cut_plane(set.problem(p, hulls[pairs[p].i], hulls[pairs[p].j]), set.options(p)).plane;
    std::lock_guard<std::mutex> guard(progress_lock);
    if (progress) progress("cut planes", ++done, pairs.size());
  });
  return planes;
}

std::vector<CutPlane> refine_cut_planes(const std::vector<ConvexPolytope>& hulls, const std::vector<HullPair>& pairs,
                                        std::vector<CutPlane> planes, const CutOptions& cut,
                                        const SweepOptions& opt, SweepReport* report, const StageProgress& progress) {
  if (report) *report = SweepReport{};
  if (cut.method != CutMethod::exact && cut.method != CutMethod::full) return planes;
  const PairSet set(hulls, pairs, cut);
  std::vector<double> vol(hulls.size());
  double scale = 0;
  for (std::size_t i = 0; i < hulls.size(); ++i) scale += vol[i] = volume(hulls[i]);

  // Warm-started polishing keeps each plane near its pairwise fit. Where the other planes
  // reshape a pair's hulls, a second start re-fits those pairs from scratch in its first sweep;
  // the start that keeps more volume wins (doc/shell.md, "Two starts").
  bool two_starts = false;
  if (opt.second_start && cut.method == CutMethod::full && !opt.global_sweeps)
    for (std::size_t p = 0; p < pairs.size() && !two_starts; ++p)
      for (std::size_t part : {pairs[p].i, pairs[p].j})
        if (set.pairs_of(part).size() > 1 && volume(set.trimmed_except(planes, part, p)) < (1 - kReshaped) * vol[part])
          two_starts = true;
  std::vector<SweepStart> starts = {SweepStart::pairwise};
  if (two_starts) starts.push_back(SweepStart::refit_reshaped);
  if (two_starts && opt.constructive_start && set.kept_volume(planes) <= (1 - kConstructive) * scale)
    starts.push_back(SweepStart::constructive);

  // The starts are independent, so they run side by side; the costliest first: with three
  // starts on two threads, the other two share a thread.
  std::vector<SweepRun> runs(starts.size());
  parallel_for(runs.size(), [&](std::size_t k) {
    const std::size_t r = runs.size() - 1 - k;
    runs[r] = run_sweeps(set, vol, scale, planes, starts[r], opt, progress);
  });
  std::size_t win = 0;
  double win_kept = set.kept_volume(runs[0].planes);
  for (std::size_t k = 1; k < runs.size(); ++k) {
    if (runs[k].report.refits == 0) continue;  // the same planes as the first start
    const double kept = set.kept_volume(runs[k].planes);
    if (kept > win_kept) win = k, win_kept = kept;
  }
  if (report) *report = runs[win].report;
  return std::move(runs[win].planes);
}

}  // namespace dcshell
