// Shared helpers for the core tests: small meshes built in code and temporary files.
#pragma once
#include <unistd.h>

#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "dcshell/kernel.h"

namespace dcshell::test {

inline std::vector<Point3> box_points(double x0, double y0, double z0, double x1, double y1, double z1) {
  return {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}, {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}};
}

/// Text of an OBJ box (quads, outward).
inline std::string box_obj(double x0, double y0, double z0, double x1, double y1, double z1) {
  std::string s;
  for (const auto& p : box_points(x0, y0, z0, x1, y1, z1))
    s += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  s += "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  return s;
}

/// A fresh temporary directory, removed at scope exit.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    static int counter = 0;
    path = std::filesystem::temp_directory_path() /
           ("dcshell-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& content) const {
    auto p = path / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << content;
    return p.string();
  }
};

inline bool shared_data_available() { return std::filesystem::is_directory(DCSHELL_SHARED_DATA); }

// Precondition of the tests on ../shared/data. A plain function, not a lambda: copying an empty
// lambda into the decorator's boost::function trips GCC 12's -Wuninitialized.
inline boost::test_tools::assertion_result shared_data_present(boost::unit_test::test_unit_id) {
  return shared_data_available();
}

}  // namespace dcshell::test
