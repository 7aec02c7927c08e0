// Stage "load": mesh file reading with validation. OBJ is parsed here (line numbers for
// errors, o/g groups for parts); OFF, PLY and STL go through CGAL's readers.
#include "dcshell/read_mesh.h"

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "dcshell/error.h"

namespace fs = std::filesystem;
namespace PMP = CGAL::Polygon_mesh_processing;

namespace dcshell {

std::string input_error_message(const std::string& file, std::size_t line, const std::string& what) {
  return line ? file + ":" + std::to_string(line) + ": " + what : file + ": " + what;
}

namespace {

constexpr double kMaxCoordinate = 1e12;         // beyond this, exact predicates still work but the
                                                // geometry is meaningless (absurd units or garbage)
constexpr double kMinExtent = 1e-90;            // below this, volumes (size^3) underflow doubles
constexpr std::size_t kMaxElements = 50000000;  // guards against absurd allocations

[[noreturn]] void fail(const std::string& file, std::size_t line, const std::string& what) {
  throw InputError(input_error_message(file, line, what));
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

bool parse_double(const char*& p, const char* end, double& out) {
  while (p < end && (*p == ' ' || *p == '\t')) ++p;
  if (p == end) return false;
  // from_chars for double is available in GCC 11+; it rejects "nan"/"inf" spelled oddly but
  // accepts "nan" and "inf", which we then reject explicitly with a clear message.
  auto r = std::from_chars(p, end, out);
  if (r.ec != std::errc()) return false;
  p = r.ptr;
  return p == end || *p == ' ' || *p == '\t' || *p == '\r';
}

void validate_point(const std::string& file, std::size_t line, const std::array<double, 3>& q) {
  for (double c : q) {
    if (!std::isfinite(c)) fail(file, line, "coordinate is NaN or infinite");
    if (std::fabs(c) > kMaxCoordinate) fail(file, line, "coordinate magnitude exceeds 1e12");
  }
}

// Statements of the OBJ specification that carry no polygon geometry: texture and normal
// coordinates, materials, smoothing/merging groups, display attributes, lines and points, and
// free-form curves and surfaces (not polygonised here).
bool is_ignored_obj_statement(const std::string& key) {
  static const char* const kIgnored[] = {"vn", "vt", "vp", "s", "mg", "usemtl", "mtllib", "usemap", "maplib",
                                         "lod", "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj",
                                         "ctech", "stech", "l", "p", "cstype", "deg", "bmat", "step", "curv",
                                         "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con",
                                         "call", "csh"};
  for (const char* k : kIgnored)
    if (key == k) return true;
  return false;
}

// A token for an error message: quoted, at most 24 characters, bytes that are not printable
// ASCII shown as \xNN (a binary file must not spill control characters onto the terminal).
std::string printable_token(const std::string& t) {
  std::string out = "'";
  for (std::size_t i = 0; i < t.size() && i < 24; ++i) {
    const unsigned char c = static_cast<unsigned char>(t[i]);
    if (c >= 0x20 && c < 0x7f) {
      out.push_back(static_cast<char>(c));
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      out += buf;
    }
  }
  out += t.size() > 24 ? "...'" : "'";
  bool binary = false;
  for (unsigned char c : t) binary |= (c < 0x20 && c != '\t') || c == 0x7f;
  return binary ? out + " (binary data: not a text OBJ file?)" : out;
}

PolygonSoup read_obj(const std::string& path, std::istream& in) {
  PolygonSoup soup;
  std::string line;
  std::size_t lineno = 0;
  std::size_t current_group = 0;
  bool have_group = false;
  // Lines end in \n, \r\n or a lone \r (old Mac exports); a trailing backslash continues a
  // line (the OBJ specification); a UTF-8 byte-order mark before the first statement is skipped.
  auto next_line = [&](std::string& out) {
    out.clear();
    bool any = false;
    for (int c; (c = in.get()) != EOF;) {
      any = true;
      if (c == '\n' || c == '\r') {
        if (c == '\r' && in.peek() == '\n') in.get();
        ++lineno;
        if (!out.empty() && out.back() == '\\') {
          out.back() = ' ';
          continue;
        }
        return true;
      }
      out.push_back(static_cast<char>(c));
    }
    if (any) ++lineno;
    return any;
  };
  const std::size_t first = lineno;
  while (next_line(line)) {
    if (lineno == first + 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);
    const char* p = line.data();
    const char* end = p + line.size();
    while (p < end && (*p == ' ' || *p == '\t')) ++p;
    if (p == end || *p == '#') continue;
    const char* kw = p;
    while (p < end && *p != ' ' && *p != '\t') ++p;
    std::string key(kw, p);
    if (key == "v") {
      std::array<double, 3> q;
      for (double& c : q)
        if (!parse_double(p, end, c)) fail(path, lineno, "malformed vertex line");
      // A fourth (w) or colour values may follow (ignored); anything else is a broken line.
      for (double extra; p < end;) {
        while (p < end && (*p == ' ' || *p == '\t')) ++p;
        if (p < end && !parse_double(p, end, extra)) fail(path, lineno, "malformed vertex line (text after the coordinates)");
      }
      validate_point(path, lineno, q);
      if (soup.points.size() >= kMaxElements) fail(path, lineno, "too many vertices");
      soup.points.push_back(q);
    } else if (key == "f") {
      std::vector<std::size_t> face;
      std::istringstream ss(std::string(p, end));
      std::string tok;
      while (ss >> tok) {
        long long idx = 0;
        const char* b = tok.data();
        auto r = std::from_chars(b, b + tok.size(), idx);
        if (r.ec != std::errc() || (r.ptr != b + tok.size() && *r.ptr != '/'))
          fail(path, lineno, "malformed face index '" + tok + "'");
        long long n = static_cast<long long>(soup.points.size());
        long long resolved = idx > 0 ? idx - 1 : n + idx;  // OBJ: 1-based, negative = relative
        if (idx == 0 || resolved < 0 || resolved >= n)
          fail(path, lineno, "face index " + std::to_string(idx) + " out of range (" + std::to_string(n) +
                                 " vertices so far)");
        face.push_back(static_cast<std::size_t>(resolved));
      }
      if (face.size() < 3) fail(path, lineno, "face with fewer than 3 vertices");
      if (soup.faces.size() >= kMaxElements) fail(path, lineno, "too many faces");
      soup.faces.push_back(std::move(face));
      if (have_group) soup.face_group.push_back(current_group);
    } else if (key == "o" || key == "g") {
      std::string name(p, end);
      name.erase(0, name.find_first_not_of(" \t"));
      if (name.empty()) name = key + std::to_string(soup.group_names.size());
      auto it = std::find(soup.group_names.begin(), soup.group_names.end(), name);
      current_group = static_cast<std::size_t>(it - soup.group_names.begin());
      if (it == soup.group_names.end()) soup.group_names.push_back(name);
      if (!have_group) {
        // faces before the first group form their own unnamed group
        if (!soup.faces.empty()) {
          soup.group_names.insert(soup.group_names.begin(), "ungrouped");
          ++current_group;
          soup.face_group.assign(soup.faces.size(), 0);
        }
        have_group = true;
      }
    } else if (is_ignored_obj_statement(key)) {
      continue;  // attributes, grouping and free-form data irrelevant to the polygons
    } else {
      fail(path, lineno, "unknown OBJ statement " + printable_token(key));
    }
  }
  if (in.bad()) fail(path, 0, "read error");
  return soup;
}

// Binary PLY files state their sizes (element counts in the header, a vertex count before each
// face's indices) and CGAL's reader allocates what they say: a 200-byte file declaring a face
// of 4 billion vertices made it allocate gigabytes. So every stated size is checked against the
// bytes the file actually holds before CGAL reads it. ASCII files need no check (a count there
// is followed by as many tokens, or the reader stops).
void check_binary_ply_sizes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line, format;
  struct Property {
    int size = 0, count_size = 0;  // count_size > 0: a list
  };
  struct Element {
    std::string name;
    unsigned long long count = 0;
    std::vector<Property> props;
  };
  std::vector<Element> elements;
  auto type_size = [&](const std::string& t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    fail(path, 0, "malformed ply file (unknown property type '" + t + "')");
  };
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key == "format") ls >> format;
    else if (key == "element") {
      Element e;
      ls >> e.name >> e.count;
      if (!ls) fail(path, 0, "malformed ply file (bad element line)");
      elements.push_back(e);
    } else if (key == "property" && !elements.empty()) {
      std::string t, a, b;
      ls >> t;
      Property pr;
      if (t == "list") {
        ls >> a >> b;
        pr.count_size = type_size(a);
        pr.size = type_size(b);
      } else {
        pr.size = type_size(t);
      }
      elements.back().props.push_back(pr);
    } else if (key == "end_header") {
      break;
    }
  }
  std::error_code ec;
  const unsigned long long size = fs::file_size(path, ec);
  if (format == "ascii") {
    // Walk the tokens as the header lays them out: a list's count must be possible in the bytes
    // left (each entry takes at least two).
    std::string tok;
    for (const auto& e : elements) {
      if (e.count > size / 2)
        fail(path, 0, "malformed ply file (header declares " + std::to_string(e.count) + " " + e.name +
                          " records, more than the file holds)");
      for (unsigned long long r = 0; r < e.count; ++r)
        for (const auto& pr : e.props) {
          if (!(in >> tok)) return;  // truncated: CGAL's reader says so
          if (pr.count_size == 0) continue;
          const unsigned long long n = std::strtoull(tok.c_str(), nullptr, 10);
          if (n > size / 2)
            fail(path, 0, "malformed ply file (" + e.name + " " + std::to_string(r) + " lists " + std::to_string(n) +
                              " entries, more than the file holds)");
          for (unsigned long long k = 0; k < n && in >> tok; ++k) {
          }
        }
    }
    return;
  }
  if (format != "binary_little_endian" && format != "binary_big_endian") return;
  const bool little = format == "binary_little_endian";
  unsigned long long pos = static_cast<unsigned long long>(in.tellg());
  for (const auto& e : elements) {
    unsigned long long fixed = 0;
    bool lists = false;
    for (const auto& pr : e.props) lists |= pr.count_size > 0, fixed += pr.count_size > 0 ? 0 : pr.size;
    if (!lists) {
      if (fixed > 0 && e.count > (size - std::min(pos, size)) / fixed)
        fail(path, 0, "malformed ply file (header declares " + std::to_string(e.count) + " " + e.name +
                          " records, more than the file holds)");
      pos += e.count * fixed;
      continue;
    }
    for (unsigned long long r = 0; r < e.count; ++r)
      for (const auto& pr : e.props) {
        if (pr.count_size == 0) {
          pos += pr.size;
          continue;
        }
        unsigned char bytes[8] = {0};
        in.seekg(static_cast<std::streamoff>(pos));
        if (!in.read(reinterpret_cast<char*>(bytes), pr.count_size))
          fail(path, 0, "malformed ply file (truncated " + e.name + " data)");
        unsigned long long n = 0;
        for (int k = 0; k < pr.count_size; ++k) n = (n << 8) | bytes[little ? pr.count_size - 1 - k : k];
        pos += pr.count_size;
        if (n > (size - std::min(pos, size)) / pr.size)
          fail(path, 0, "malformed ply file (" + e.name + " " + std::to_string(r) + " lists " + std::to_string(n) +
                            " entries, more than the file holds)");
        pos += n * pr.size;
      }
  }
}

// OFF and binary STL state their counts too, and CGAL's readers only say "failed" when they
// do not fit: these name the count. An OFF vertex takes at least 6 bytes ("0 0 0\n") and a
// face at least 8 ("3 0 1 2\n"); a binary STL triangle takes 50 bytes after an 84-byte head.
void check_off_stl_sizes(const std::string& path, const std::string& ext) {
  std::ifstream in(path, std::ios::binary);
  const auto size = static_cast<unsigned long long>(fs::file_size(path));
  if (ext == ".stl") {
    char head[84];
    if (!in.read(head, 84) || std::string(head, 5) == "solid") return;  // too short, or ASCII: CGAL decides
    unsigned long long n = 0;
    for (int b = 3; b >= 0; --b) n = (n << 8) | static_cast<unsigned char>(head[80 + b]);
    if (84 + 50 * n > size)
      fail(path, 0, "malformed stl file (header declares " + std::to_string(n) + " triangles, more than the file holds)");
    return;
  }
  std::string tok;
  std::vector<std::string> head;  // the keyword, then vertex, face and edge counts
  while (head.size() < 4 && in >> tok) {
    if (tok[0] == '#') {
      std::string rest;
      std::getline(in, rest);
      continue;
    }
    head.push_back(tok);
  }
  // [ST][C][N]OFF only: nOFF and 4OFF put a dimension first, OFF BINARY has no text counts.
  if (head.size() < 3 || head[0].find("OFF") == std::string::npos || head[0].find_first_of("n4") != std::string::npos)
    return;
  auto count = [](const std::string& t) -> long long {
    if (t.empty() || t.size() > 18 || t.find_first_not_of("0123456789") != std::string::npos) return -1;
    return std::stoll(t);
  };
  const long long nv = count(head[1]), nf = count(head[2]);
  if (nv < 0 || nf < 0) return;  // not plain counts: CGAL decides
  if (6.0 * double(nv) + 8.0 * double(nf) > double(size))
    fail(path, 0, "malformed off file (header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                      " faces, more than the file holds)");
}

}  // namespace

PolygonSoup read_polygon_soup(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(path, 0, "no such file");
  if (fs::is_directory(path, ec)) fail(path, 0, "is a directory, expected a mesh file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, "cannot open file for reading");
  if (fs::file_size(path, ec) == 0) fail(path, 0, "empty file");
  const std::string ext = lower_extension(path);
  PolygonSoup soup;
  if (ext == ".obj") {
    soup = read_obj(path, in);
  } else if (ext == ".off" || ext == ".ply" || ext == ".stl") {
    in.close();
    std::vector<Point3> pts;
    std::vector<std::vector<std::size_t>> faces;
    bool ok = false;
    if (ext == ".ply") check_binary_ply_sizes(path);
    else if (ext == ".off" || ext == ".stl") check_off_stl_sizes(path, ext);
    try {
      ok = CGAL::IO::read_polygon_soup(path, pts, faces, CGAL::parameters::verbose(false));
    } catch (const std::bad_alloc&) {
      fail(path, 0, "malformed " + ext.substr(1) + " file (a stated count is too large)");
    } catch (const std::exception& e) {
      fail(path, 0, std::string("malformed ") + ext.substr(1) + " file (" + e.what() + ")");
    }
    if (!ok) fail(path, 0, "malformed " + ext.substr(1) + " file");
    for (const auto& q : pts) {
      std::array<double, 3> a{q.x(), q.y(), q.z()};
      validate_point(path, 0, a);
      soup.points.push_back(a);
    }
    for (auto& f : faces) {
      if (f.size() < 3) fail(path, 0, "face with fewer than 3 vertices");
      for (auto i : f)
        if (i >= soup.points.size()) fail(path, 0, "face index out of range");
    }
    soup.faces = std::move(faces);
  } else {
    fail(path, 0, "unknown mesh format '" + ext + "' (expected .obj, .off, .ply or .stl)");
  }
  if (soup.points.empty()) fail(path, 0, "no vertices");
  if (soup.faces.empty()) fail(path, 0, "no faces");
  double extent = 0;
  for (int d = 0; d < 3; ++d) {
    double lo = soup.points[0][d], hi = lo;
    for (const auto& q : soup.points) lo = std::min(lo, q[d]), hi = std::max(hi, q[d]);
    extent = std::max(extent, hi - lo);
  }
  if (extent > 0 && extent < kMinExtent) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g", extent);
    fail(path, 0, std::string("model is too small to compute with (extent ") + buf +
                      " < 1e-90: its volumes would underflow doubles); rescale it");
  }
  return soup;
}

namespace {

Mesh soup_to_mesh(const std::string& path, const std::string& what, const std::vector<std::array<double, 3>>& points,
                  const std::vector<std::vector<std::size_t>>& in_faces) {
  // Keep only the referenced points, in first-reference order.
  std::vector<long> remap(points.size(), -1);
  std::vector<Point3> pts;
  auto faces = in_faces;
  for (auto& f : faces)
    for (auto& i : f) {
      if (remap[i] < 0) {
        remap[i] = long(pts.size());
        pts.emplace_back(points[i][0], points[i][1], points[i][2]);
      }
      i = std::size_t(remap[i]);
    }
  // STL and some exporters duplicate vertices per face; merging exact duplicates is lossless.
  PMP::merge_duplicate_points_in_polygon_soup(pts, faces);
  for (auto& f : faces) {
    std::vector<std::size_t> g(f);
    std::sort(g.begin(), g.end());
    if (std::adjacent_find(g.begin(), g.end()) != g.end()) fail(path, 0, what + "face with a repeated vertex");
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(faces)) {
    if (!PMP::orient_polygon_soup(pts, faces) || !PMP::is_polygon_soup_a_polygon_mesh(faces))
      fail(path, 0, what + "faces do not form a 2-manifold surface (non-manifold edges or vertices)");
  }
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(pts, faces, mesh);
  return mesh;
}

}  // namespace

Mesh read_mesh(const std::string& path) {
  PolygonSoup soup = read_polygon_soup(path);
  return soup_to_mesh(path, "", soup.points, soup.faces);
}

std::vector<std::pair<std::string, Mesh>> read_mesh_objects(const std::string& path) {
  PolygonSoup soup = read_polygon_soup(path);
  std::vector<std::pair<std::string, Mesh>> out;
  if (soup.group_names.size() <= 1) {
    // No groups: one mesh per connected component, as `dcshell shell` reads parts (a file that
    // holds all hulls of a decomposition is a set of shells, not one broken shell).
    const auto comps = soup_components(soup);
    if (comps.size() == 1) {
      out.emplace_back(path, soup_to_mesh(path, "", soup.points, soup.faces));
      return out;
    }
    for (std::size_t c = 0; c < comps.size(); ++c) {
      std::vector<std::vector<std::size_t>> faces;
      for (auto f : comps[c]) faces.push_back(soup.faces[f]);
      const std::string tag = "component " + std::to_string(c) + ": ";
      out.emplace_back(path + "#" + std::to_string(c), soup_to_mesh(path, tag, soup.points, faces));
    }
    return out;
  }
  std::vector<std::vector<std::vector<std::size_t>>> groups(soup.group_names.size());
  for (std::size_t f = 0; f < soup.faces.size(); ++f) groups[soup.face_group[f]].push_back(soup.faces[f]);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (groups[g].empty()) continue;
    const std::string name = path + "#" + soup.group_names[g];
    out.emplace_back(name, soup_to_mesh(path, "object '" + soup.group_names[g] + "': ", soup.points, groups[g]));
  }
  return out;
}

std::vector<std::pair<std::string, Mesh>> read_mesh_set(const std::vector<std::string>& inputs) {
  std::vector<std::pair<std::string, Mesh>> out;
  for (const auto& file : expand_inputs(inputs))
    for (auto& m : read_mesh_objects(file)) out.push_back(std::move(m));
  return out;
}

bool is_mesh_file_name(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".stl";
}

std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs) {
  std::vector<std::string> out;
  for (const auto& in : inputs) {
    std::error_code ec;
    if (!fs::exists(in, ec)) fail(in, 0, "no such file or directory");
    if (fs::is_directory(in, ec)) {
      std::vector<std::string> files;
      for (const auto& e : fs::directory_iterator(in, ec)) {
        // Hidden files (".x.obj", macOS "._x.obj" resource forks) are not meshes of the set.
        if (!e.is_regular_file() || e.path().filename().string().rfind('.', 0) == 0) continue;
        if (is_mesh_file_name(e.path().string())) files.push_back(e.path().string());
      }
      if (ec) fail(in, 0, "cannot list directory (" + ec.message() + ")");
      if (files.empty()) fail(in, 0, "directory holds no mesh files (.obj .off .ply .stl)");
      std::sort(files.begin(), files.end());
      // A `dcshell shell` output directory: shells.obj repeats shell_NNN.obj for viewers.
      auto is_shell_file = [](const std::string& f) { return fs::path(f).filename().string().rfind("shell_", 0) == 0; };
      if (std::any_of(files.begin(), files.end(), is_shell_file))
        files.erase(std::remove_if(files.begin(), files.end(),
                                   [](const std::string& f) { return fs::path(f).filename() == "shells.obj"; }),
                    files.end());
      out.insert(out.end(), files.begin(), files.end());
    } else {
      out.push_back(in);
    }
  }
  return out;
}

}  // namespace dcshell
