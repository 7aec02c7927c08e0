// Printable sheets: nets laid out at physical scale on paper pages, as SVG or PDF, with the
// marks a child needs to cut, fold and glue them (issue 5 §5; doc/sheets.md explains the marks).
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "dcshell/net.h"

namespace dcshell {

struct SheetOptions {
  enum class Format { svg, pdf } format = Format::svg;
  double paper_width_mm = 210, paper_height_mm = 297;  // A4 portrait
  double margin_mm = 10;
  /// 0 = fit: the largest scale at which every piece fits on one page (same scale for all
  /// pieces, so the parts of one model match). The fitted scale is rounded down to 3
  /// significant digits so it can be quoted on the sheet.
  double scale_mm_per_unit = 0;
  bool tabs = true;

  /// Paper size from "a3", "a4", "a5", "letter", "legal" (case-insensitive, portrait) or
  /// "WxHmm", e.g. "300x200mm". Other fields keep their defaults.
  /// Throws std::invalid_argument with a message naming the string and the accepted forms.
  static SheetOptions paper_from_string(const std::string&);
};

/// One line of the assembly page: two shells that touch, and along what (e.g. the cut plane).
struct AssemblyJoin {
  std::string shell_a, shell_b;
  std::string description;
};

/// Writes the sheets of `nets` (one piece per net) in options.format. SVG: one <g id="page-N">
/// per page, stacked vertically, each holding one <g class="piece" id="piece-NAME"> per piece
/// and a legend. PDF 1.4: one page per sheet. When `assembly` is non-empty, assembly page(s)
/// follow the sheets. Output is deterministic (same input => same bytes).
/// Throws std::invalid_argument on an inconsistent net, bad options, or a piece that does not
/// fit on a page at the requested scale (the message names the piece and the scale that fits).
void write_net_sheets(const std::vector<Net>& nets, const SheetOptions&,
                      const std::vector<AssemblyJoin>& assembly, std::ostream& out);

/// Why `net` cannot be printed (a face mirrored or of no area in the plane, an edge that is not
/// its faces', a corner that is not finite, ...), or empty when it can. write_net_sheets throws on
/// such a net; a caller with several nets can leave it off instead.
std::string net_sheet_problem(const Net& net);

/// Where one piece went. Page coordinates are mm from the paper's top-left corner, y down.
struct SheetPlacement {
  std::size_t net = 0;  ///< index into the nets given
  int page = 0;         ///< 0-based sheet page
  /// Footprint rectangle on the page: the piece, its tabs and marks, plus a small padding.
  double x_mm = 0, y_mm = 0, width_mm = 0, height_mm = 0;
  /// Net plane (model units) -> page (mm): linear * p + offset. Rotation and scale only; the
  /// determinant is negative because page y points down, so on paper the net is not mirrored.
  Eigen::Matrix2d linear = Eigen::Matrix2d::Identity();
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  /// Glue tabs on the page (mm): base corner a, outer corner near a, outer corner near b, base
  /// corner b. Exactly one per glued edge pair when tabs are on.
  std::vector<std::array<Eigen::Vector2d, 4>> tabs;
};

struct SheetLayout {
  double scale_mm_per_unit = 0;
  int sheet_pages = 0;  ///< pages holding pieces; assembly pages come after these
  /// The region of every sheet page where pieces may go: inside the margins, above the legend.
  double area_x_mm = 0, area_y_mm = 0, area_width_mm = 0, area_height_mm = 0;
  std::vector<SheetPlacement> pieces;  ///< in the order of `nets`
};

/// The layout write_net_sheets uses (scale, rotation, packing), exposed for checks and tools.
SheetLayout layout_net_sheets(const std::vector<Net>& nets, const SheetOptions&);

}  // namespace dcshell
