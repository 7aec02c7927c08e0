// Writes the convex hull of every part of composite models as one OBJ per part, the same hulls
// tools/bench_unfold builds in memory (load_parts + convex_hull_mesh), so that tools which read
// files (Blender's paper-model add-on, tools/run_blender_baseline.sh) unfold exactly the same
// meshes as our benchmark. Output: OUT/<Model>__<part stem>.obj (vertices with %.17g).
//
// usage: write_part_hulls --out DIR MODEL_DIR...
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "dcshell/convex_hull.h"
#include "dcshell/load_parts.h"
#include "dcshell/write_obj.h"

namespace fs = std::filesystem;
using namespace dcshell;

int main(int argc, char** argv) {
  std::string out;
  std::vector<std::string> models;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--help" || a == "-h") {
      std::cout << "usage: write_part_hulls --out DIR MODEL_DIR...\n";
      return 0;
    } else models.push_back(a);
  }
  if (out.empty() || models.empty()) {
    std::cerr << "usage: write_part_hulls --out DIR MODEL_DIR...\n";
    return 2;
  }
  try {
    fs::create_directories(out);
    for (const auto& m : models) {
      std::vector<std::string> warnings;
      auto parts = load_parts({m}, warnings);
      for (const auto& w : warnings) std::cerr << "warning: " << w << "\n";
      const std::string model = fs::path(m).lexically_normal().filename().empty()
                                    ? fs::path(m).lexically_normal().parent_path().filename().string()
                                    : fs::path(m).lexically_normal().filename().string();
      for (const auto& p : parts) {
        Mesh hull = convex_hull_mesh(p.points);
        if (hull.is_empty()) {
          std::cerr << "warning: " << p.name << ": flat hull, skipped\n";
          continue;
        }
        // Part names are file names ("cow2_003.obj") or "file#component": keep them readable.
        std::string stem = fs::path(p.name).stem().string();
        for (char& c : stem)
          if (c == '#' || c == '/' || c == ' ') c = '_';
        fs::path file = fs::path(out) / (model + "__" + stem + ".obj");
        std::ofstream os(file);
        write_obj(os, hull);
        if (!os) {
          std::cerr << "write_part_hulls: cannot write " << file << "\n";
          return 1;
        }
        std::cout << file.string() << " " << hull.number_of_faces() << "\n";
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "write_part_hulls: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
