// Stage "load": a composite shape's parts from files.
#pragma once
#include <string>
#include <vector>

#include "dcshell/kernel.h"

namespace dcshell {

struct Part {
  std::string name;    ///< e.g. "cow2_003.obj" or "yoshi-sep.obj#7" (component) or "model.obj#arm" (group)
  std::string source;  ///< the file it came from
  std::vector<Point3> points;  ///< vertices referenced by its faces
};

struct LoadPartsOptions {
  /// A part whose hull volume is below this fraction of the cube of the whole shape's bounding
  /// box diagonal is "tiny": warned about and skipped (it cannot carry a meaningful shell).
  double tiny_volume_fraction = 1e-12;
};

/// Reads a composite shape. Several files: one part per file. One file: its OBJ `o`/`g` groups
/// when it has more than one, otherwise its connected components. Directories expand to their
/// mesh files in name order. Flat (coplanar, < 4 points) or tiny parts are skipped with a warning
/// naming the file and part, appended to `warnings`. Throws InputError on bad files or when no
/// part is left.
std::vector<Part> load_parts(const std::vector<std::string>& inputs, std::vector<std::string>& warnings,
                             const LoadPartsOptions& options = {});

}  // namespace dcshell
