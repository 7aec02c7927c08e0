// Private to the sheet writer: the display list that net_sheets.cpp builds and that the SVG and
// PDF back ends (net_sheets_writers.cpp) render. Page coordinates: mm, origin at the paper's
// top-left corner, y down.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "dcshell/net_sheets.h"

namespace dcshell::sheets {

using V2 = Eigen::Vector2d;

/// What a mark means; each ink has one style shared by both formats.
enum class Ink { cut, mountain, valley, tab, stroke, start, paper, text };

struct InkStyle {
  const char* cls;       ///< SVG class
  double r, g, b;        ///< stroke colour, 0..1
  double width;          ///< stroke width, mm
  std::vector<double> dash;  ///< dash pattern, mm; empty = solid
  bool stroke, fill;
  double fill_gray;      ///< fill colour (grey level, 0 = black)
};
const InkStyle& style(Ink);

struct Item {
  enum class Kind { path, text } kind = Kind::path;
  Ink ink = Ink::cut;
  std::string cls;  ///< extra SVG classes, after the ink's class
  // path
  std::vector<V2> pts;
  bool closed = false;
  // text: `at` is the baseline's start (centered = false) or middle (centered = true);
  // the baseline runs along angle (radians, page coordinates, clockwise on paper).
  V2 at = V2::Zero();
  double size = 0, angle = 0;
  bool centered = false;
  std::string text;
};

struct Group {
  std::string id, cls;
  std::vector<Item> items;
};

struct Page {
  std::string id, cls;
  std::vector<Group> groups;
};

struct Document {
  double width_mm = 0, height_mm = 0;
  std::vector<Page> pages;
};

Document build_document(const std::vector<Net>&, const SheetOptions&, const std::vector<AssemblyJoin>&);
SheetLayout layout(const std::vector<Net>&, const SheetOptions&);

void write_svg(const Document&, std::ostream&);
void write_pdf(const Document&, std::ostream&);

/// Printed width of `s` in Helvetica at `size` mm (used to centre and wrap text in both formats).
double text_width_mm(const std::string& s, double size);
/// Printable ASCII only: other bytes become '?', so text is valid XML and WinAnsi in any case.
std::string printable(const std::string& s);
/// Fixed-point number with at most 3 decimals, locale-independent, no "-0".
std::string num(double v);

}  // namespace dcshell::sheets
