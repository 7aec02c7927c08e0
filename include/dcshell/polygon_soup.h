// Plain polygon soup as read from a mesh file, before any topology is built.
#pragma once
#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace dcshell {

struct PolygonSoup {
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<std::size_t>> faces;  ///< indices into points, >= 3 each
  /// OBJ `o`/`g` group of each face (index into group_names); empty when the file has no groups.
  std::vector<std::size_t> face_group;
  std::vector<std::string> group_names;
};

/// Faces grouped by connected component (faces sharing a vertex index are connected), each
/// group in face order, groups in order of their first face.
std::vector<std::vector<std::size_t>> soup_components(const PolygonSoup& soup);

}  // namespace dcshell
