// Loading composite shapes, and one test per class of bad input.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "dcshell/atomic_output.h"
#include "dcshell/error.h"
#include "dcshell/json.h"
#include "dcshell/load_parts.h"
#include "dcshell/read_mesh.h"
#include "test_util.h"

using namespace dcshell;
using dcshell::test::box_obj;
using dcshell::test::TempDir;

namespace {

// The error message must name the file and contain `what`.
void expect_input_error(const std::string& path, const std::string& what) {
  try {
    std::vector<std::string> w;
    load_parts({path}, w);
    BOOST_ERROR("no error for " << path);
  } catch (const InputError& e) {
    std::string msg = e.what();
    BOOST_TEST(msg.find(path) != std::string::npos, "message names the file: " << msg);
    BOOST_TEST(msg.find(what) != std::string::npos, "message says '" << what << "': " << msg);
    BOOST_TEST(msg.find('\n') == std::string::npos);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(load)

BOOST_AUTO_TEST_CASE(several_files_are_one_part_each) {
  TempDir t;
  t.write("d/a.obj", box_obj(0, 0, 0, 1, 1, 1));
  t.write("d/b.obj", box_obj(0.5, 0, 0, 1.5, 1, 1));
  t.write("d/notes.txt", "not a mesh");
  std::vector<std::string> w;
  auto parts = load_parts({(t.path / "d").string()}, w);
  BOOST_REQUIRE(parts.size() == 2u);
  BOOST_TEST(parts[0].name == "a.obj");
  BOOST_TEST(parts[1].name == "b.obj");
  BOOST_TEST(parts[0].points.size() == 8u);
  BOOST_TEST(w.empty());
}

BOOST_AUTO_TEST_CASE(one_file_connected_components_or_groups) {
  TempDir t;
  std::string two = box_obj(0, 0, 0, 1, 1, 1) + box_obj(2, 0, 0, 3, 1, 1);
  // Second box's face indices must follow the first's 8 vertices.
  std::string fixed;
  std::istringstream in(two);
  std::string line;
  int vcount = 0, fline = 0;
  while (std::getline(in, line)) {
    if (line[0] == 'v') ++vcount;
    if (line[0] == 'f' && ++fline > 6) {
      std::istringstream ls(line.substr(2));
      int i;
      line = "f";
      while (ls >> i) line += " " + std::to_string(i + 8);
    }
    fixed += line + "\n";
  }
  std::vector<std::string> w;
  auto comps = load_parts({t.write("c.obj", fixed)}, w);
  BOOST_TEST(comps.size() == 2u);
  BOOST_TEST(comps[1].name == "c.obj#1");
  // With groups, the groups are the parts even when connected.
  std::string grouped = "o first\n" + box_obj(0, 0, 0, 1, 1, 1) + "o second\nf 1 2 6\n";
  auto groups = load_parts({t.write("g.obj", grouped)}, w);
  // "second" is a single triangle: flat, so skipped with a warning naming it.
  BOOST_TEST(groups.size() == 1u);
  BOOST_TEST(groups[0].name == "g.obj#first");
  BOOST_REQUIRE(w.size() == 1u);
  BOOST_TEST(w[0].find("g.obj#second") != std::string::npos);
  BOOST_TEST(w[0].find("flat") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(open_part_is_kept_with_one_warning_per_file) {
  TempDir t;
  // A box without its last face: open, but its hull is a solid box.
  std::string box = box_obj(0, 0, 0, 1, 1, 1);
  box.erase(box.rfind("f "));
  std::vector<std::string> w;
  auto parts = load_parts({t.write("open.obj", box), t.write("closed.obj", box_obj(2, 0, 0, 3, 1, 1))}, w);
  BOOST_TEST(parts.size() == 2u);
  BOOST_REQUIRE(w.size() == 1u);
  BOOST_TEST(w[0].find("open.obj: 1 part(s) are open or non-manifold surfaces") != std::string::npos, w[0]);
}

BOOST_AUTO_TEST_CASE(tiny_part_is_warned_and_skipped) {
  TempDir t;
  t.write("d/big.obj", box_obj(0, 0, 0, 1000, 1000, 1000));
  t.write("d/tiny.obj", box_obj(0, 0, 0, 1e-5, 1e-5, 1e-5));
  std::vector<std::string> w;
  auto parts = load_parts({(t.path / "d").string()}, w);
  BOOST_TEST(parts.size() == 1u);
  BOOST_REQUIRE(w.size() == 1u);
  BOOST_TEST(w[0].find("tiny.obj") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(missing_file) { expect_input_error("/nonexistent/dir/x.obj", "no such file"); }

BOOST_AUTO_TEST_CASE(empty_file) {
  TempDir t;
  expect_input_error(t.write("e.obj", ""), "empty file");
}

BOOST_AUTO_TEST_CASE(malformed_vertex_line_with_line_number) {
  TempDir t;
  std::string p = t.write("m.obj", "v 0 0 0\nv 1 0 zero\n");
  expect_input_error(p, ":2: malformed vertex line");
}

BOOST_AUTO_TEST_CASE(nan_and_inf_coordinates) {
  TempDir t;
  expect_input_error(t.write("n.obj", "v 0 0 nan\n"), "NaN or infinite");
  expect_input_error(t.write("i.obj", "v inf 0 0\n"), "NaN or infinite");
}

BOOST_AUTO_TEST_CASE(absurd_coordinates) {
  TempDir t;
  expect_input_error(t.write("a.obj", "v 0 0 1e300\n"), "exceeds 1e12");
}

BOOST_AUTO_TEST_CASE(face_index_out_of_range) {
  TempDir t;
  expect_input_error(t.write("f.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), ":4: face index 9 out of range");
}

BOOST_AUTO_TEST_CASE(unknown_format_and_statement) {
  TempDir t;
  expect_input_error(t.write("x.xyz", "1 2 3\n"), "unknown mesh format");
  expect_input_error(t.write("s.obj", "v 0 0 0\nbogus 1\n"), "unknown OBJ statement");
}

BOOST_AUTO_TEST_CASE(obj_line_endings_bom_continuation_and_ignored_statements) {
  TempDir t;
  const std::string tet = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  std::string cr = tet, bom = "\xEF\xBB\xBF" + tet;
  for (auto& c : cr)
    if (c == '\n') c = '\r';
  const std::string cont = "v 0 0 0\nv 1 \\\n 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const std::string extra = "mg 1 0.5\nlod 2\nmaplib a.map\nusemap b\ncstype bezier\n" + tet;
  for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
           {"cr.obj", cr}, {"bom.obj", bom}, {"cont.obj", cont}, {"extra.obj", extra}}) {
    std::vector<std::string> w;
    auto parts = load_parts({t.write(name, text)}, w);
    BOOST_TEST(parts.size() == 1u, name);
    BOOST_TEST(parts[0].points.size() == 4u, name);
  }
  // Text after the coordinates that is not a number is a broken line, not ignored.
  expect_input_error(t.write("junk.obj", "v 0 0 0 junk\n"), ":1: malformed vertex line");
}

BOOST_AUTO_TEST_CASE(binary_garbage_is_not_echoed) {
  TempDir t;
  const std::string garbage = std::string("\x01\x02\xF5\x07\x1B[31m") + std::string(300, '\xAB') + "\n";
  try {
    std::vector<std::string> w;
    load_parts({t.write("g.obj", garbage)}, w);
    BOOST_ERROR("no error for binary garbage");
  } catch (const InputError& e) {
    const std::string msg = e.what();
    BOOST_TEST(msg.find("binary data") != std::string::npos, msg);
    BOOST_TEST(msg.size() < 300u);
    for (unsigned char c : msg) BOOST_TEST((c >= 0x20 && c < 0x7f), "unprintable byte in: " << msg);
  }
}

BOOST_AUTO_TEST_CASE(ply_counts_are_checked_against_the_file_size) {
  TempDir t;
  const std::string head = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                           "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  std::string body(36, '\0');             // three vertices at the origin
  body += std::string("\xFF", 1);         // a face of 255 indices...
  body += std::string(12, '\0');          // ...of which the file holds 3
  expect_input_error(t.write("f.ply", head + body), "face 0 lists 255 entries, more than the file holds");
  const std::string big = "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n";
  expect_input_error(t.write("v.ply", big + std::string(24, '\0')), "declares 2000000000 vertex records");
  const std::string ascii = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n"
                            "0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n";
  expect_input_error(t.write("a.ply", ascii), "face 0 lists 4000000000 entries");
}

BOOST_AUTO_TEST_CASE(off_and_stl_counts_are_checked_against_the_file_size) {
  TempDir t;
  expect_input_error(t.write("v.off", "OFF\n# big\n99999999999 1 0\n0 0 0\n"),
                     "declares 99999999999 vertices and 1 faces, more than the file holds");
  std::string stl = std::string(80, ' ') + std::string("\x00\x00\x00\x10", 4) + std::string(100, '\0');
  expect_input_error(t.write("t.stl", stl), "declares 268435456 triangles, more than the file holds");
  // Files that hold what they state still read: a tetrahedron as OFF (with a comment) and as
  // binary STL (4 triangles of 50 bytes after the 84-byte head).
  std::vector<std::string> w;
  const std::string off = "OFF\n# c\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  BOOST_CHECK_EQUAL(read_polygon_soup(t.write("ok.off", off)).faces.size(), 4u);
  std::string bin = std::string(80, ' ') + std::string("\x04\x00\x00\x00", 4);
  const float tri[4][9] = {{0, 0, 0, 0, 1, 0, 1, 0, 0}, {0, 0, 0, 1, 0, 0, 0, 0, 1}, {0, 0, 0, 0, 0, 1, 0, 1, 0}, {1, 0, 0, 0, 1, 0, 0, 0, 1}};
  for (const auto& f : tri) {
    bin += std::string(12, '\0');
    bin += std::string(reinterpret_cast<const char*>(f), sizeof f);
    bin += std::string(2, '\0');
  }
  BOOST_CHECK_EQUAL(read_polygon_soup(t.write("ok.stl", bin)).faces.size(), 4u);
}

BOOST_AUTO_TEST_CASE(a_model_too_small_for_doubles_is_refused) {
  TempDir t;
  expect_input_error(t.write("t.obj", "v 0 0 0\nv 1e-170 0 0\nv 0 1e-170 0\nv 0 0 1e-170\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"),
                     "model is too small");
}

BOOST_AUTO_TEST_CASE(no_faces) {
  TempDir t;
  expect_input_error(t.write("v.obj", "v 0 0 0\nv 1 0 0\n"), "no faces");
}

BOOST_AUTO_TEST_CASE(malformed_off) {
  TempDir t;
  expect_input_error(t.write("bad.off", "OFF\n3 1 0\n0 0 0\n1 0\n"), "malformed off");
}

BOOST_AUTO_TEST_CASE(only_flat_parts_is_an_error) {
  TempDir t;
  expect_input_error(t.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n"), "no solid part");
}

BOOST_AUTO_TEST_CASE(non_manifold_soup_is_rejected_by_read_mesh) {
  TempDir t;
  // Three triangles on one edge.
  std::string p = t.write("nm.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  try {
    read_mesh(p);
    BOOST_ERROR("non-manifold soup accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("nm.obj") != std::string::npos);
    BOOST_TEST(std::string(e.what()).find("manifold") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(atomic_directory_refuses_and_cleans_up) {
  TempDir t;
  std::string target = (t.path / "out").string();
  {
    AtomicDirectory d(target, false);
    d.write("a.txt", [](std::ostream& os) { os << "x"; });
    // no commit: nothing must appear
  }
  BOOST_TEST(!std::filesystem::exists(target));
  {
    AtomicDirectory d(target, false);
    d.write("a.txt", [](std::ostream& os) { os << "x"; });
    d.commit();
  }
  BOOST_TEST(std::filesystem::exists(std::filesystem::path(target) / "a.txt"));
  BOOST_CHECK_THROW(AtomicDirectory(target, false), InputError);  // non-empty
  BOOST_CHECK_NO_THROW(AtomicDirectory(target, true));
  std::string input = t.write("in/part.obj", "v 0 0 0\n");
  BOOST_CHECK_THROW(AtomicDirectory((t.path / "in").string(), true, {input}), InputError);
  std::size_t leftovers = 0;
  for (auto& e : std::filesystem::directory_iterator(t.path)) leftovers += e.path().filename().string()[0] == '.';
  BOOST_TEST(leftovers == 0u);
}

BOOST_AUTO_TEST_CASE(json_writer_escapes_and_formats) {
  std::ostringstream os;
  JsonWriter j(os, 0);
  j.begin_object().field("a\"b", std::string("x\ny")).field("n", 0.1).field("nan", std::nan("")).field("t", true);
  j.key("v").value(std::vector<double>{1, 2});
  j.end_object();
  BOOST_TEST(os.str() == "{\"a\\\"b\":\"x\\ny\",\"n\":0.10000000000000001,\"nan\":null,\"t\":true,\"v\":[1,2]}\n");
}

BOOST_AUTO_TEST_SUITE_END()
