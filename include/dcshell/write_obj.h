// Stage "export": Wavefront OBJ with round-trip precision, so what is certified in memory is
// exactly what a reader gets back.
#pragma once
#include <ostream>
#include <string>

#include "dcshell/kernel.h"

namespace dcshell {

/// Writes the mesh's vertices ("%.17g") and faces. `object_name` non-empty adds an `o` line;
/// `index_offset` shifts face indices, for several objects in one file (OBJ indices are global).
void write_obj(std::ostream& os, const Mesh& mesh, const std::string& object_name = "", std::size_t index_offset = 0);

}  // namespace dcshell
