// Fold selection: which of a shell's overlap-free nets to return, by its folding check
// (doc/fold_check.md). The stages run in this order, each only while the work budget and the
// check count last:
//   1. the search's nets within the slack, best score first (`check_ranked`);
//   2. fresh trees of the heuristics past the search's attempts (`fresh_trees`);
//   3. nets set aside undecided, re-checked with what is left (`recheck_deferred`);
//   4. when none verified, the nets within the wider fallback slack (`fallback`);
//   5. when a net verified but scores worse than the best, fresh trees that beat it
//      (`improve`), then better nets that were set aside (`recheck_better`);
//   6. cut length: edge-swap descent from the verified net (`descend_by_length`,
//      fold_descent.cpp).
// Deterministic: the budget counts work units (pieces placed, faces decoded), never time.
#pragma once
#include <optional>
#include <set>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "dcshell/fold_check.h"
#include "dcshell/net.h"
#include "dcshell/unfold.h"
#include "unfold/unfold_internal.h"

namespace dcshell::unfold_detail {

/// a + b for budgets >= 0, saturating at the cap scaled_fold_work uses (no overflow).
long long add_work(long long a, long long b);

/// One edge swap of a cut tree: fold the cut group `cut` and cut the folded group `fold` on the
/// cycle that closes (the tree stays a spanning tree), shortening the cut by `gain`.
struct LengthSwap {
  int cut = -1, fold = -1;
  double gain = 0;
};

/// The swap of the tree `folded` (per group, 1 = folded) that shortens its cut most, skipping
/// the (cut, fold) pairs in `tabu`; none when no swap shortens it.
std::optional<LengthSwap> best_length_swap(const ShellGraph& g, const std::vector<char>& folded,
                                           const std::set<std::pair<int, int>>& tabu);

/// Per face, the part of the facet graph it lies in when only the groups folded in both trees
/// join facets: two faces of one part are joined by the same hinges in both nets, so their
/// relative motion is the same (FoldCheckOptions::proved_group).
std::vector<int> shared_parts(const ShellGraph& g, const std::vector<char>& a, const std::vector<char>& b);

class FoldSelection {
 public:
  /// `ranked`: the candidates in score order (the GA's best first when it ran); `evaluated`: every
  /// tree the search tried (they are not tried again as fresh trees); `ref`: the normalisation
  /// reference of the scores. `st` receives the checks, attempts and the returned net's result.
  FoldSelection(const ShellGraph& g, const SearchGraph& sg, const UnfoldOptions& options,
                const std::vector<Candidate>& ranked, const std::vector<Candidate>& evaluated,
                const NetMetrics& ref, UnfoldStats& st);

  /// Runs the stages with `checks` (> 0) checks; true when some net was checked, which is then
  /// `net()` (verified when st.fold.verified).
  bool run(int checks);
  Net& net() { return net_; }

 private:
  struct Deferred {  // undecided on its first pass: out of budget (t reached) or end unproved (t = -1)
    Genome genome;
    std::string heuristic;
    double t;
    double score;
  };
  struct Spare {  // overlap-free but outside the current slack
    Genome genome;
    std::string heuristic;
    double score;
  };
  struct Kept {  // the returned net and its report, to go back to
    Net net;
    NetMetrics result;
    FoldCheckResult fold;
    std::string heuristic;
    Genome genome;
  };

  double score(const NetMetrics& m) const { return objective_score(m, ref_, options_.objective); }
  double returned_score() const { return score(st_.result); }
  bool within_slack(const NetMetrics& m) const { return m.overlapping_pairs == 0 && score(m) <= max_score_; }
  long long first_budget() const { return std::min(first_work_, work_); }

  /// Checks one net (unless it overlaps or, once a net is kept, lies outside the slack) and
  /// keeps it when it is the first or verifies; true when it verifies. `first_pass`: screened by
  /// sampled states and its path's end first, set aside when undecided. `proved`: groups of
  /// faces whose pairs are already proved (the descent).
  bool check(const Genome& genome, const std::string& heuristic, long long budget, bool first_pass,
             const std::vector<int>* proved = nullptr);
  /// A fresh tree of heuristic h at the current attempt number, decoded and evaluated (charged
  /// to the budget); none when its tree was seen before.
  std::optional<NetMetrics> fresh_tree(UnfoldHeuristic h, Genome& w);

  void check_ranked();
  void fresh_trees(int max_checks);
  void recheck_deferred();
  void fallback();
  void improve();
  void recheck_better();
  void descend_by_length();  // fold_descent.cpp
  bool descend(bool single, int max_checks);
  Kept keep() const { return Kept{net_, st_.result, st_.fold, st_.heuristic, verified_genome_}; }
  void restore(const Kept& k);
  void report_first_contact();

  const ShellGraph& g_;
  const SearchGraph& sg_;
  const UnfoldOptions& options_;
  const std::vector<Candidate>& ranked_;
  const NetMetrics& ref_;
  UnfoldStats& st_;

  int checks_ = 0;  ///< checks per stage (UnfoldOptions::fold_candidates)
  long long work_ = 0;
  long long first_work_ = 0;
  std::unordered_set<std::uint64_t> seen_;
  std::vector<Deferred> deferred_;
  std::vector<Spare> spare_;
  double best_score_ = 0;  ///< the best overlap-free candidate's score
  double max_score_ = 0;   ///< nets scoring above it are not checked (the current slack)
  Net net_;
  bool have_ = false;
  bool done_ = false;          ///< a net verified
  Genome verified_genome_;     ///< the tree of the returned net, once one verified
  bool refuted_early_ = false; ///< st_.fold is a sampled state or the end screen, not the check's first contact
  std::optional<std::vector<Eigen::Vector3d>> preferred_;  ///< the shell's preferred directions, once needed
  int attempt_ = 1;            ///< the next fresh trees' attempt number
  int overlap_free_[4] = {0, 0, 0, 0};  ///< overlap-free fresh trees per heuristic
};

}  // namespace dcshell::unfold_detail
