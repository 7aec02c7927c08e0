// A separating plane between two shells, as plain data.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace dcshell {

/// The plane normal·x = offset. By convention the shell of the *first* part of a pair keeps
/// normal·x <= offset and the second keeps normal·x >= offset. Coefficients are doubles, so the
/// plane is exactly representable and the exact trim and certification use it as is.
struct CutPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;

  /// Signed value normal·x - offset (floating point; exact tests convert to Epeck).
  double eval(const Eigen::Vector3d& x) const { return normal.dot(x) - offset; }
  /// The same plane seen from the other side of the pair.
  CutPlane flipped() const { return {-normal, -offset}; }
};

}  // namespace dcshell
