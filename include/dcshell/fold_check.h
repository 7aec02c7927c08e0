// Continuous folding check: every fold angle goes linearly from 0 (the flat net) to its shell
// angle (a straight line in configuration space, t in [0, 1]); is the motion free of
// self-intersection? Method and argument: doc/fold_check.md.
//
// Faces joined by (near) flat folds move as one rigid planar piece; each piece is represented by
// the convex hull of its net corners (which contains it). Every pair of pieces is proved
// disjoint over the whole path by one of:
//  - hinge: pieces turning about one common line (a fold, or two common fixed corners) on
//    opposite sides of it never meet off that line while the turn stays below pi;
//  - conservative advancement: from state t, two pieces at distance d cannot meet before
//    t + d / (bound on their relative speed) (levers grow with the travel, accounted for);
//  - cone test: pieces that keep a common corner v lie in their angular wedges at v; while the
//    wedges' arcs on the unit sphere around v are apart, the pieces meet only at v; the arcs
//    advance by arc distance / (sum of the angular speeds between them);
//  - end window: pieces that touch in the folded shell are separated near t = 1 by the plane of
//    one of them: every other corner stays strictly inside it, proved for the touching corners
//    from their exact velocity at t = 1 and a bound on the acceleration (Taylor, order 2);
//  - plane advancement: the same from the current state, for pairs at (nearly) zero distance.
// Distance and cone steps also use the exact relative velocity now plus an acceleration bound.
// It never verifies a path along which two pieces come closer than `tolerance` x net size (or
// poke through a separating plane by more than that) other than at corners they share on their
// fold lines. It reports the first state where it cannot proceed, with the two faces (or, for a
// pair that can never be proved up to t = 1, the state where its steps got short).
#pragma once
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "dcshell/net.h"

namespace dcshell {

struct FoldCheckOptions {
  /// Smallest step; a pair that forces a smaller one is reported (not verified).
  double min_step = 1e-9;
  int max_steps = 100000;
  /// Work budget in piece placements (each step places every rigid piece once: steps x pieces);
  /// 0 = none. A count, not a time: the same nets pass or run out on every machine.
  long long max_work = 0;
  /// With max_work: the candidate pairs the steps examine, summed over the steps, are bounded
  /// too, by pairs_per_work x max_work (0: not bounded); past that the check stops undecided
  /// (out_of_budget). On a net of thousands of one-triangle pieces whose travel boxes all meet
  /// (a 2,000-point sphere hull: 200,000 pairs a step) the pairs are what costs, not the
  /// placements. The unfolder bounds its candidates' checks so (25).
  double pairs_per_work = 0;
  /// Corners tested against separating planes (plane advancement and end windows) per unit of
  /// FoldCheckResult::work (0: not counted). Counted, not bounded: a check that needs them
  /// keeps its verdict, but a caller's budget pays for them (pieces with hundreds of corners at
  /// contact cost hundreds of millions in one step).
  double corners_per_work = 0;
  /// Contact tolerance relative to the net size (diagonal of its bounding box): closer than this
  /// counts as a collision; it also absorbs floating-point rounding of the folded coordinates.
  double tolerance = 1e-9;
  /// Second-order steps (distance and cone) from the pieces' exact relative velocity, and the
  /// early stop at a pair that can never be proved up to t = 1 (doc/fold_check.md). Off:
  /// first-order steps only and no early stop, for comparison (tests); the verdicts should agree.
  bool second_order = true;
  /// Nets with more rigid pieces than this are reported undecided (out_of_budget, t = 0) without
  /// a check: max_work bounds the stepping, not the set-up, whose per-piece paths to the root
  /// grow faster than the piece count (100,000 pieces: 90 s and 10 GB). 0 = no limit.
  int max_pieces = 20000;
  /// Check only the end of the path, t in [t_begin, 1] (0: the whole path; clamped to [0, 1],
  /// not finite: 0). A verdict on the net needs the whole path; a conclusive failure after
  /// t_begin refutes it in a few steps, where the whole check would first step through the path
  /// before it (what end_first does).
  double t_begin = 0;
  /// Prove the end of the path, t in [1 - end_proof, 1], on its own first, from the state at
  /// 1 - end_proof (0: not). When it holds, the path from t_begin is checked only up to that
  /// state: near t = 1 the pieces close up, and a pass arriving there from t_begin can crawl and
  /// fail to prove what the pass from 1 - end_proof proved (rare: one returned net of the shared
  /// sets' DC-shells). When it does not hold, the path from t_begin is checked up to 1 exactly
  /// as without it (the pairs' set-up is reused), after the end's steps were spent for nothing;
  /// so it only pays where the end is screened anyway (end_first, the unfolder's candidates).
  /// With the same end_proof, a verdict is the same whether or not the end was screened.
  double end_proof = 0;
  /// Check t in [1 - end_first, 1] first (0: not; replaces end_proof). When that fails
  /// conclusively, that failure is the result (refuted_at_end: the net can never be verified,
  /// and the steps before the end were not checked); else as end_proof. The unfolder's
  /// candidates are checked so (UnfoldOptions::fold_screen).
  double end_first = 0;
  /// With end_first: when the end fails but not conclusively, stop there too (undecided_at_end)
  /// instead of checking the path from t_begin. Such a net almost never verifies from t_begin
  /// (2 of 282 on the shared sets, doc/fold_check.md), and its whole check is the costly part; a
  /// caller with other candidates sets the net aside and checks it in full only if none verifies.
  bool end_first_defers = false;
  /// Per net face, a group id, or empty: two rigid pieces whose faces all lie in the same group
  /// (id >= 0) are taken as proved apart and never examined. For a caller that proved every pair
  /// of another net of the same shell, and whose groups are the parts both cut trees share: the
  /// hinges between two faces of one part are the same in both nets, so their relative motion
  /// is too (the unfolder's edge-swap descent; doc/fold_check.md).
  std::vector<int> proved_group;
};

struct FoldCheckResult {
  bool verified = false;  ///< the whole path t in [0, 1] is free of self-intersection
  int steps = 0;
  bool out_of_budget = false;  ///< stopped by max_steps / max_work, not by a contact (undecided)
  double t = 1;               ///< where the check stopped (1 when verified)
  int face_a = -1, face_b = -1;  ///< the colliding (or too close) faces when not verified
  std::string message;        ///< why not verified; empty when verified
  int pieces = 0;             ///< rigid pieces (faces joined by flat folds)
  int pairs = 0;              ///< pairs of pieces examined (candidates at some step; with end_first, the end's too)
  long long pair_tests = 0;   ///< candidate pairs summed over all steps (with end_first, the end's too)
  long long corner_tests = 0; ///< corners tested against separating planes (likewise)
  /// The budget this check used: steps x pieces (both passes with end_first), pair_tests /
  /// pairs_per_work or corner_tests / corners_per_work, whichever is most.
  long long work = 0;
  /// Not verified, and no check of this net can verify it, whatever its start (t_begin) and
  /// steps: the two faces cross at t by more than 1e-7 x net size, or their pieces touch in the
  /// folded shell where no end window can prove the approach. Otherwise a failure may be the
  /// check's own limit at the state it stepped to (a check from t = 0 can still verify the net
  /// when t_begin > 0).
  bool conclusive = false;
  /// With end_first: the end of the path failed conclusively and is the result; t, the faces and
  /// the message are that failure's, not the first contact along the path.
  bool refuted_at_end = false;
  int end_first_steps = 0;  ///< with end_first or end_proof: the steps of the end's check (not in steps)
  /// With end_first_defers: the end of the path failed, not conclusively, and the path before it
  /// was not checked (undecided, like out_of_budget; t, faces and message are the end's failure).
  bool undecided_at_end = false;
};

FoldCheckResult check_folding(const Net& net, const FoldCheckOptions& options = {});

/// Rigid pieces of the net's motion: faces joined by folds flatter than the check's rigid angle
/// (1e-4 rad) move as one (FoldCheckResult::pieces, without running the check).
int rigid_pieces(const Net& net);

/// Refutation only, much cheaper than check_folding on a net that collides: the states
/// t = 1 - (k / samples)^2 (k = 1 .. samples - 1, densest near the folded end) of the same motion, and the first of them in which
/// an edge of one face passes through the interior of another face of a different rigid piece,
/// clear of its plane and its sides by more than `margin` x net size (a sure collision: rounding
/// is far below that). Returns that state as a not-verified result (steps = states sampled);
/// nothing when no sampled state collides, which proves nothing about the states in between.
/// `pair_tests`, when given, receives the face pairs whose boxes met, summed over the states.
std::optional<FoldCheckResult> find_sampled_collision(const Net& net, int samples = 32, double margin = 1e-7,
                                                      long long* pair_tests = nullptr);

/// Net faces moved to folding state t (0 = flat net at z = 0, 1 = folded shell, in net
/// coordinates): corners of each face, in shell order.
std::vector<std::array<Eigen::Vector3d, 3>> folded_faces(const Net& net, double t);

}  // namespace dcshell
