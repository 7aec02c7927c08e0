// Cut-plane method "svm": a linear soft-margin SVM separating points sampled inside two shells.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "dcshell/convex_polytope.h"
#include "dcshell/cut_plane.h"

namespace dcshell {

/// `count` points uniform in the polytope (tetrahedral fan from the vertex mean, tetrahedron
/// chosen by volume). Uses only raw rng() output, so results are identical on every platform,
/// and does not depend on the order of the polytope's vertices and faces.
std::vector<Eigen::Vector3d> sample_polytope(const ConvexPolytope& p, std::size_t count, std::mt19937_64& rng);

/// Linear soft-margin SVM (hinge loss, penalty c, bias regularised like LIBLINEAR) solved by
/// dual coordinate descent on features centred and scaled to unit RMS radius. Returns the
/// hyperplane with unit normal pointing from `negative` toward `positive`.
CutPlane linear_svm(const std::vector<Eigen::Vector3d>& negative, const std::vector<Eigen::Vector3d>& positive,
                    double c, std::uint64_t seed);

/// SVM plane between `samples` points drawn in a \ b and b \ a (the overlap's points belong to
/// both classes and only add noise; counts proportional to volume, at least 16 each). When
/// either difference has less than 1% of its hull's volume (nested hulls), the points are
/// drawn in the whole of a and b. Normal oriented from a toward b.
/// `overlap_volume`: vol(a ∩ b) when the caller knows it (computed otherwise).
CutPlane svm_cut_plane(const ConvexPolytope& a, const ConvexPolytope& b, double c, std::size_t samples,
                       std::uint64_t seed, std::optional<double> overlap_volume = std::nullopt);

}  // namespace dcshell
