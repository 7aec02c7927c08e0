// Printable sheets: geometry of the printed pieces (tabs, labels, marks), scale fitting and
// packing, and a small display list that the SVG and PDF writers (net_sheets_writers.cpp)
// both render, so the two formats show exactly the same drawing.
#include "net_sheets_doc.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

namespace dcshell {
namespace sheets {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Layout constants, in mm on paper.
constexpr double kGapMm = 3.0;            // between pieces: room for the scissors
constexpr double kPadMm = 0.5;            // footprint padding: half line widths plus safety
constexpr double kTabMaxMm = 6.0;         // glue tab height
constexpr double kStrokeHalfMm = 1.5;     // half-length of the alignment strokes
constexpr double kMinFontMm = 2.0;        // smallest text a child can still read
constexpr double kMaxLabelFontMm = 3.5;
constexpr double kMaxNameFontMm = 5.0;
constexpr double kMaxStartMarkMm = 5.0;
constexpr double kLegendFontMm = 3.0;
constexpr double kLegendRowMm = 5.5;
constexpr double kLegendSampleMm = 8.0;
constexpr double kFlatFoldRad = 1e-3;     // |fold angle| below this (0.06 deg): flat, no fold line drawn
constexpr double kEps = 1e-9;
// Layout of wrapped text and of the legend assumes a font this much wider than Helvetica, so a
// viewer's substitute font (SVG) still fits.
constexpr double kFallbackFontSlack = 1.12;

double cross2(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }
V2 left_normal(const V2& u) { return V2(-u.y(), u.x()); }

std::vector<V2> convex_hull(std::vector<V2> p) {
  std::sort(p.begin(), p.end(), [](const V2& a, const V2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<V2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross2(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross2(h[k - 1] - h[k - 2], p[i - 1] - h[k - 2]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

/// Direction angle of the minimum-area bounding rectangle (rotating calipers: one side of the
/// optimal rectangle lies along a hull edge, so trying every hull edge is exact).
double min_area_rect_angle(const std::vector<V2>& hull) {
  if (hull.size() < 2) return 0.0;
  double best_area = std::numeric_limits<double>::infinity(), best_angle = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    V2 e = hull[(i + 1) % hull.size()] - hull[i];
    if (e.norm() <= 0) continue;
    V2 u = e.normalized(), v = left_normal(u);
    double u0 = std::numeric_limits<double>::infinity(), u1 = -u0, v0 = u0, v1 = -u0;
    for (const V2& p : hull) {
      u0 = std::min(u0, p.dot(u)), u1 = std::max(u1, p.dot(u));
      v0 = std::min(v0, p.dot(v)), v1 = std::max(v1, p.dot(v));
    }
    double area = (u1 - u0) * (v1 - v0);
    if (area < best_area * (1 - 1e-9)) best_area = area, best_angle = std::atan2(u.y(), u.x());
  }
  return best_angle;
}

/// Interiors of two convex polygons overlap (separating axis test; touching is not overlap).
bool convex_overlap(const std::vector<V2>& p, const std::vector<V2>& q, double eps) {
  for (const std::vector<V2>* poly : {&p, &q}) {
    for (std::size_t i = 0; i < poly->size(); ++i) {
      V2 e = (*poly)[(i + 1) % poly->size()] - (*poly)[i];
      if (e.norm() <= 0) continue;
      V2 axis = left_normal(e.normalized());
      double p0 = std::numeric_limits<double>::infinity(), p1 = -p0, q0 = p0, q1 = -p0;
      for (const V2& a : p) p0 = std::min(p0, a.dot(axis)), p1 = std::max(p1, a.dot(axis));
      for (const V2& a : q) q0 = std::min(q0, a.dot(axis)), q1 = std::max(q1, a.dot(axis));
      if (p1 <= q0 + eps || q1 <= p0 + eps) return false;
    }
  }
  return true;
}

std::string piece_letter(std::size_t i) {
  std::string s;
  for (std::size_t n = i + 1; n > 0; n = (n - 1) / 26) s.insert(s.begin(), char('A' + (n - 1) % 26));
  return s;
}

std::string xml_id(const std::string& name) {
  std::string s;
  for (char c : name)
    s += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.') ? c : '_';
  return s;
}

/// At most 3 significant digits, never an exponent: "37.4", "0.000123", "1230".
std::string fmt_scale(double s) {
  const int decimals = s > 0 ? std::clamp(2 - static_cast<int>(std::floor(std::log10(s))), 0, 12) : 0;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, s);
  std::string r = buf;
  for (char& c : r)
    if (c == ',') c = '.';  // a C library locale must not change the printed scale
  if (r.find('.') != std::string::npos) {
    while (r.back() == '0') r.pop_back();
    if (r.back() == '.') r.pop_back();
  }
  return r;
}

double round_down_3_significant(double s) {
  double p = std::pow(10.0, std::floor(std::log10(s)) - 2);
  double r = std::floor(s / p * (1 + 1e-12)) * p;
  return r > 0 && r <= s ? r : s;
}

// ---------------------------------------------------------------------------------------
// Scale-independent description of one piece, checked against the Net contract.

struct CutCopy {
  int edge = -1;
  int face = -1;
  V2 a, b;            // net plane; the piece is on the left of a->b
  std::string label;  // empty for an open boundary edge (no partner to glue to)
};

struct FoldLine {
  V2 a, b;
  bool mountain = true;
};

struct PieceModel {
  std::size_t index = 0;
  std::string name, letter, id;
  std::vector<std::array<V2, 3>> tris;
  std::vector<CutCopy> cuts;
  std::vector<std::array<int, 2>> glued;  // pairs of indices into cuts, in edge order
  std::vector<bool> glued_mountain;
  std::vector<FoldLine> folds;
  int root = 0;
  V2 name_center = V2::Zero();  // where the shell id goes, and the radius of free room there
  double name_room = 0;
  bool name_on_root = false;
  double diameter = 0;
};

// An inconsistent net; `reason` without the net's name (net_sheet_problem).
struct BadNet : std::invalid_argument {
  std::string reason;
  BadNet(const PieceModel& m, const std::string& what)
      : std::invalid_argument("sheets: net " + std::to_string(m.index) + " ('" + m.name + "'): " + what), reason(what) {}
};

[[noreturn]] void bad_net(const PieceModel& m, const std::string& what) { throw BadNet(m, what); }

int find_directed(const Net& net, int f, int from, int to) {
  for (int k = 0; k < 3; ++k)
    if (net.shell_faces[f][k] == from && net.shell_faces[f][(k + 1) % 3] == to) return k;
  return -1;
}

double inradius(const std::array<V2, 3>& t) {
  double per = (t[1] - t[0]).norm() + (t[2] - t[1]).norm() + (t[0] - t[2]).norm();
  return per > 0 ? std::abs(cross2(t[1] - t[0], t[2] - t[0])) / per : 0.0;
}

double segment_distance(const V2& p, const V2& a, const V2& b) {
  const V2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

V2 incenter(const std::array<V2, 3>& t) {
  double la = (t[1] - t[2]).norm(), lb = (t[2] - t[0]).norm(), lc = (t[0] - t[1]).norm();
  double s = la + lb + lc;
  return s > 0 ? V2((la * t[0] + lb * t[1] + lc * t[2]) / s) : t[0];
}

PieceModel make_model(const Net& net, std::size_t index) {
  PieceModel m;
  m.index = index;
  m.name = net.name.empty() ? "piece" + std::to_string(index + 1) : net.name;
  m.letter = piece_letter(index);
  const int nf = static_cast<int>(net.shell_faces.size());
  const int nv = static_cast<int>(net.shell_vertices.size());
  if (nf == 0) bad_net(m, "no faces");
  if (static_cast<int>(net.corners.size()) != nf || static_cast<int>(net.parent.size()) != nf)
    bad_net(m, "corners/parent sizes do not match the number of faces");
  m.root = -1;
  double area = 0;
  for (int f = 0; f < nf; ++f) {
    for (int v : net.shell_faces[f])
      if (v < 0 || v >= nv) bad_net(m, "face " + std::to_string(f) + " has vertex index out of range");
    for (const V2& c : net.corners[f])
      if (!c.allFinite()) bad_net(m, "face " + std::to_string(f) + " has a non-finite corner");
    if (net.parent[f] < -1 || net.parent[f] >= nf) bad_net(m, "parent of face " + std::to_string(f) + " out of range");
    if (net.parent[f] == -1 && m.root < 0) m.root = f;
    m.tris.push_back(net.corners[f]);
    const auto& t = net.corners[f];
    const double a2 = cross2(t[1] - t[0], t[2] - t[0]);
    const double longest2 = std::max({(t[1] - t[0]).squaredNorm(), (t[2] - t[1]).squaredNorm(), (t[0] - t[2]).squaredNorm()});
    // A clockwise face would be printed mirrored and get its tabs on the wrong side.
    if (a2 < -1e-12 * longest2) bad_net(m, "face " + std::to_string(f) + " is clockwise in the net (mirrored)");
    area += a2 / 2;
  }
  if (m.root < 0) bad_net(m, "no root face (parent == -1)");
  if (!(area > 0)) bad_net(m, "zero area");

  int glue_number = 0;
  struct Flat { int f0, f1, k0; };  // coplanar faces: printed as one region, no fold line
  std::vector<Flat> flat;
  for (std::size_t i = 0; i < net.edges.size(); ++i) {
    const Net::Edge& e = net.edges[i];
    const std::string where = "edge " + std::to_string(i);
    if (e.f0 < 0 || e.f0 >= nf || e.f1 < -1 || e.f1 >= nf) bad_net(m, where + " has a face index out of range");
    int k0 = find_directed(net, e.f0, e.v0, e.v1);
    if (k0 < 0) bad_net(m, where + " is not an edge v0->v1 of face f0");
    const V2 a = net.corners[e.f0][k0], b = net.corners[e.f0][(k0 + 1) % 3];
    if (e.fold) {
      if (e.f1 < 0) bad_net(m, where + " is a fold with only one face");
      if (std::abs(e.fold_angle) > kFlatFoldRad) m.folds.push_back({a, b, e.mountain});
      else flat.push_back({e.f0, e.f1, k0});
      continue;
    }
    m.cuts.push_back({static_cast<int>(i), e.f0, a, b, ""});
    if (e.f1 < 0) continue;  // open boundary: cut, nothing to glue
    int k1 = find_directed(net, e.f1, e.v1, e.v0);
    if (k1 < 0) bad_net(m, where + " is not an edge v1->v0 of face f1");
    const std::string label = m.letter + std::to_string(++glue_number);
    m.cuts.back().label = label;
    m.cuts.push_back({static_cast<int>(i), e.f1, net.corners[e.f1][k1], net.corners[e.f1][(k1 + 1) % 3], label});
    const int c = static_cast<int>(m.cuts.size());
    m.glued.push_back({c - 2, c - 1});
    m.glued_mountain.push_back(e.mountain);
  }

  // The shell id goes where there is most room: a face's incircle, or the middle of a flat fold
  // (two coplanar triangles print as one region, e.g. a square). Not on the root region, which
  // holds the start mark, unless there is nothing else; among equal rooms, farthest from the root.
  struct Spot { V2 center; double room; bool on_root; };
  std::vector<Spot> spots;
  for (int f = 0; f < nf; ++f) spots.push_back({incenter(m.tris[f]), inradius(m.tris[f]), f == m.root});
  for (const Flat& fl : flat) {
    const V2 A = m.tris[fl.f0][fl.k0], B = m.tris[fl.f0][(fl.k0 + 1) % 3], mid = (A + B) / 2;
    const double tol = 1e-9 * (B - A).norm();
    double room = std::numeric_limits<double>::infinity();
    for (int f : {fl.f0, fl.f1})
      for (int k = 0; k < 3; ++k) {  // the four outer edges; the shared one passes through mid
        const V2 p = m.tris[f][k], q = m.tris[f][(k + 1) % 3];
        const bool shared = ((p - A).norm() <= tol && (q - B).norm() <= tol) || ((p - B).norm() <= tol && (q - A).norm() <= tol);
        if (!shared) room = std::min(room, segment_distance(mid, p, q));
      }
    spots.push_back({mid, room, fl.f0 == m.root || fl.f1 == m.root});
  }
  const V2 root_center = incenter(m.tris[m.root]);
  const Spot* best = nullptr;
  for (const Spot& sp : spots) {
    if (!best) { best = &sp; continue; }
    if (sp.on_root != best->on_root) { if (!sp.on_root) best = &sp; continue; }
    const double d = (sp.center - root_center).norm(), bd = (best->center - root_center).norm();
    if (sp.room > best->room * (1 + 1e-6) || (sp.room >= best->room * (1 - 1e-6) && d > bd * (1 + 1e-9))) best = &sp;
  }
  m.name_center = best->center, m.name_room = best->room, m.name_on_root = best->on_root;

  std::vector<V2> pts;
  for (const auto& t : m.tris) pts.insert(pts.end(), t.begin(), t.end());
  std::vector<V2> hull = convex_hull(pts);
  for (std::size_t i = 0; i < hull.size(); ++i)
    for (std::size_t j = i + 1; j < hull.size(); ++j) m.diameter = std::max(m.diameter, (hull[i] - hull[j]).norm());
  if (!(m.diameter > 0)) bad_net(m, "degenerate (all corners coincide)");
  return m;
}

// ---------------------------------------------------------------------------------------
// A piece at a given scale: tabs and the footprint (in mm, net orientation).

struct Tab {
  int cut = -1;  // index into PieceModel::cuts
  std::array<V2, 4> quad;
};

struct PieceShape {
  double scale = 0;
  std::vector<Tab> tabs;
  std::vector<V2> footprint;
};

std::array<V2, 4> tab_quad(const V2& a, const V2& b, double h, double inset) {
  V2 u = (b - a).normalized(), n(u.y(), -u.x());  // n points away from the piece
  return {a, V2(a + n * h + u * inset), V2(b + n * h - u * inset), b};
}

double stroke_half(double len_mm) { return std::min(kStrokeHalfMm, 0.15 * len_mm); }

/// Convex polygons (the piece's faces, then the tabs placed so far) in a uniform grid of buckets,
/// so that testing a candidate tab costs about the number of polygons near it, not all of them
/// (pieces can have thousands of faces, and the scale search builds the tabs many times).
class ObstacleIndex {
 public:
  ObstacleIndex(const PieceModel& m, double s) : eps_(1e-7 * std::max(1.0, m.diameter * s)) {
    V2 lo = V2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const auto& t : m.tris)
      for (const V2& p : t) lo = lo.cwiseMin(V2(p * s)), hi = hi.cwiseMax(V2(p * s));
    lo.array() -= kTabMaxMm, hi.array() += kTabMaxMm;  // tabs stay within this box
    const double side = std::max(1e-9, std::max(hi.x() - lo.x(), hi.y() - lo.y()));
    const int n = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(m.tris.size()))), 1, 512);
    origin_ = lo, cell_ = side / n, nx_ = n, ny_ = n;
    cells_.resize(static_cast<std::size_t>(nx_) * ny_);
    for (const auto& t : m.tris) add({V2(t[0] * s), V2(t[1] * s), V2(t[2] * s)});
  }

  void add(std::vector<V2> poly) {
    Item it{std::move(poly), V2::Zero(), V2::Zero()};
    bounds(it.poly, it.lo, it.hi);
    const int id = static_cast<int>(items_.size());
    items_.push_back(std::move(it));
    stamp_.push_back(0);
    for_cells(items_.back().lo, items_.back().hi, [&](std::vector<int>& cell) { cell.push_back(id); });
  }

  /// The polygon's interior meets no obstacle's interior.
  bool clear(const std::vector<V2>& q) {
    V2 lo, hi;
    bounds(q, lo, hi);
    ++query_;
    bool ok = true;
    for_cells(lo, hi, [&](std::vector<int>& cell) {
      for (int id : cell) {
        if (!ok || stamp_[id] == query_) continue;
        stamp_[id] = query_;
        const Item& o = items_[id];
        if (o.lo.x() >= hi.x() - eps_ || o.hi.x() <= lo.x() + eps_ || o.lo.y() >= hi.y() - eps_ || o.hi.y() <= lo.y() + eps_)
          continue;
        ok = !convex_overlap(q, o.poly, eps_);
      }
    });
    return ok;
  }

 private:
  struct Item {
    std::vector<V2> poly;
    V2 lo, hi;
  };
  static void bounds(const std::vector<V2>& poly, V2& lo, V2& hi) {
    lo = V2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const V2& p : poly) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  int index(double v, double o, int n) const {
    return std::clamp(static_cast<int>(std::floor((v - o) / cell_)), 0, n - 1);
  }
  template <class F>
  void for_cells(const V2& lo, const V2& hi, F&& f) {
    const int x0 = index(lo.x(), origin_.x(), nx_), x1 = index(hi.x(), origin_.x(), nx_);
    const int y0 = index(lo.y(), origin_.y(), ny_), y1 = index(hi.y(), origin_.y(), ny_);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) f(cells_[static_cast<std::size_t>(y) * nx_ + x]);
  }

  double eps_, cell_ = 1;
  V2 origin_ = V2::Zero();
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> cells_;
  std::vector<Item> items_;
  std::vector<unsigned> stamp_;  // last query that looked at the item (each item tested once per query)
  unsigned query_ = 0;
};

/// Tabs go on one copy of each glued pair: the copy whose largest non-overlapping tab is bigger
/// (ties: the f0 copy). Candidates shrink in height and steepen their sides, because near a
/// sharp outer corner only steeper sides clear the neighbouring face.
std::vector<Tab> make_tabs(const PieceModel& m, double s) {
  ObstacleIndex obstacles(m, s);
  std::vector<Tab> tabs;
  for (const auto& pair : m.glued) {
    Tab best;
    double best_area = 0;
    for (int side = 0; side < 2; ++side) {
      const CutCopy& c = m.cuts[pair[side]];
      const V2 a = c.a * s, b = c.b * s;
      const double len = (b - a).norm();
      bool found = false;
      for (double deg : {45.0, 30.0, 15.0}) {
        const double tn = std::tan(deg * kPi / 180);
        for (double f : {1.0, 0.7, 0.5, 0.35, 0.25}) {
          const double h = std::min(kTabMaxMm, 0.3 * len * tn) * f;
          std::array<V2, 4> q = tab_quad(a, b, h, h / tn);
          std::vector<V2> qv(q.begin(), q.end());
          if (!(h > 0) || !obstacles.clear(qv)) continue;
          const double area = h * (len - h / tn);
          if (area > best_area * (1 + 1e-9)) best_area = area, best = {pair[side], q};
          found = true;
          break;
        }
        if (found) break;
      }
    }
    if (best.cut < 0) {  // no clear tab on either side: a small one on the f0 copy still says where to glue
      const CutCopy& c = m.cuts[pair[0]];
      const double len = (c.b - c.a).norm() * s, h = std::min(kTabMaxMm, 0.3 * len) * 0.25;
      best = {pair[0], tab_quad(c.a * s, c.b * s, h, h)};
    }
    tabs.push_back(best);
    obstacles.add(std::vector<V2>(best.quad.begin(), best.quad.end()));
  }
  return tabs;
}

PieceShape make_shape(const PieceModel& m, double s, bool with_tabs) {
  PieceShape sh;
  sh.scale = s;
  if (with_tabs) sh.tabs = make_tabs(m, s);
  for (const auto& t : m.tris)
    for (const V2& p : t) sh.footprint.push_back(p * s);
  for (const Tab& t : sh.tabs) sh.footprint.insert(sh.footprint.end(), t.quad.begin(), t.quad.end());
  for (const CutCopy& c : m.cuts) {
    if (c.label.empty()) continue;
    const V2 a = c.a * s, b = c.b * s, mid = (a + b) / 2, n = left_normal((b - a).normalized());
    const double hl = stroke_half((b - a).norm());
    sh.footprint.push_back(mid + n * hl);
    sh.footprint.push_back(mid - n * hl);
  }
  return sh;
}

// ---------------------------------------------------------------------------------------
// Orientation and packing.

struct Orientation {
  bool fits = false;
  double theta = 0;  // rotation applied to the piece (net plane, radians)
  double w = 0, h = 0, minx = 0, maxy = 0;
};

Orientation oriented_box(const std::vector<V2>& hull, double theta, double area_w, double area_h) {
  Orientation r;
  r.theta = theta;
  const double c = std::cos(theta), sn = std::sin(theta);
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const V2& p : hull) {
    const double x = c * p.x() - sn * p.y(), y = sn * p.x() + c * p.y();
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  r.w = x1 - x0 + 2 * kPadMm, r.h = y1 - y0 + 2 * kPadMm, r.minx = x0, r.maxy = y1;
  r.fits = r.w <= area_w + kEps && r.h <= area_h + kEps;
  return r;
}

/// The minimum-area bounding rectangle's orientation (landscape first: flat pieces make low
/// shelves). If that does not fit the page, another rotating-calipers orientation may (a long
/// piece fits along the page diagonal direction it would otherwise waste): the one that leaves
/// the most room. Without any fit, the closest miss (for the error message).
Orientation orient(const std::vector<V2>& footprint, double area_w, double area_h) {
  const std::vector<V2> hull = convex_hull(footprint);
  const double phi = min_area_rect_angle(hull);
  const Orientation o0 = oriented_box(hull, -phi, area_w, area_h), o1 = oriented_box(hull, -phi - kPi / 2, area_w, area_h);
  const Orientation& first = o0.w >= o0.h ? o0 : o1;
  const Orientation& second = o0.w >= o0.h ? o1 : o0;
  if (first.fits) return first;
  if (second.fits) return second;
  auto ratio = [&](const Orientation& o) { return std::max(o.w / area_w, o.h / area_h); };
  Orientation best = ratio(o0) <= ratio(o1) ? o0 : o1;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const V2 e = hull[(i + 1) % hull.size()] - hull[i];
    for (int turn = 0; turn < 2; ++turn) {
      const Orientation o = oriented_box(hull, -std::atan2(e.y(), e.x()) - turn * kPi / 2, area_w, area_h);
      if ((o.fits && !best.fits) || (o.fits == best.fits && ratio(o) < ratio(best) * (1 - 1e-9))) best = o;
    }
  }
  return best;
}

bool fits_at(const PieceModel& m, double s, const SheetOptions& opt, double aw, double ah) {
  return orient(make_shape(m, s, opt.tabs).footprint, aw, ah).fits;
}

// Scales are printed with 3 significant digits, k x 10^e with k in 100 .. 999; index them in
// increasing order, 900 e + k - 100, so the largest one that fits is found by bisecting integers.
double three_digit_scale(long long index) {
  const long long e = index >= 0 ? index / 900 : -((-index + 899) / 900);
  return static_cast<double>(100 + index - 900 * e) * std::pow(10.0, static_cast<double>(e));
}

long long three_digit_index(double s) {  // of the largest 3-digit scale <= s (s > 0)
  long long e = static_cast<long long>(std::floor(std::log10(s))) - 2;
  long long index = 900 * e + static_cast<long long>(std::floor(s / std::pow(10.0, static_cast<double>(e)) * (1 + 1e-12))) - 100;
  while (three_digit_scale(index) > s) --index;  // log10 and the division may round up
  while (three_digit_scale(index + 1) <= s) ++index;
  return index;
}

// The largest 3-digit scale at which the piece fits the printable area (fitting is monotone in
// the scale): about 11 layouts of the piece, where bisecting the scale to 6e-8 took 26.
double max_fit_scale(const PieceModel& m, const SheetOptions& opt, double aw, double ah) {
  // A piece wider than the page diagonal cannot fit, so diag/diameter bounds the scale.
  double hi = std::hypot(aw, ah) / m.diameter, lo = hi;
  bool found = false;
  for (int i = 0; i < 200 && !found; ++i) found = fits_at(m, lo *= 0.5, opt, aw, ah);
  if (!found) throw std::invalid_argument("sheets: piece '" + m.name + "' does not fit on the page at any scale");
  // Invariant: scale a fits, scale b does not (b is above 2 lo, which did not fit, or above the bound).
  long long a = three_digit_index(lo), b = three_digit_index(std::min(hi, 2 * lo)) + 1;
  while (b - a > 1) {
    const long long mid = a + (b - a) / 2;
    (fits_at(m, three_digit_scale(mid), opt, aw, ah) ? a : b) = mid;
  }
  return three_digit_scale(a);
}

struct Legend {
  struct Item {
    Ink sample;
    std::string text;
    double x = 0;  // from the legend's left edge
    int row = 0;
  };
  std::vector<Item> items;
  int rows = 0;
  double height = 0;
};

Legend make_legend(double width) {
  Legend lg;
  const std::pair<Ink, const char*> entries[] = {
      {Ink::cut, "cut"},
      {Ink::mountain, "mountain fold"},
      {Ink::valley, "valley fold"},
      {Ink::tab, "glue tab: glue it under the edge with the same label"},
      {Ink::start, "start folding here"},
      {Ink::stroke, "line up the marks"},
  };
  double x = 0;
  int row = 0;
  for (const auto& [ink, text] : entries) {
    const double w = kLegendSampleMm + 2 + kFallbackFontSlack * text_width_mm(text, kLegendFontMm);
    if (x > 0 && x + w > width) x = 0, ++row;
    lg.items.push_back({ink, text, x, row});
    x += w + 6;
  }
  lg.rows = row + 1;
  lg.height = (lg.rows + 1) * kLegendRowMm + 2;  // + the page/scale line and a gap above
  return lg;
}

struct Layout {
  SheetLayout pub;
  std::vector<PieceModel> models;
  std::vector<PieceShape> shapes;
  Legend legend;
};

void check_options(const SheetOptions& o) {
  auto finite_pos = [](double v) { return std::isfinite(v) && v > 0; };
  if (!finite_pos(o.paper_width_mm) || !finite_pos(o.paper_height_mm))
    throw std::invalid_argument("sheets: paper size must be positive");
  if (!std::isfinite(o.margin_mm) || o.margin_mm < 0) throw std::invalid_argument("sheets: margin must be >= 0 mm");
  if (!std::isfinite(o.scale_mm_per_unit) || o.scale_mm_per_unit < 0)
    throw std::invalid_argument("sheets: scale must be >= 0 mm per unit (0 = fit to the page)");
}

Layout compute_layout(const std::vector<Net>& nets, const SheetOptions& opt) {
  check_options(opt);
  if (nets.empty()) throw std::invalid_argument("sheets: no nets to print");
  Layout L;
  const double aw = opt.paper_width_mm - 2 * opt.margin_mm;
  L.legend = make_legend(aw);
  const double ah = opt.paper_height_mm - 2 * opt.margin_mm - L.legend.height;
  if (aw < 20 || ah < 20)
    throw std::invalid_argument("sheets: paper " + fmt_scale(opt.paper_width_mm) + "x" + fmt_scale(opt.paper_height_mm) +
                                "mm with margin " + fmt_scale(opt.margin_mm) + "mm leaves no room for pieces");
  L.pub.area_x_mm = opt.margin_mm, L.pub.area_y_mm = opt.margin_mm, L.pub.area_width_mm = aw, L.pub.area_height_mm = ah;

  std::set<std::string> used_ids;
  for (std::size_t i = 0; i < nets.size(); ++i) {
    L.models.push_back(make_model(nets[i], i));
    PieceModel& m = L.models.back();
    std::string id = "piece-" + xml_id(m.name);
    for (int k = 2; used_ids.count(id); ++k) id = "piece-" + xml_id(m.name) + "-" + std::to_string(k);
    used_ids.insert(id);
    m.id = id;
  }

  double s = opt.scale_mm_per_unit;
  if (s == 0) {
    s = std::numeric_limits<double>::infinity();
    for (const PieceModel& m : L.models)  // a piece that fits at the current bound cannot lower it
      if (!(s < std::numeric_limits<double>::infinity() && fits_at(m, s, opt, aw, ah)))
        s = std::min(s, max_fit_scale(m, opt, aw, ah));
    s = round_down_3_significant(s);
  }
  L.pub.scale_mm_per_unit = s;

  std::vector<Orientation> orients;
  for (const PieceModel& m : L.models) {
    L.shapes.push_back(make_shape(m, s, opt.tabs));
    orients.push_back(orient(L.shapes.back().footprint, aw, ah));
    if (!orients.back().fits) {
      const Orientation& o = orients.back();
      throw std::invalid_argument("sheets: piece '" + m.name + "' is " + fmt_scale(o.w) + " x " + fmt_scale(o.h) +
                                  " mm at scale " + fmt_scale(s) + " mm per unit and does not fit the printable area " +
                                  fmt_scale(aw) + " x " + fmt_scale(ah) + " mm; it fits at scale " +
                                  fmt_scale(round_down_3_significant(max_fit_scale(m, opt, aw, ah))) +
                                  " mm per unit or less");
    }
  }

  // First-fit decreasing height shelf packing over pages.
  std::vector<std::size_t> order(L.models.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (orients[a].h != orients[b].h) return orients[a].h > orients[b].h;
    return orients[a].w > orients[b].w;
  });
  struct Shelf { int page; double y, h, x; };
  std::vector<Shelf> shelves;
  std::vector<double> page_next_y;
  L.pub.pieces.resize(L.models.size());
  for (std::size_t i : order) {
    const Orientation& o = orients[i];
    Shelf* shelf = nullptr;
    for (Shelf& sh : shelves)
      if (o.h <= sh.h + kEps && sh.x + o.w <= aw + kEps) { shelf = &sh; break; }
    if (!shelf) {
      int page = -1;
      for (std::size_t p = 0; p < page_next_y.size() && page < 0; ++p)
        if (page_next_y[p] + o.h <= ah + kEps) page = static_cast<int>(p);
      if (page < 0) page = static_cast<int>(page_next_y.size()), page_next_y.push_back(0);
      shelves.push_back({page, page_next_y[page], o.h, 0});
      page_next_y[page] += o.h + kGapMm;
      shelf = &shelves.back();
    }
    SheetPlacement& pl = L.pub.pieces[i];
    pl.net = i;
    pl.page = shelf->page;
    pl.x_mm = opt.margin_mm + shelf->x, pl.y_mm = opt.margin_mm + shelf->y;
    pl.width_mm = o.w, pl.height_mm = o.h;
    shelf->x += o.w + kGapMm;
    // mm-space point q (net orientation) -> page: rotate by theta, flip y, move into the rectangle.
    const double c = std::cos(o.theta), sn = std::sin(o.theta);
    Eigen::Matrix2d rot_flip;
    rot_flip << c, -sn, -sn, -c;
    pl.linear = rot_flip * s;
    pl.offset = V2(pl.x_mm + kPadMm - o.minx, pl.y_mm + kPadMm + o.maxy);
    for (const Tab& t : L.shapes[i].tabs) {
      std::array<V2, 4> q;
      for (int k = 0; k < 4; ++k) q[k] = rot_flip * t.quad[k] + pl.offset;
      pl.tabs.push_back(q);
    }
  }
  L.pub.sheet_pages = static_cast<int>(page_next_y.size());
  return L;
}

// ---------------------------------------------------------------------------------------
// Drawing.

Item path(Ink ink, std::vector<V2> pts, bool closed, std::string cls = "") {
  Item it;
  it.kind = Item::Kind::path, it.ink = ink, it.pts = std::move(pts), it.closed = closed, it.cls = std::move(cls);
  return it;
}

/// Text centred on `center` (both ways), baseline along `dir` (page coordinates).
Item text_centered(const std::string& s, V2 center, V2 dir, double size, std::string cls) {
  if (dir.x() < -1e-9 || (std::abs(dir.x()) <= 1e-9 && dir.y() > 0)) dir = -dir;  // keep it upright
  dir.normalize();
  const V2 up(dir.y(), -dir.x());
  Item it;
  it.kind = Item::Kind::text, it.ink = Ink::text, it.text = s, it.size = size, it.centered = true;
  it.at = center - up * (0.35 * size);
  it.angle = std::atan2(dir.y(), dir.x());
  it.cls = std::move(cls);
  return it;
}

Item text_left(const std::string& s, V2 baseline_start, double size, std::string cls) {
  Item it;
  it.kind = Item::Kind::text, it.ink = Ink::text, it.text = s, it.size = size, it.centered = false;
  it.at = baseline_start, it.cls = std::move(cls);
  return it;
}

Group draw_piece(const PieceModel& m, const PieceShape& sh, const SheetPlacement& pl) {
  const double s = sh.scale;
  const double c = pl.linear(0, 0) / s, sn = -pl.linear(1, 0) / s;
  Eigen::Matrix2d rot_flip;
  rot_flip << c, -sn, -sn, -c;
  auto page = [&](const V2& mm) { return V2(rot_flip * mm + pl.offset); };
  Group g;
  g.cls = "piece", g.id = m.id;

  std::vector<bool> has_tab(m.cuts.size(), false);
  for (const Tab& t : sh.tabs) {
    has_tab[t.cut] = true;
    g.items.push_back(path(Ink::tab, {page(t.quad[0]), page(t.quad[1]), page(t.quad[2]), page(t.quad[3])}, true));
  }
  for (const FoldLine& f : m.folds)
    g.items.push_back(path(f.mountain ? Ink::mountain : Ink::valley, {page(f.a * s), page(f.b * s)}, false));
  for (std::size_t i = 0; i < m.glued.size(); ++i)
    for (int k : m.glued[i])
      if (has_tab[k])  // the paper folds at the tab's base, the same way as the shell's folds
        g.items.push_back(path(m.glued_mountain[i] ? Ink::mountain : Ink::valley,
                               {page(m.cuts[k].a * s), page(m.cuts[k].b * s)}, false, "tab-fold"));
  for (const Tab& t : sh.tabs)
    g.items.push_back(path(Ink::cut, {page(t.quad[0]), page(t.quad[1]), page(t.quad[2]), page(t.quad[3])}, false));
  for (std::size_t k = 0; k < m.cuts.size(); ++k)
    if (!has_tab[k]) g.items.push_back(path(Ink::cut, {page(m.cuts[k].a * s), page(m.cuts[k].b * s)}, false));

  for (const CutCopy& cc : m.cuts) {
    if (cc.label.empty()) continue;
    const V2 a = cc.a * s, b = cc.b * s, mid = (a + b) / 2, n = left_normal((b - a).normalized());
    const double len = (b - a).norm(), hl = stroke_half(len);
    g.items.push_back(path(Ink::stroke, {page(mid + n * hl), page(mid - n * hl)}, false));
    const double font = std::clamp(len / 5, kMinFontMm, kMaxLabelFontMm);
    // Centred just inside the edge, clear of the alignment stroke (cap height ~0.72 em).
    g.items.push_back(text_centered(cc.label, page(mid + n * (hl + 0.4 + 0.36 * font)), page(b) - page(a), font, "edge-label"));
  }

  const std::array<V2, 3>& root = m.tris[m.root];
  const double r_root = inradius(root) * s;
  const double side = std::min(kMaxStartMarkMm, r_root);
  V2 mark = page(incenter(root) * s);
  const std::string name = m.name + " (" + m.letter + ")";
  const double r_name = m.name_room * s;
  // The text box (width k*font, height ~font) inscribed in the incircle: (k f/2)^2 + (f/2)^2 <= r^2.
  const double k = text_width_mm(name, 1.0) * kFallbackFontSlack;
  const double name_font = std::clamp(1.8 * r_name / std::sqrt(k * k + 1), kMinFontMm, kMaxNameFontMm);
  V2 name_at = page(m.name_center * s);
  if (m.name_on_root) mark.y() -= 0.5 * (side + name_font), name_at.y() += 0.5 * (side + 0.2 * name_font);
  g.items.push_back(path(Ink::start,
                         {V2(mark + V2(-side / 2, -side / 2)), V2(mark + V2(side / 2, -side / 2)),
                          V2(mark + V2(side / 2, side / 2)), V2(mark + V2(-side / 2, side / 2))},
                         true));
  g.items.push_back(text_centered(name, name_at, V2(1, 0), name_font, "piece-name"));
  return g;
}

Group draw_legend(const Legend& lg, const SheetOptions& opt, int page, int pages, double scale) {
  Group g;
  g.cls = "legend";
  const double top = opt.paper_height_mm - opt.margin_mm - lg.height + 2;
  const double x0 = opt.margin_mm;
  for (const Legend::Item& it : lg.items) {
    const double cy = top + (it.row + 0.5) * kLegendRowMm, sx = x0 + it.x, L = kLegendSampleMm;
    switch (it.sample) {
      case Ink::tab: {
        const double h = 2.5;
        g.items.push_back(path(Ink::tab, {V2(sx, cy + h / 2), V2(sx + h, cy - h / 2), V2(sx + L - h, cy - h / 2), V2(sx + L, cy + h / 2)}, true));
        g.items.push_back(path(Ink::cut, {V2(sx, cy + h / 2), V2(sx + h, cy - h / 2), V2(sx + L - h, cy - h / 2), V2(sx + L, cy + h / 2)}, false));
        break;
      }
      case Ink::start:
        g.items.push_back(path(Ink::start, {V2(sx + 2, cy - 2), V2(sx + 6, cy - 2), V2(sx + 6, cy + 2), V2(sx + 2, cy + 2)}, true));
        break;
      case Ink::stroke:
        g.items.push_back(path(Ink::cut, {V2(sx, cy), V2(sx + L, cy)}, false));
        g.items.push_back(path(Ink::stroke, {V2(sx + L / 2, cy - kStrokeHalfMm), V2(sx + L / 2, cy + kStrokeHalfMm)}, false));
        break;
      default:
        g.items.push_back(path(it.sample, {V2(sx, cy), V2(sx + L, cy)}, false));
    }
    g.items.push_back(text_left(it.text, V2(sx + L + 2, cy + 0.35 * kLegendFontMm), kLegendFontMm, "legend"));
  }
  const std::string info = "Page " + std::to_string(page) + " of " + std::to_string(pages) + "   Scale: " +
                           fmt_scale(scale) + " mm per model unit   Print at 100% (no fit to page)";
  g.items.push_back(text_left(info, V2(x0, top + (lg.rows + 0.5) * kLegendRowMm + 0.35 * kLegendFontMm), kLegendFontMm, "legend"));
  return g;
}

/// Greedy word wrap by printed width.
std::vector<std::string> wrap(const std::string& s, double size, double width) {
  std::vector<std::string> lines;
  std::string line, word;
  auto flush_word = [&] {
    if (word.empty()) return;
    const std::string candidate = line.empty() ? word : line + " " + word;
    if (!line.empty() && kFallbackFontSlack * text_width_mm(candidate, size) > width) lines.push_back(line), line = word;
    else line = candidate;
    word.clear();
  };
  for (char ch : s) {
    if (ch == ' ' || ch == '\n') flush_word();
    else word += ch;
  }
  flush_word();
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

std::vector<Page> assembly_pages(const Layout& L, const SheetOptions& opt, const std::vector<AssemblyJoin>& joins) {
  std::map<std::string, std::string> letter_of;
  for (const PieceModel& m : L.models) letter_of.emplace(m.name, m.letter);
  auto who = [&](const std::string& name) {
    auto it = letter_of.find(name);
    return it == letter_of.end() ? name : name + " (" + it->second + ")";
  };
  const double x0 = opt.margin_mm, width = opt.paper_width_mm - 2 * opt.margin_mm;
  const double title_font = 6, font = 3.5, line_h = 5.5, bottom = opt.paper_height_mm - opt.margin_mm;
  const std::string intro = "When every shell is folded and glued, glue the shells to each other. "
                            "Each line names two shells that touch along a flat cut face.";
  std::vector<Page> pages;
  double y = 0;
  auto new_page = [&] {
    pages.emplace_back();
    pages.back().cls = "page assembly";
    pages.back().groups.emplace_back();
    pages.back().groups.back().cls = "assembly";
    y = opt.margin_mm + title_font;
    pages.back().groups.back().items.push_back(
        text_left(pages.size() == 1 ? "Assembly" : "Assembly (continued)", V2(x0, y), title_font, "title"));
    y += line_h;
  };
  auto add_line = [&](const std::string& text, double indent) {
    if (pages.empty() || y + line_h > bottom) new_page();
    y += line_h;
    pages.back().groups.back().items.push_back(text_left(text, V2(x0 + indent, y), font, "assembly-line"));
  };
  for (const std::string& l : wrap(intro, font, width)) add_line(l, 0);
  y += line_h / 2;
  for (std::size_t i = 0; i < joins.size(); ++i) {
    const AssemblyJoin& j = joins[i];
    const std::string head = std::to_string(i + 1) + ". " + who(j.shell_a) + " + " + who(j.shell_b) +
                             (j.description.empty() ? "" : ":");
    for (const std::string& l : wrap(head, font, width)) add_line(l, 0);
    if (!j.description.empty())
      for (const std::string& l : wrap(j.description, font, width - 8)) add_line(l, 8);
  }
  return pages;
}

}  // namespace

double text_width_mm(const std::string& s, double size) {
  // Helvetica advance widths (1/1000 em) for ASCII 32..126, from the standard AFM metrics.
  static const short widths[95] = {
      278, 278, 355, 556, 556, 889, 667, 191, 333, 333, 389, 584, 278, 333, 278, 278,  // ' '../
      556, 556, 556, 556, 556, 556, 556, 556, 556, 556, 278, 278, 584, 584, 584, 556,  // 0..?
      1015, 667, 667, 722, 722, 667, 611, 778, 722, 278, 500, 667, 556, 833, 722, 778,  // @..O
      667, 778, 722, 667, 611, 722, 667, 944, 667, 667, 611, 278, 278, 278, 469, 556,   // P.._
      333, 556, 556, 500, 556, 556, 278, 556, 556, 222, 222, 500, 222, 833, 556, 556,   // `..o
      556, 556, 333, 500, 278, 556, 500, 722, 500, 500, 500, 334, 260, 334, 584};       // p..~
  double w = 0;
  for (char ch : printable(s)) w += widths[static_cast<unsigned char>(ch) - 32];
  return w * size / 1000;
}

std::string printable(const std::string& s) {
  std::string r;
  for (char ch : s) r += (ch >= 32 && ch <= 126) ? ch : '?';
  return r;
}

std::string num(double v) {
  if (!std::isfinite(v)) throw std::logic_error("sheets: non-finite coordinate");
  const long long t = std::llround(v * 1000.0);
  const unsigned long long a = t < 0 ? 0ULL - static_cast<unsigned long long>(t) : static_cast<unsigned long long>(t);
  std::string s = (t < 0 ? "-" : "") + std::to_string(a / 1000);
  if (unsigned frac = static_cast<unsigned>(a % 1000)) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "%03u", frac);
    std::string f = buf;
    while (f.back() == '0') f.pop_back();
    s += "." + f;
  }
  return s;
}

const InkStyle& style(Ink ink) {
  static const InkStyle styles[] = {
      // cls, color, width, dash, stroke, fill, fill gray
      {"cut", 0, 0, 0, 0.35, {}, true, false, 0},
      {"fold mountain", 0.70, 0.13, 0.13, 0.3, {4, 1.2, 0.6, 1.2}, true, false, 0},
      {"fold valley", 0.12, 0.31, 0.75, 0.3, {2, 1.5}, true, false, 0},
      {"tab", 0, 0, 0, 0, {}, false, true, 0.87},
      {"align-mark", 0, 0, 0, 0.35, {}, true, false, 0},
      {"start-mark", 0, 0, 0, 0, {}, false, true, 0},
      {"paper", 0.6, 0.6, 0.6, 0.2, {}, true, true, 1},
      {"text", 0, 0, 0, 0, {}, false, true, 0},
  };
  return styles[static_cast<int>(ink)];
}

Document build_document(const std::vector<Net>& nets, const SheetOptions& opt,
                        const std::vector<AssemblyJoin>& assembly) {
  const Layout L = compute_layout(nets, opt);
  Document doc;
  doc.width_mm = opt.paper_width_mm, doc.height_mm = opt.paper_height_mm;
  std::vector<Page> extra = assembly.empty() ? std::vector<Page>{} : assembly_pages(L, opt, assembly);
  const int total = L.pub.sheet_pages + static_cast<int>(extra.size());
  doc.pages.resize(L.pub.sheet_pages);
  for (int p = 0; p < L.pub.sheet_pages; ++p) doc.pages[p].cls = "page sheet";
  for (std::size_t i = 0; i < L.models.size(); ++i)  // net order within each page
    doc.pages[L.pub.pieces[i].page].groups.push_back(draw_piece(L.models[i], L.shapes[i], L.pub.pieces[i]));
  for (int p = 0; p < L.pub.sheet_pages; ++p)
    doc.pages[p].groups.push_back(draw_legend(L.legend, opt, p + 1, total, L.pub.scale_mm_per_unit));
  for (Page& p : extra) doc.pages.push_back(std::move(p));
  for (std::size_t p = 0; p < doc.pages.size(); ++p) doc.pages[p].id = "page-" + std::to_string(p + 1);
  return doc;
}

SheetLayout layout(const std::vector<Net>& nets, const SheetOptions& opt) { return compute_layout(nets, opt).pub; }

}  // namespace sheets

SheetOptions SheetOptions::paper_from_string(const std::string& text) {
  std::string s;
  for (char c : text) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  static const std::map<std::string, std::pair<double, double>> named = {
      {"a3", {297, 420}}, {"a4", {210, 297}}, {"a5", {148, 210}}, {"letter", {215.9, 279.4}}, {"legal", {215.9, 355.6}}};
  SheetOptions o;
  if (auto it = named.find(s); it != named.end()) {
    o.paper_width_mm = it->second.first, o.paper_height_mm = it->second.second;
    return o;
  }
  // "WxHmm": two plain decimal numbers (digits with at most one point), both positive.
  auto parse_number = [](const std::string& t, double& v) {
    if (t.empty() || t.size() > 12) return false;
    int dots = 0, digits = 0;
    for (char c : t) {
      if (c == '.') ++dots;
      else if (std::isdigit(static_cast<unsigned char>(c))) ++digits;
      else return false;
    }
    if (dots > 1 || digits == 0) return false;
    v = 0;
    double frac = 0;  // locale-independent: std::stod would honour a ',' decimal point
    for (char c : t) {
      if (c == '.') frac = 1;
      else if (frac > 0) frac /= 10, v += (c - '0') * frac;
      else v = v * 10 + (c - '0');
    }
    return v > 0;
  };
  const std::size_t x = s.find('x');
  double w = 0, h = 0;
  if (s.size() > 2 && s.compare(s.size() - 2, 2, "mm") == 0 && x != std::string::npos &&
      parse_number(s.substr(0, x), w) && parse_number(s.substr(x + 1, s.size() - 2 - x - 1), h)) {
    o.paper_width_mm = w, o.paper_height_mm = h;
    return o;
  }
  throw std::invalid_argument("invalid paper size '" + text +
                              "': expected a3, a4, a5, letter, legal or WIDTHxHEIGHTmm with positive decimal numbers, "
                              "e.g. 300x200mm");
}

SheetLayout layout_net_sheets(const std::vector<Net>& nets, const SheetOptions& opt) { return sheets::layout(nets, opt); }

std::string net_sheet_problem(const Net& net) {
  try {
    sheets::make_model(net, 0);
  } catch (const sheets::BadNet& e) {
    return e.reason;
  }
  return {};
}

void write_net_sheets(const std::vector<Net>& nets, const SheetOptions& opt, const std::vector<AssemblyJoin>& assembly,
                      std::ostream& out) {
  const sheets::Document doc = sheets::build_document(nets, opt, assembly);
  if (opt.format == SheetOptions::Format::pdf) sheets::write_pdf(doc, out);
  else sheets::write_svg(doc, out);
}

}  // namespace dcshell
