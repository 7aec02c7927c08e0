// Printable sheets: nets are built by hand here (a unit cube unfolded into a cross, a regular
// tetrahedron unfolded into a triangle), so these tests do not depend on the unfolder.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include <Eigen/Dense>

#include "dcshell/net_sheets.h"

using dcshell::AssemblyJoin;
using dcshell::Net;
using dcshell::SheetLayout;
using dcshell::SheetOptions;
using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;

namespace {

// ---------------------------------------------------------------------------------------
// Hand-made nets: corners are laid out along the cut tree from 3D edge lengths.

Net make_net(const std::string& name, const std::vector<V3>& verts, const std::vector<std::array<int, 3>>& faces,
             const std::vector<int>& parent) {
  Net net;
  net.name = name, net.shell_vertices = verts, net.shell_faces = faces, net.parent = parent;
  const int nf = static_cast<int>(faces.size());
  net.corners.resize(nf);
  std::vector<bool> placed(nf, false);
  auto normal = [&](int f) {
    return V3((verts[faces[f][1]] - verts[faces[f][0]]).cross(verts[faces[f][2]] - verts[faces[f][0]]).normalized());
  };
  // Third corner of a counter-clockwise triangle (x, y, c) from its 3D edge lengths.
  auto apex = [](const V2& x, const V2& y, double lxc, double lyc) {
    const double d = (y - x).norm(), along = (lxc * lxc - lyc * lyc + d * d) / (2 * d);
    const V2 u = (y - x) / d;
    return V2(x + u * along + V2(-u.y(), u.x()) * std::sqrt(std::max(0.0, lxc * lxc - along * along)));
  };
  for (int done = 0; done < nf;) {
    for (int f = 0; f < nf; ++f) {
      if (placed[f] || (parent[f] >= 0 && !placed[parent[f]])) continue;
      const auto& t = faces[f];
      if (parent[f] < 0) {
        net.corners[f][0] = V2(0, 0);
        net.corners[f][1] = V2((verts[t[1]] - verts[t[0]]).norm(), 0);
        net.corners[f][2] = apex(net.corners[f][0], net.corners[f][1], (verts[t[2]] - verts[t[0]]).norm(),
                                 (verts[t[2]] - verts[t[1]]).norm());
      } else {
        const int p = parent[f];
        int k = -1;
        std::map<int, V2> known;
        for (int j = 0; j < 3; ++j) known[faces[p][j]] = net.corners[p][j];
        for (int j = 0; j < 3 && k < 0; ++j)
          if (known.count(t[j]) && known.count(t[(j + 1) % 3])) k = j;
        BOOST_REQUIRE_MESSAGE(k >= 0, "face " << f << " shares no edge with its parent");
        const int x = t[k], y = t[(k + 1) % 3], c = t[(k + 2) % 3];
        net.corners[f][k] = known[x];
        net.corners[f][(k + 1) % 3] = known[y];
        net.corners[f][(k + 2) % 3] =
            apex(known[x], known[y], (verts[c] - verts[x]).norm(), (verts[c] - verts[y]).norm());
      }
      placed[f] = true;
      ++done;
    }
  }
  std::map<std::pair<int, int>, int> edge_of;
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces[f][k], b = faces[f][(k + 1) % 3];
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = edge_of.find(key);
      if (it == edge_of.end()) {
        edge_of[key] = static_cast<int>(net.edges.size());
        Net::Edge e;
        e.v0 = a, e.v1 = b, e.f0 = f;
        net.edges.push_back(e);
      } else {
        Net::Edge& e = net.edges[it->second];
        e.f1 = f;
        e.fold = parent[e.f0] == f || parent[f] == e.f0;
        e.fold_angle = std::acos(std::clamp(normal(e.f0).dot(normal(f)), -1.0, 1.0));
      }
    }
  return net;
}

/// Unit cube unfolded into a cross: bottom square in the middle, front/back/left/right around
/// it, top attached to front. Each square is two coplanar triangles (a flat fold inside).
Net cube_cross(const std::string& name) {
  std::vector<V3> v;
  for (int i = 0; i < 8; ++i) v.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const std::array<std::array<int, 4>, 6> sq = {{{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};
  const int sq_parent[6] = {-1, 2, 0, 0, 0, 0};
  std::vector<std::array<int, 3>> faces;
  for (const auto& s : sq) faces.push_back({s[0], s[1], s[2]}), faces.push_back({s[0], s[2], s[3]});
  std::vector<int> parent(12, -1);
  auto shares_edge = [&](int f, int g) {
    int common = 0;
    for (int a : faces[f]) common += std::count(faces[g].begin(), faces[g].end(), a);
    return common == 2;
  };
  for (int s = 0; s < 6; ++s) {
    if (sq_parent[s] < 0) { parent[2 * s + 1] = 2 * s; continue; }
    int t = -1, u = -1;
    for (int a = 2 * s; a < 2 * s + 2 && t < 0; ++a)
      for (int b = 2 * sq_parent[s]; b < 2 * sq_parent[s] + 2 && t < 0; ++b)
        if (shares_edge(a, b)) t = a, u = b;
    parent[t] = u;
    parent[t == 2 * s ? 2 * s + 1 : 2 * s] = t;
  }
  return make_net(name, v, faces, parent);
}

/// Regular tetrahedron, three faces folded around the root: the net is one big triangle.
Net tetra_star(const std::string& name) {
  std::vector<V3> v = {V3(1, 1, 1), V3(1, -1, -1), V3(-1, 1, -1), V3(-1, -1, 1)};
  std::vector<std::array<int, 3>> faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  for (auto& f : faces) {  // outward
    const V3 n = (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]);
    if (n.dot(v[f[0]] + v[f[1]] + v[f[2]]) < 0) std::swap(f[1], f[2]);
  }
  return make_net(name, v, faces, {-1, 0, 0, 0});
}

int glued_pairs(const Net& n) {
  int c = 0;
  for (const auto& e : n.edges) c += !e.fold && e.f1 >= 0;
  return c;
}

// ---------------------------------------------------------------------------------------
// A small strict XML parser: well-formedness (matching tags, quoted attributes, no duplicate
// attributes, valid entity references, one root) and a tree to query.

struct XmlNode {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::vector<XmlNode> children;
  std::string text;
};

class XmlParser {
 public:
  explicit XmlParser(const std::string& s) : s_(s) {}
  XmlNode parse() {
    skip_misc();
    if (s_.compare(i_, 5, "<?xml") == 0) skip_past("?>");
    skip_misc();
    XmlNode root = element();
    skip_misc();
    if (i_ != s_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error("XML error at byte " + std::to_string(i_) + ": " + what);
  }
  void skip_past(const char* end) {
    const std::size_t j = s_.find(end, i_);
    if (j == std::string::npos) fail(std::string("missing ") + end);
    i_ = j + std::string(end).size();
  }
  void skip_ws() { while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_; }
  void skip_misc() {
    for (;;) {
      skip_ws();
      if (s_.compare(i_, 4, "<!--") == 0) skip_past("-->");
      else return;
    }
  }
  std::string name() {
    const std::size_t b = i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || std::strchr(":_-.", s_[i_]))) ++i_;
    if (i_ == b) fail("expected a name");
    return s_.substr(b, i_ - b);
  }
  std::string chars(char stop) {  // text or attribute value up to `stop`, entities decoded
    std::string out;
    while (i_ < s_.size() && s_[i_] != stop) {
      const char c = s_[i_];
      if (c == '<') fail("'<' inside text or attribute");
      if (c == '&') {
        const std::size_t semi = s_.find(';', i_);
        if (semi == std::string::npos) fail("unterminated entity");
        const std::string ent = s_.substr(i_ + 1, semi - i_ - 1);
        static const std::map<std::string, char> named = {{"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
        if (named.count(ent)) out += named.at(ent);
        else if (ent.size() > 1 && ent[0] == '#') out += '?';
        else fail("bad entity &" + ent + ";");
        i_ = semi + 1;
      } else {
        out += c, ++i_;
      }
    }
    return out;
  }
  XmlNode element() {
    if (i_ >= s_.size() || s_[i_] != '<') fail("expected '<'");
    ++i_;
    XmlNode n;
    n.name = name();
    for (;;) {
      skip_ws();
      if (s_.compare(i_, 2, "/>") == 0) { i_ += 2; return n; }
      if (i_ < s_.size() && s_[i_] == '>') { ++i_; break; }
      const std::string a = name();
      skip_ws();
      if (i_ >= s_.size() || s_[i_] != '=') fail("expected '=' after attribute " + a);
      ++i_;
      skip_ws();
      if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\'')) fail("unquoted attribute " + a);
      const char q = s_[i_++];
      std::string v = chars(q);
      if (i_ >= s_.size()) fail("unterminated attribute " + a);
      ++i_;
      if (!n.attrs.emplace(a, v).second) fail("duplicate attribute " + a);
    }
    for (;;) {
      n.text += chars('<');
      if (i_ >= s_.size()) fail("unclosed element " + n.name);
      if (s_.compare(i_, 4, "<!--") == 0) { skip_past("-->"); continue; }
      if (s_.compare(i_, 2, "</") == 0) {
        i_ += 2;
        if (name() != n.name) fail("mismatched closing tag for " + n.name);
        skip_ws();
        if (i_ >= s_.size() || s_[i_] != '>') fail("expected '>'");
        ++i_;
        return n;
      }
      n.children.push_back(element());
    }
  }
  const std::string& s_;
  std::size_t i_ = 0;
};

void collect(const XmlNode& n, const std::string& name, std::vector<const XmlNode*>& out) {
  if (n.name == name) out.push_back(&n);
  for (const XmlNode& c : n.children) collect(c, name, out);
}
std::vector<const XmlNode*> all(const XmlNode& n, const std::string& name) {
  std::vector<const XmlNode*> v;
  collect(n, name, v);
  return v;
}
bool has_class(const XmlNode& n, const std::string& cls) {
  auto it = n.attrs.find("class");
  if (it == n.attrs.end()) return false;
  std::istringstream ss(it->second);
  for (std::string w; ss >> w;)
    if (w == cls) return true;
  return false;
}
int count_class(const XmlNode& n, const std::string& cls) {
  int c = has_class(n, cls);
  for (const XmlNode& k : n.children) c += count_class(k, cls);
  return c;
}

std::string render(const std::vector<Net>& nets, const SheetOptions& o, const std::vector<AssemblyJoin>& a = {}) {
  std::ostringstream ss;
  dcshell::write_net_sheets(nets, o, a, ss);
  return ss.str();
}

// ---------------------------------------------------------------------------------------
// Geometry checks on the layout.

bool convex_interiors_overlap(const std::vector<V2>& p, const std::vector<V2>& q) {
  for (const auto* poly : {&p, &q})
    for (std::size_t i = 0; i < poly->size(); ++i) {
      const V2 e = (*poly)[(i + 1) % poly->size()] - (*poly)[i];
      const V2 axis = V2(-e.y(), e.x()).normalized();
      double p0 = 1e300, p1 = -1e300, q0 = 1e300, q1 = -1e300;
      for (const V2& a : p) p0 = std::min(p0, a.dot(axis)), p1 = std::max(p1, a.dot(axis));
      for (const V2& a : q) q0 = std::min(q0, a.dot(axis)), q1 = std::max(q1, a.dot(axis));
      if (p1 <= q0 + 1e-6 || q1 <= p0 + 1e-6) return false;
    }
  return true;
}

void check_layout(const std::vector<Net>& nets, const SheetLayout& L, bool tabs) {
  BOOST_REQUIRE_EQUAL(L.pieces.size(), nets.size());
  const double tol = 1e-6;
  for (std::size_t i = 0; i < L.pieces.size(); ++i) {
    const auto& p = L.pieces[i];
    BOOST_CHECK_EQUAL(p.net, i);
    BOOST_CHECK(p.page >= 0 && p.page < L.sheet_pages);
    // Inside the printable area.
    BOOST_CHECK_GE(p.x_mm, L.area_x_mm - tol);
    BOOST_CHECK_GE(p.y_mm, L.area_y_mm - tol);
    BOOST_CHECK_LE(p.x_mm + p.width_mm, L.area_x_mm + L.area_width_mm + tol);
    BOOST_CHECK_LE(p.y_mm + p.height_mm, L.area_y_mm + L.area_height_mm + tol);
    // Physical scale, not mirrored on paper (page y points down).
    BOOST_CHECK_CLOSE(-p.linear.determinant(), L.scale_mm_per_unit * L.scale_mm_per_unit, 1e-9);
    // Every corner and every tab inside its rectangle; tabs clear of the piece and of each other.
    auto inside = [&](const V2& q) {
      return q.x() >= p.x_mm - tol && q.x() <= p.x_mm + p.width_mm + tol && q.y() >= p.y_mm - tol &&
             q.y() <= p.y_mm + p.height_mm + tol;
    };
    std::vector<std::vector<V2>> tris;
    for (const auto& t : nets[i].corners) {
      tris.push_back({});
      for (const V2& c : t) {
        tris.back().push_back(p.linear * c + p.offset);
        BOOST_CHECK(inside(tris.back().back()));
      }
    }
    BOOST_CHECK_EQUAL(p.tabs.size(), tabs ? static_cast<std::size_t>(glued_pairs(nets[i])) : 0u);
    for (std::size_t k = 0; k < p.tabs.size(); ++k) {
      std::vector<V2> q(p.tabs[k].begin(), p.tabs[k].end());
      for (const V2& c : q) BOOST_CHECK(inside(c));
      BOOST_CHECK_GT((q[1] - q[0]).norm(), 0.5);  // a real tab, not a sliver
      for (const auto& t : tris) BOOST_CHECK(!convex_interiors_overlap(q, t));
      for (std::size_t j = 0; j < k; ++j)
        BOOST_CHECK(!convex_interiors_overlap(q, std::vector<V2>(p.tabs[j].begin(), p.tabs[j].end())));
    }
    // No two pieces of one page overlap.
    for (std::size_t j = 0; j < i; ++j) {
      const auto& o = L.pieces[j];
      if (o.page != p.page) continue;
      const bool apart = p.x_mm + p.width_mm <= o.x_mm + tol || o.x_mm + o.width_mm <= p.x_mm + tol ||
                         p.y_mm + p.height_mm <= o.y_mm + tol || o.y_mm + o.height_mm <= p.y_mm + tol;
      BOOST_CHECK_MESSAGE(apart, "pieces " << i << " and " << j << " overlap on page " << p.page);
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(net_sheets)

BOOST_AUTO_TEST_CASE(paper_from_string_parses_and_rejects) {
  SheetOptions a4 = SheetOptions::paper_from_string("a4");
  BOOST_CHECK_EQUAL(a4.paper_width_mm, 210);
  BOOST_CHECK_EQUAL(a4.paper_height_mm, 297);
  SheetOptions letter = SheetOptions::paper_from_string("Letter");
  BOOST_CHECK_CLOSE(letter.paper_width_mm, 215.9, 1e-12);
  BOOST_CHECK_CLOSE(letter.paper_height_mm, 279.4, 1e-12);
  SheetOptions custom = SheetOptions::paper_from_string("300x200mm");
  BOOST_CHECK_EQUAL(custom.paper_width_mm, 300);
  BOOST_CHECK_EQUAL(custom.paper_height_mm, 200);
  SheetOptions frac = SheetOptions::paper_from_string("12.5x30.25MM");
  BOOST_CHECK_EQUAL(frac.paper_width_mm, 12.5);
  BOOST_CHECK_EQUAL(frac.paper_height_mm, 30.25);
  for (const char* bad : {"", "a6", "300x200", "0x200mm", "-5x10mm", "x200mm", "300xmm", "300x200cm",
                          "1e3x2mm", "300x200x5mm", "3.0.0x2mm", " 300x200mm", "mm"}) {
    try {
      SheetOptions::paper_from_string(bad);
      BOOST_ERROR("accepted bad paper '" << bad << "'");
    } catch (const std::invalid_argument& e) {
      BOOST_CHECK_MESSAGE(std::string(e.what()).find("'" + std::string(bad) + "'") != std::string::npos, e.what());
    }
  }
}

BOOST_AUTO_TEST_CASE(svg_is_well_formed_with_one_group_per_piece) {
  const std::vector<Net> nets = {cube_cross("cube"), tetra_star("tetra <1> & \"x\"")};
  SheetOptions o;
  const std::string svg = render(nets, o);
  XmlNode root = XmlParser(svg).parse();
  BOOST_CHECK_EQUAL(root.name, "svg");
  BOOST_CHECK_EQUAL(root.attrs["width"], "210mm");
  BOOST_CHECK(root.attrs["viewBox"].rfind("0 0 210 ", 0) == 0);

  const SheetLayout L = dcshell::layout_net_sheets(nets, o);
  std::vector<const XmlNode*> pages;
  for (const XmlNode& c : root.children)
    if (c.name == "g") pages.push_back(&c);
  BOOST_REQUIRE_EQUAL(pages.size(), static_cast<std::size_t>(L.sheet_pages));
  std::map<std::string, const XmlNode*> pieces;
  for (std::size_t p = 0; p < pages.size(); ++p) {
    BOOST_CHECK_EQUAL(pages[p]->attrs.at("id"), "page-" + std::to_string(p + 1));
    std::vector<const XmlNode*> legend;
    for (const XmlNode& g : pages[p]->children)
      if (g.name == "g" && has_class(g, "piece")) pieces[g.attrs.at("id")] = &g;
      else if (g.name == "g" && has_class(g, "legend")) legend.push_back(&g);
    BOOST_CHECK_EQUAL(legend.size(), 1u);
  }
  BOOST_REQUIRE_EQUAL(pieces.size(), 2u);
  BOOST_REQUIRE(pieces.count("piece-cube"));
  BOOST_REQUIRE(pieces.count("piece-tetra__1_____x_"));

  const XmlNode& cube = *pieces["piece-cube"];
  const XmlNode& tetra = *pieces["piece-tetra__1_____x_"];
  // The cube's six square diagonals are flat folds: not drawn. 11 tree edges - 6 = 5 folds.
  BOOST_CHECK_EQUAL(count_class(cube, "mountain") - count_class(cube, "tab-fold"), 5);
  BOOST_CHECK_EQUAL(count_class(tetra, "mountain") - count_class(tetra, "tab-fold"), 3);
  BOOST_CHECK_EQUAL(count_class(cube, "valley"), 0);
  // One tab per glued pair, folded at its base.
  BOOST_CHECK_EQUAL(count_class(cube, "tab"), glued_pairs(nets[0]));
  BOOST_CHECK_EQUAL(count_class(cube, "tab-fold"), glued_pairs(nets[0]));
  BOOST_CHECK_EQUAL(count_class(tetra, "tab"), 3);
  // One start square per piece, one alignment stroke per glued edge copy.
  BOOST_CHECK_EQUAL(count_class(cube, "start-mark"), 1);
  BOOST_CHECK_EQUAL(count_class(cube, "align-mark"), 2 * glued_pairs(nets[0]));

  // Every glued edge label appears exactly twice, inside the piece it belongs to.
  for (const auto& [node, net, letter] :
       {std::tuple<const XmlNode*, const Net*, std::string>{&cube, &nets[0], "A"}, {&tetra, &nets[1], "B"}}) {
    std::map<std::string, int> seen;
    for (const XmlNode* t : all(*node, "text"))
      if (has_class(*t, "edge-label")) ++seen[t->text];
    BOOST_CHECK_EQUAL(seen.size(), static_cast<std::size_t>(glued_pairs(*net)));
    for (const auto& [label, n] : seen) {
      BOOST_CHECK_EQUAL(n, 2);
      BOOST_CHECK(label.rfind(letter, 0) == 0);
    }
    // Each label's anchor lies inside its piece on paper (not on a tab, not on another piece).
    const auto& pl = L.pieces[net == &nets[0] ? 0 : 1];
    for (const XmlNode* t : all(*node, "text")) {
      const V2 at(std::stod(t->attrs.at("x")), std::stod(t->attrs.at("y")));
      bool inside = false;
      for (const auto& tri : net->corners) {
        V2 q[3];
        for (int k = 0; k < 3; ++k) q[k] = pl.linear * tri[k] + pl.offset;
        int sign = 0;
        bool in = true;
        for (int k = 0; k < 3 && in; ++k) {
          const V2 e = q[(k + 1) % 3] - q[k], d = at - q[k];
          const int s = e.x() * d.y() - e.y() * d.x() > 0 ? 1 : -1;
          in = sign == 0 || s == sign;
          sign = s;
        }
        inside = inside || in;
      }
      BOOST_CHECK_MESSAGE(inside, "text '" << t->text << "' at " << at.transpose() << " is outside its piece");
    }
    std::vector<std::string> names;
    for (const XmlNode* t : all(*node, "text"))
      if (has_class(*t, "piece-name")) names.push_back(t->text);
    BOOST_REQUIRE_EQUAL(names.size(), 1u);
    BOOST_CHECK_EQUAL(names[0], net->name + " (" + letter + ")");
  }
}

BOOST_AUTO_TEST_CASE(labels_are_not_smaller_than_the_minimum) {
  // A tiny scale: labels clamp to a readable size instead of shrinking with the piece.
  SheetOptions o;
  o.scale_mm_per_unit = 10;
  const XmlNode root = XmlParser(render({cube_cross("cube")}, o)).parse();
  int labels = 0;
  for (const XmlNode* t : all(root, "text")) {
    BOOST_CHECK_GE(std::stod(t->attrs.at("font-size")), 2.0);
    labels += has_class(*t, "edge-label");
  }
  BOOST_CHECK_EQUAL(labels, 2 * glued_pairs(cube_cross("cube")));
}

BOOST_AUTO_TEST_CASE(tabs_can_be_turned_off) {
  SheetOptions o;
  o.tabs = false;
  const std::vector<Net> nets = {cube_cross("cube")};
  const XmlNode root = XmlParser(render(nets, o)).parse();
  BOOST_CHECK_EQUAL(count_class(root, "tab"), 1);  // the legend sample only
  BOOST_CHECK_EQUAL(count_class(root, "tab-fold"), 0);
  BOOST_CHECK_EQUAL(count_class(root, "edge-label"), 2 * glued_pairs(nets[0]));
  check_layout(nets, dcshell::layout_net_sheets(nets, o), false);
}

BOOST_AUTO_TEST_CASE(fit_scale_is_the_largest_that_fits) {
  const std::vector<Net> nets = {cube_cross("cube"), tetra_star("tetra")};
  SheetOptions o;
  const SheetLayout L = dcshell::layout_net_sheets(nets, o);
  check_layout(nets, L, true);
  BOOST_CHECK_GT(L.scale_mm_per_unit, 0);
  // The limiting piece nearly fills the printable area in one direction.
  std::size_t limiting = 0;
  double fill = 0;
  for (std::size_t i = 0; i < L.pieces.size(); ++i) {
    const auto& p = L.pieces[i];
    const double f = std::max(p.width_mm / L.area_width_mm, p.height_mm / L.area_height_mm);
    if (f > fill) fill = f, limiting = i;
  }
  BOOST_CHECK_GT(fill, 0.98);
  // It has 3 significant digits, and the next such scale up does not fit.
  const double e = std::pow(10.0, std::floor(std::log10(L.scale_mm_per_unit)) - 2);
  const double k = std::round(L.scale_mm_per_unit / e);
  BOOST_CHECK(k >= 100 && k <= 999);
  BOOST_CHECK_CLOSE(k * e, L.scale_mm_per_unit, 1e-9);
  SheetOptions next = o;
  next.scale_mm_per_unit = (k + 1) * e;
  BOOST_CHECK_THROW(dcshell::layout_net_sheets(nets, next), std::invalid_argument);
  // 2% larger does not fit: an error naming the piece and the scale that would.
  o.scale_mm_per_unit = L.scale_mm_per_unit * 1.02;
  try {
    dcshell::layout_net_sheets(nets, o);
    BOOST_ERROR("a piece larger than the page was accepted");
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    BOOST_CHECK_MESSAGE(msg.find("'" + nets[limiting].name + "'") != std::string::npos, msg);
    BOOST_CHECK_MESSAGE(msg.find("fits at scale") != std::string::npos, msg);
  }
}

BOOST_AUTO_TEST_CASE(many_pieces_pack_onto_pages_without_overlap) {
  std::vector<Net> nets;
  for (int i = 0; i < 9; ++i) nets.push_back(i % 3 == 2 ? tetra_star("t" + std::to_string(i)) : cube_cross("c" + std::to_string(i)));
  SheetOptions o;
  o.scale_mm_per_unit = 25;
  const SheetLayout L = dcshell::layout_net_sheets(nets, o);
  BOOST_CHECK_EQUAL(L.scale_mm_per_unit, 25);
  BOOST_CHECK_GE(L.sheet_pages, 2);
  check_layout(nets, L, true);
  // Every page is used, and the SVG has one page group per page and one group per piece.
  std::set<int> used;
  for (const auto& p : L.pieces) used.insert(p.page);
  BOOST_CHECK_EQUAL(used.size(), static_cast<std::size_t>(L.sheet_pages));
  const XmlNode root = XmlParser(render(nets, o)).parse();
  BOOST_CHECK_EQUAL(count_class(root, "page"), L.sheet_pages);
  BOOST_CHECK_EQUAL(count_class(root, "piece"), 9);
  // Letter paper, landscape custom paper: still valid layouts.
  for (const char* paper : {"letter", "300x200mm"}) {
    SheetOptions p = SheetOptions::paper_from_string(paper);
    check_layout(nets, dcshell::layout_net_sheets(nets, p), true);
  }
}

BOOST_AUTO_TEST_CASE(pdf_xref_points_at_objects) {
  const std::vector<Net> nets = {cube_cross("cube"), tetra_star("tetra")};
  const std::vector<AssemblyJoin> joins = {{"cube", "tetra", "cut plane 1: x + y = 1 (glue the flat faces)"},
                                           {"tetra", "other(shell)", ""}};
  SheetOptions o;
  o.format = SheetOptions::Format::pdf;
  o.scale_mm_per_unit = 30;
  const std::string pdf = render(nets, o, joins);
  BOOST_CHECK(pdf.rfind("%PDF-1.4\n", 0) == 0);
  BOOST_CHECK(pdf.size() > 6 && pdf.compare(pdf.size() - 6, 6, "%%EOF\n") == 0);

  const std::size_t sx = pdf.rfind("startxref\n");
  BOOST_REQUIRE(sx != std::string::npos);
  const std::size_t xref = std::stoul(pdf.substr(sx + 10));
  BOOST_REQUIRE(pdf.compare(xref, 5, "xref\n") == 0);
  std::istringstream in(pdf.substr(xref + 5));
  int first = -1, count = 0;
  in >> first >> count;
  BOOST_REQUIRE_EQUAL(first, 0);
  BOOST_REQUIRE_GT(count, 3);
  std::string line;
  std::getline(in, line);  // end of the "0 N" line
  for (int id = 0; id < count; ++id) {
    char entry[21] = {};
    in.read(entry, 20);
    BOOST_REQUIRE_EQUAL(in.gcount(), 20);  // xref entries are exactly 20 bytes
    const std::string e(entry, 20);
    if (id == 0) { BOOST_CHECK_EQUAL(e, "0000000000 65535 f \n"); continue; }
    BOOST_CHECK_EQUAL(e.substr(10), " 00000 n \n");
    const std::size_t off = std::stoul(e.substr(0, 10));
    const std::string head = std::to_string(id) + " 0 obj";
    BOOST_CHECK_MESSAGE(pdf.compare(off, head.size(), head) == 0, "xref entry " << id << " -> " << off);
  }
  BOOST_CHECK(pdf.find("/Size " + std::to_string(count) + " ") != std::string::npos);

  // Stream lengths match, pages = sheets + assembly, A4 MediaBox in points, Helvetica text.
  std::size_t streams = 0;
  for (std::size_t at = pdf.find("/Length "); at != std::string::npos; at = pdf.find("/Length ", at + 1)) {
    const std::size_t len = std::stoul(pdf.substr(at + 8));
    const std::size_t data = pdf.find("stream\n", at) + 7;
    BOOST_CHECK_EQUAL(pdf.compare(data + len, 9, "endstream"), 0);
    ++streams;
  }
  const SheetLayout L = dcshell::layout_net_sheets(nets, o);
  BOOST_CHECK_EQUAL(streams, static_cast<std::size_t>(L.sheet_pages + 1));
  BOOST_CHECK(pdf.find("/Count " + std::to_string(L.sheet_pages + 1) + " ") != std::string::npos);
  BOOST_CHECK(pdf.find("/MediaBox [0 0 595.276 841.89]") != std::string::npos);
  BOOST_CHECK(pdf.find("/BaseFont /Helvetica ") != std::string::npos);
  for (int k = 1; k <= glued_pairs(nets[0]); ++k) {
    const std::string tj = "(A" + std::to_string(k) + ") Tj";
    std::size_t n = 0;
    for (std::size_t at = pdf.find(tj); at != std::string::npos; at = pdf.find(tj, at + 1)) ++n;
    BOOST_CHECK_EQUAL(n, 2u);
  }
  BOOST_CHECK(pdf.find("cube \\(A\\) + tetra \\(B\\):") != std::string::npos);
  BOOST_CHECK(pdf.find("other\\(shell\\)") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(assembly_page_in_svg) {
  const std::vector<Net> nets = {cube_cross("shell_000"), tetra_star("shell_001")};
  std::vector<AssemblyJoin> joins;
  for (int i = 0; i < 80; ++i)  // long enough to need a second assembly page
    joins.push_back({"shell_000", "shell_001", "cut plane " + std::to_string(i) + ": 0.5 x + 0.25 y - z = 0.125"});
  SheetOptions o;
  const XmlNode root = XmlParser(render(nets, o, joins)).parse();
  const SheetLayout L = dcshell::layout_net_sheets(nets, o);
  const int assembly_pages = count_class(root, "assembly") / 2;  // page group + its content group
  BOOST_CHECK_GE(assembly_pages, 2);
  BOOST_CHECK_EQUAL(count_class(root, "page"), L.sheet_pages + assembly_pages);
  int lines = 0;
  for (const XmlNode* t : all(root, "text"))
    lines += t->text.find("cut plane 79: 0.5 x") != std::string::npos || t->text.rfind("1. shell_000 (A) + shell_001 (B)", 0) == 0;
  BOOST_CHECK_EQUAL(lines, 2);
}

BOOST_AUTO_TEST_CASE(output_is_deterministic) {
  const std::vector<Net> nets = {tetra_star("t"), cube_cross("c"), cube_cross("c")};  // duplicate names get unique ids
  const std::vector<AssemblyJoin> joins = {{"t", "c", "plane"}};
  for (auto f : {SheetOptions::Format::svg, SheetOptions::Format::pdf}) {
    SheetOptions o;
    o.format = f;
    const std::string a = render(nets, o, joins), b = render(nets, o, joins);
    BOOST_CHECK(!a.empty());
    BOOST_CHECK(a == b);
  }
  const XmlNode root = XmlParser(render(nets, SheetOptions())).parse();
  std::set<std::string> ids;
  for (const XmlNode* g : all(root, "g"))
    if (has_class(*g, "piece")) BOOST_CHECK(ids.insert(g->attrs.at("id")).second);
  BOOST_CHECK_EQUAL(ids.size(), 3u);
}

BOOST_AUTO_TEST_CASE(bad_input_is_rejected) {
  SheetOptions o;
  BOOST_CHECK_THROW(render({}, o), std::invalid_argument);
  Net broken = cube_cross("broken");
  broken.corners.pop_back();
  BOOST_CHECK_THROW(render({broken}, o), std::invalid_argument);
  Net mirrored = tetra_star("mirrored");
  for (auto& t : mirrored.corners)
    for (auto& c : t) c.x() = -c.x();
  BOOST_CHECK_THROW(render({mirrored}, o), std::invalid_argument);
  Net one_mirrored_face = cube_cross("one mirrored face");
  for (auto& c : one_mirrored_face.corners[5]) c.x() = -c.x();
  BOOST_CHECK_THROW(render({one_mirrored_face}, o), std::invalid_argument);
  Net wrong_edge = tetra_star("wrong");
  std::swap(wrong_edge.edges[0].v0, wrong_edge.edges[0].v1);
  BOOST_CHECK_THROW(render({wrong_edge}, o), std::invalid_argument);
  // The reasons, net by net, so that a caller can leave a bad net off and print the rest.
  BOOST_TEST(dcshell::net_sheet_problem(cube_cross("good")).empty());
  BOOST_TEST(dcshell::net_sheet_problem(tetra_star("good")).empty());
  BOOST_TEST(dcshell::net_sheet_problem(one_mirrored_face) == "face 5 is clockwise in the net (mirrored)");
  BOOST_TEST(dcshell::net_sheet_problem(mirrored).find("mirrored") != std::string::npos);
  BOOST_TEST(dcshell::net_sheet_problem(broken).find("sizes do not match") != std::string::npos);
  BOOST_TEST(dcshell::net_sheet_problem(wrong_edge).find("is not an edge") != std::string::npos);
  BOOST_CHECK_NO_THROW(render({cube_cross("a"), tetra_star("b")}, o));
  SheetOptions tiny = SheetOptions::paper_from_string("30x30mm");
  BOOST_CHECK_THROW(render({tetra_star("t")}, tiny), std::invalid_argument);
  BOOST_TEST(dcshell::net_sheet_problem(tetra_star("t")).empty());  // the paper's problem, not the net's
  SheetOptions negative;
  negative.scale_mm_per_unit = -1;
  BOOST_CHECK_THROW(render({tetra_star("t")}, negative), std::invalid_argument);
}

BOOST_AUTO_TEST_SUITE_END()
