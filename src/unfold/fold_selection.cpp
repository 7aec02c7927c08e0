// Fold selection (fold_selection.h): the first overlap-free net whose folding path is verified;
// else the best one. Candidates come cheapest first: the search's nets in score order (already
// evaluated), then fresh trees of the heuristics (more directions, jitters, random weights) as
// long as the work budget lasts. Each net gets a small share of the budget: a failing check
// usually stops at its first contact after few steps, but an undecided one (out of steps) is set
// aside and re-checked with the rest of the budget when no net verifies or a worse one does.
#include "unfold/fold_selection.h"

#include <algorithm>
#include <iterator>
#include <limits>

namespace dcshell::unfold_detail {

namespace {

// Most nets whose straight-line fold collides are still interpenetrating just before the end
// (doc/fold_check.md, *Sampled refutation*): a few sampled states refute them for about one
// step's work, where the check would run to their first contact.
constexpr int kProbeStates = 16;
// Pairs examined per unit of budget, in a check (FoldCheckOptions::pairs_per_work, a bound) and in
// a probe (a cost).
constexpr double kPairsPerWork = 25;
// Corners tested against planes per unit of budget (FoldCheckOptions::corners_per_work). The
// shared sets' checks test up to 240 per unit of their own budget; the candidates of a hull of
// 600 random points on a cylinder up to 3,700, 0.35 s each: its shell took 10.4 s, now 2.2 s.
constexpr double kCornersPerWork = 1000;

const UnfoldHeuristic kFreshHeuristics[] = {UnfoldHeuristic::steepest, UnfoldHeuristic::flat,
                                            UnfoldHeuristic::min_perimeter, UnfoldHeuristic::random};
// Past the first attempts, a heuristic that has not given one overlap-free tree yet is tried
// only every period-th attempt: on the shells where fresh trees are needed at all, nearly all of
// them overlap, and steepest edge gave 35% of the overlap-free ones, min-perimeter 9%, flat 5%,
// random 1% (the shared sets' DC-shells, doc/fold_check.md).
const int kFreshPeriod[] = {1, 4, 2, 8};

}  // namespace

long long add_work(long long a, long long b) {
  constexpr long long cap = 1LL << 62;
  a = std::clamp(a, 0LL, cap), b = std::clamp(b, 0LL, cap);
  return a > cap - b ? cap : a + b;
}

FoldSelection::FoldSelection(const ShellGraph& g, const SearchGraph& sg, const UnfoldOptions& options,
                             const std::vector<Candidate>& ranked, const std::vector<Candidate>& evaluated,
                             const NetMetrics& ref, UnfoldStats& st)
    : g_(g), sg_(sg), options_(options), ranked_(ranked), ref_(ref), st_(st) {
  for (const auto& c : evaluated) seen_.insert(tree_hash(folded_groups(g, c.genome)));
  // A candidate worse than the best overlap-free net by more than the slack is not worth a check
  // (it would be returned only for its fold).
  best_score_ = std::numeric_limits<double>::infinity();
  for (const auto& c : ranked)
    if (c.metrics.overlapping_pairs == 0) best_score_ = std::min(best_score_, score(c.metrics));
  max_score_ = best_score_ * (1 + std::max(options.fold_slack, 0.0));
}

bool FoldSelection::run(int checks) {
  checks_ = checks;
  work_ = scaled_fold_work(options_.fold_work, g_.F.size());
  first_work_ = scaled_fold_work(options_.fold_first_work, g_.F.size());
  check_ranked();
  fresh_trees(checks_);
  recheck_deferred();
  fallback();
  improve();
  recheck_better();
  descend_by_length();
  // A fallback's net replaced by a better one may lie within the first slack after all.
  st_.fold_fallback = st_.fold_fallback && returned_score() > best_score_ * (1 + std::max(options_.fold_slack, 0.0));
  report_first_contact();
  return have_;
}

bool FoldSelection::check(const Genome& genome, const std::string& heuristic, long long budget, bool first_pass,
                          const std::vector<int>* proved) {
  const long long faces = static_cast<long long>(g_.F.size());
  NetMetrics m;
  Net candidate = finish_net(g_, genome, &m);
  work_ -= 8 + faces;
  if (m.overlapping_pairs != 0 || (have_ && !within_slack(m))) return false;
  // Only nets no sampled state refutes get the check. A sampled state places every face, a step
  // of the check every rigid piece: nets with more than 4 faces a piece (a finely triangulated
  // cube: 1,200 faces, 6 pieces; DC-shells have 1-3) are checked directly. The rest are screened
  // on the end of their path first (options.fold_screen): there the pieces close up, and a
  // conclusive failure refutes the net.
  std::optional<FoldCheckResult> hit;
  if (first_pass && faces <= 4LL * rigid_pieces(candidate)) {  // a deferred net was probed on its first pass
    long long probe_pairs = 0;
    hit = find_sampled_collision(candidate, kProbeStates, 1e-7, &probe_pairs);
    // Needle faces (hulls of points on a cone) make boxes that meet by the thousand: 144 pairs
    // per face and state on a 600-point cone, against at most 11 on the shared sets.
    work_ -= std::max<long long>((hit ? hit->steps : kProbeStates - 1) * faces,
                                 static_cast<long long>(static_cast<double>(probe_pairs) / kPairsPerWork));
  }
  FoldCheckResult fc;
  if (hit) {
    fc = *hit;
  } else {
    FoldCheckOptions fo;
    fo.max_work = std::max<long long>(budget, 1);
    // The candidates' checks on the shared sets examine up to 18 pairs per unit of budget; a
    // 2,000-point sphere hull's 55 (1.7 s a check, all undecided).
    fo.pairs_per_work = kPairsPerWork;
    fo.corners_per_work = kCornersPerWork;
    // The end is proved on its own (the same window): the pass from t = 0 stops where it begins.
    fo.end_proof = std::max(options_.fold_screen, 0.0);
    // A deferred net was screened on its first pass; one whose end the screen could not prove is
    // set aside, not checked from t = 0 (it nearly never verifies from there).
    if (first_pass) fo.end_first = options_.fold_screen, fo.end_first_defers = true;
    if (proved) fo.proved_group = *proved;
    fc = check_folding(candidate, fo);
    work_ -= fc.work;
    if (fc.refuted_at_end || fc.undecided_at_end) hit = fc;
  }
  ++st_.fold_checks;
  // Set aside: re-checked when no net verifies, those that got furthest first, and those whose
  // end failed last; or, when a worse net verifies, the better ones (recheck_better).
  if (first_pass && (fc.out_of_budget || fc.undecided_at_end))
    deferred_.push_back({genome, heuristic, fc.undecided_at_end ? -1.0 : fc.t, score(m)});
  if (!have_ || fc.verified) {
    net_ = std::move(candidate), st_.result = m, st_.fold = fc, st_.heuristic = heuristic, have_ = true;
    if (fc.verified) verified_genome_ = genome;
    refuted_early_ = hit.has_value();
  }
  return fc.verified;
}

void FoldSelection::check_ranked() {
  for (std::size_t i = 0; i < ranked_.size() && !done_ && st_.fold_checks < checks_ && work_ > 0; ++i) {
    const Candidate& c = ranked_[i];
    if (c.metrics.overlapping_pairs != 0) break;
    if (have_ && !within_slack(c.metrics)) {
      spare_.push_back({c.genome, c.heuristic, score(c.metrics)});  // the fallback's first candidates
      continue;
    }
    done_ = check(c.genome, c.heuristic, first_budget(), true);
  }
}

std::optional<NetMetrics> FoldSelection::fresh_tree(UnfoldHeuristic h, Genome& w) {
  if (!preferred_) preferred_ = preferred_directions(g_);
  w = heuristic_genome(g_, h, attempt_, options_.seed, *preferred_);
  auto folded = folded_groups(g_, w);
  if (!seen_.insert(tree_hash(folded)).second) return std::nullopt;
  work_ -= 8 + sg_.faces();
  return sg_.evaluate(folded);
}

void FoldSelection::fresh_trees(int max_checks) {
  // Attempt numbers past the search's, every heuristic in turn (only the ones that differ from
  // the trees seen so far cost a decode and an overlap test).
  for (; !done_ && st_.fold_checks < max_checks && work_ > 0 && attempt_ <= 4 * max_checks; ++attempt_)
    for (std::size_t k = 0; k < std::size(kFreshHeuristics); ++k) {
      if (done_ || st_.fold_checks >= max_checks || work_ <= 0) break;
      if (attempt_ > 4 && overlap_free_[k] == 0 && attempt_ % kFreshPeriod[k] != 0) continue;
      const UnfoldHeuristic h = kFreshHeuristics[k];
      Genome w;
      const auto evaluated = fresh_tree(h, w);
      if (!evaluated) continue;
      const NetMetrics& m = *evaluated;
      if (m.overlapping_pairs == 0) ++overlap_free_[k];
      if (!within_slack(m)) {
        if (m.overlapping_pairs == 0) spare_.push_back({std::move(w), to_string(h), score(m)});
        continue;
      }
      st_.attempts++;
      done_ = check(w, to_string(h), first_budget(), true);
    }
}

void FoldSelection::recheck_deferred() {
  // Undecided nets (out of budget, or an end the screen could not prove), the one that got
  // furthest first, with what is left.
  if (done_) return;  // kept for recheck_better
  std::stable_sort(deferred_.begin(), deferred_.end(), [](const Deferred& a, const Deferred& b) { return a.t > b.t; });
  for (std::size_t i = 0; i < deferred_.size() && !done_ && work_ > 0; ++i)
    done_ = check(deferred_[i].genome, deferred_[i].heuristic, work_, false);
  deferred_.clear();
}

void FoldSelection::fallback() {
  // No net within the slack folds. A net whose straight-line folding is proved beats a
  // better-scored one that collides, so the nets up to the wider fallback slack get what is left
  // of the budget plus a small one of their own, and as many checks again (the nets the slack
  // left out first, in score order, then fresh trees).
  if (done_ || options_.fold_fallback_slack <= options_.fold_slack) return;
  max_score_ = best_score_ * (1 + options_.fold_fallback_slack);
  work_ = add_work(work_, scaled_fold_work(options_.fold_fallback_work, g_.F.size()));
  std::stable_sort(spare_.begin(), spare_.end(), [](const Spare& a, const Spare& b) { return a.score < b.score; });
  const int max_checks = st_.fold_checks + checks_;
  for (std::size_t i = 0; i < spare_.size() && !done_ && st_.fold_checks < max_checks && work_ > 0; ++i)
    if (spare_[i].score <= max_score_) done_ = check(spare_[i].genome, spare_[i].heuristic, first_budget(), true);
  fresh_trees(max_checks);
  recheck_deferred();
  st_.fold_fallback = done_;
}

void FoldSelection::improve() {
  // A net verified but scores worse than the best overlap-free one (whose folds collide): fresh
  // trees of a few more attempt numbers that score better than it are checked, best first, as
  // many as attempts, and the first that verifies replaces it. The search's best is not the best
  // tree there is: on the triakis icosahedron (cut length) the nets within 0.3% of it collide,
  // the first ranked net that verifies is 12% longer, and a fresh min-perimeter tree 0.06%
  // shorter than the search's best folds.
  const int attempts = options_.fold_improve_attempts >= 0 ? options_.fold_improve_attempts
                       : options_.objective == UnfoldObjective::cut_length ? 8 : 0;
  if (!done_ || attempts <= 0) return;
  const double verified_score = returned_score();
  if (verified_score <= best_score_ * (1 + 1e-9)) return;
  std::vector<Spare> better;
  for (const int last = attempt_ + attempts; attempt_ < last && work_ > 0; ++attempt_)
    for (std::size_t k = 0; k < std::size(kFreshHeuristics) && work_ > 0; ++k) {
      Genome w;
      const auto m = fresh_tree(kFreshHeuristics[k], w);
      if (!m) continue;
      ++st_.attempts;
      const double s = score(*m);
      if (m->overlapping_pairs == 0 && s < verified_score) better.push_back({std::move(w), to_string(kFreshHeuristics[k]), s});
    }
  std::stable_sort(better.begin(), better.end(), [](const Spare& a, const Spare& b) { return a.score < b.score; });
  max_score_ = verified_score;
  const int max_checks = st_.fold_checks + attempts;
  for (std::size_t i = 0; i < better.size() && st_.fold_checks < max_checks && work_ > 0; ++i)
    if (check(better[i].genome, better[i].heuristic, first_budget(), true)) break;
}

void FoldSelection::recheck_better() {
  // A net verified, but nets scored better than it were set aside undecided (out of their first
  // budget) before it: best score first, each gets up to fold_recheck_work of what is left, so
  // the verified net returned is the best one examined where the budget allows. Nets whose end
  // screen failed are left out: their full check nearly never verifies (doc/fold_check.md,
  // session 24).
  if (!done_ || options_.fold_recheck_work <= 0 || deferred_.empty()) return;
  const long long recheck_work = scaled_fold_work(options_.fold_recheck_work, g_.F.size());
  const double returned = returned_score();  // after improve()
  std::stable_sort(deferred_.begin(), deferred_.end(), [](const Deferred& a, const Deferred& b) { return a.score < b.score; });
  for (std::size_t i = 0; i < deferred_.size() && work_ > 0; ++i) {
    if (deferred_[i].score >= returned) break;
    if (deferred_[i].t < 0) continue;
    if (check(deferred_[i].genome, deferred_[i].heuristic, std::min(work_, recheck_work), false)) break;
  }
  deferred_.clear();
}

void FoldSelection::restore(const Kept& k) {
  net_ = k.net, st_.result = k.result, st_.fold = k.fold, st_.heuristic = k.heuristic, verified_genome_ = k.genome;
  max_score_ = returned_score();
}

void FoldSelection::report_first_contact() {
  // No net verified and the one returned was refuted by a sampled state or the end screen: its
  // first contact, for the report, unless that check runs out (then the sampled collision stands).
  if (done_ || !refuted_early_) return;
  FoldCheckOptions fo;
  fo.max_work = std::max<long long>(first_work_, 1);
  fo.end_proof = std::max(options_.fold_screen, 0.0);
  FoldCheckResult fc = check_folding(net_, fo);
  if (!fc.out_of_budget) st_.fold = fc;
}

}  // namespace dcshell::unfold_detail
