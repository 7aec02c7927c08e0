// A net: the unfolding of a convex triangle shell into the plane, as plain data.
// Produced by unfold.h, consumed by the overlap check, the folding check and the sheet writer.
#pragma once
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace dcshell {

struct Net {
  /// The shell, as triangles (outward, counter-clockwise), in the order faces are listed.
  std::vector<Eigen::Vector3d> shell_vertices;
  std::vector<std::array<int, 3>> shell_faces;

  /// 2D corner positions of net face f: corners[f][k] is shell vertex shell_faces[f][k].
  /// Faces keep their orientation (counter-clockwise in the plane), never mirrored.
  std::vector<std::array<Eigen::Vector2d, 3>> corners;

  /// Cut tree (spanning tree of the dual graph): parent face of f, -1 for the root.
  std::vector<int> parent;

  /// Every shell edge once: its two shell vertices, the faces on each side (f0 holds the edge as
  /// v0->v1), whether it is folded (a tree edge) or cut, and its dihedral fold angle in radians
  /// (pi - interior dihedral; 0 for coplanar faces). On a convex shell every fold is the same
  /// kind seen from outside; `mountain` records which, seen from the printed side.
  struct Edge {
    int v0 = -1, v1 = -1, f0 = -1, f1 = -1;
    bool fold = false;
    bool mountain = true;
    double fold_angle = 0.0;
  };
  std::vector<Edge> edges;

  std::string name;  ///< e.g. "shell_003"
};

}  // namespace dcshell
