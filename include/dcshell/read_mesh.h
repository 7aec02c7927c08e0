// Stage "load": reading and validating mesh files (OBJ, OFF, PLY, STL).
#pragma once
#include <string>

#include "dcshell/kernel.h"
#include "dcshell/polygon_soup.h"

namespace dcshell {

/// Reads a mesh file as a polygon soup and validates it: the file exists and is readable,
/// the format is known (by extension), every line parses, coordinates are finite and of
/// sane magnitude (|x| <= 1e12), face indices are in range, and there is at least one face.
/// Throws InputError naming the file (and line number for OBJ) on any problem.
PolygonSoup read_polygon_soup(const std::string& path);

/// Reads a closed surface mesh (e.g. a convex shell) into a Surface_mesh.
/// Throws InputError when the file is bad or the faces do not form a valid
/// oriented 2-manifold (non-manifold soup, inconsistent orientation).
Mesh read_mesh(const std::string& path);

/// Reads every object of a mesh file: one mesh per OBJ `o`/`g` group when the file has more
/// than one (V-HACD and similar tools write all hulls into one OBJ), otherwise one per
/// connected component. Names are "file", "file#group" or "file#k". Same validation as read_mesh.
std::vector<std::pair<std::string, Mesh>> read_mesh_objects(const std::string& path);

/// Reads a set of meshes given on the command line: directories expand to their mesh files,
/// and every file contributes its objects (read_mesh_objects). Names as in read_mesh_objects.
std::vector<std::pair<std::string, Mesh>> read_mesh_set(const std::vector<std::string>& inputs);

/// True for the file names dcshell reads as meshes (.obj .off .ply .stl, case-insensitive).
bool is_mesh_file_name(const std::string& path);

/// Expands command-line inputs: a directory means all mesh files in it (.obj .off .ply .stl,
/// case-insensitive; hidden files excluded), in name order, except a `shells.obj` beside `shell_*` files (the combined
/// copy a `dcshell shell` run writes for viewers); a file is kept as is. Throws InputError for a missing path
/// or a directory without mesh files.
std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs);

}  // namespace dcshell
