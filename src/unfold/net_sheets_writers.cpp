// SVG and PDF back ends of the sheet writer: both render the same display list (net_sheets_doc.h).
// Hand-written on purpose (no new dependencies); every number goes through num(), so the output
// is byte-identical from run to run and independent of the C locale.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

#include "net_sheets_doc.h"

namespace dcshell::sheets {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSvgPageGapMm = 10.0;  // pages are stacked vertically in one SVG

std::string hex_color(double r, double g, double b) {
  auto c = [](double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c(r), c(g), c(b));
  return buf;
}

std::string xml_escape(const std::string& raw) {
  std::string s;
  for (char ch : printable(raw)) {
    switch (ch) {
      case '&': s += "&amp;"; break;
      case '<': s += "&lt;"; break;
      case '>': s += "&gt;"; break;
      case '"': s += "&quot;"; break;
      default: s += ch;
    }
  }
  return s;
}

std::string dash_list(const std::vector<double>& dash, const char* sep) {
  std::string s;
  for (std::size_t i = 0; i < dash.size(); ++i) s += (i ? sep : "") + num(dash[i]);
  return s;
}

void svg_item(const Item& it, std::ostream& out) {
  const InkStyle& st = style(it.ink);
  const std::string cls = xml_escape(it.cls.empty() ? std::string(st.cls) : std::string(st.cls) + " " + it.cls);
  if (it.kind == Item::Kind::text) {
    out << "<text class=\"" << cls << "\" x=\"" << num(it.at.x()) << "\" y=\"" << num(it.at.y())
        << "\" font-family=\"Helvetica, Arial, sans-serif\" font-size=\"" << num(it.size) << "\" fill=\"#000000\""
        << (it.centered ? " text-anchor=\"middle\"" : "");
    const std::string deg = num(it.angle * 180 / kPi);
    if (deg != "0") out << " transform=\"rotate(" << deg << " " << num(it.at.x()) << " " << num(it.at.y()) << ")\"";
    out << ">" << xml_escape(it.text) << "</text>\n";
    return;
  }
  out << "<path class=\"" << cls << "\" d=\"";
  for (std::size_t i = 0; i < it.pts.size(); ++i)
    out << (i ? " L" : "M") << num(it.pts[i].x()) << " " << num(it.pts[i].y());
  out << (it.closed ? " Z" : "") << "\" fill=\""
      << (st.fill ? hex_color(st.fill_gray, st.fill_gray, st.fill_gray) : std::string("none")) << "\"";
  if (st.stroke) {
    out << " stroke=\"" << hex_color(st.r, st.g, st.b) << "\" stroke-width=\"" << num(st.width)
        << "\" stroke-linejoin=\"round\"";
    if (!st.dash.empty()) out << " stroke-dasharray=\"" << dash_list(st.dash, " ") << "\"";
  } else {
    out << " stroke=\"none\"";
  }
  out << "/>\n";
}

/// PDF graphics state, so that colour, width and dash are only emitted when they change.
struct PdfState {
  std::string stroke_color, fill_color, width, dash;
  void set(std::string& cur, const std::string& want, std::string& content) {
    if (cur != want) cur = want, content += want;
  }
};

std::string pdf_string(const std::string& raw) {
  std::string s = "(";
  for (char ch : printable(raw)) {
    if (ch == '(' || ch == ')' || ch == '\\') s += '\\';
    s += ch;
  }
  return s + ")";
}

void pdf_item(const Item& it, PdfState& gs, std::string& c) {
  const InkStyle& st = style(it.ink);
  if (it.ink == Ink::paper) return;  // the paper is the page itself
  if (st.fill) {
    const std::string g = num(st.fill_gray);
    gs.set(gs.fill_color, g + " " + g + " " + g + " rg\n", c);
  }
  if (it.kind == Item::Kind::text) {
    const V2 dir(std::cos(it.angle), std::sin(it.angle));
    const V2 start = it.centered ? V2(it.at - dir * (text_width_mm(it.text, it.size) / 2)) : it.at;
    // The page CTM flips y (mm, y down); glyph "up" must map to -y rotated by the angle.
    c += "BT /F1 1 Tf " + num(it.size * dir.x()) + " " + num(it.size * dir.y()) + " " + num(it.size * dir.y()) + " " +
         num(-it.size * dir.x()) + " " + num(start.x()) + " " + num(start.y()) + " Tm " + pdf_string(it.text) +
         " Tj ET\n";
    return;
  }
  if (st.stroke) {
    gs.set(gs.stroke_color, num(st.r) + " " + num(st.g) + " " + num(st.b) + " RG\n", c);
    gs.set(gs.width, num(st.width) + " w\n", c);
    gs.set(gs.dash, "[" + dash_list(st.dash, " ") + "] 0 d\n", c);
  }
  for (std::size_t i = 0; i < it.pts.size(); ++i)
    c += num(it.pts[i].x()) + " " + num(it.pts[i].y()) + (i ? " l\n" : " m\n");
  if (it.closed) c += "h\n";
  c += st.fill && st.stroke ? "B\n" : st.fill ? "f\n" : "S\n";
}

}  // namespace

void write_svg(const Document& doc, std::ostream& out) {
  const std::size_t n = doc.pages.size();
  const double total_h = n * doc.height_mm + (n > 0 ? (n - 1) * kSvgPageGapMm : 0);
  const std::string w = num(doc.width_mm), h = num(total_h);
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << w << "mm\" height=\"" << h
      << "mm\" viewBox=\"0 0 " << w << " " << h << "\">\n"
      << "<title>dcshell paper model: cut, fold, glue</title>\n";
  for (std::size_t p = 0; p < n; ++p) {
    const Page& page = doc.pages[p];
    out << "<g id=\"" << xml_escape(page.id) << "\" class=\"" << xml_escape(page.cls) << "\" transform=\"translate(0 "
        << num(p * (doc.height_mm + kSvgPageGapMm)) << ")\">\n";
    Item paper;
    paper.ink = Ink::paper, paper.closed = true;
    paper.pts = {V2(0, 0), V2(doc.width_mm, 0), V2(doc.width_mm, doc.height_mm), V2(0, doc.height_mm)};
    svg_item(paper, out);
    for (const Group& g : page.groups) {
      out << "<g class=\"" << xml_escape(g.cls) << "\"";
      if (!g.id.empty()) out << " id=\"" << xml_escape(g.id) << "\"";
      out << ">\n";
      for (const Item& it : g.items) svg_item(it, out);
      out << "</g>\n";
    }
    out << "</g>\n";
  }
  out << "</svg>\n";
}

void write_pdf(const Document& doc, std::ostream& out) {
  const char* kPtPerMm = "2.83464566929";  // 72 / 25.4
  const double pt = 72.0 / 25.4;
  const std::size_t n = doc.pages.size();
  // Objects: 1 catalog, 2 page tree, 3 font, then (page, contents) for each page.
  const std::size_t count = 3 + 2 * n;
  std::vector<std::size_t> offset(count + 1, 0);
  std::string buf = "%PDF-1.4\n%\xE2\xE3\xCF\xD3\n";
  auto object = [&](std::size_t id, const std::string& body) {
    offset[id] = buf.size();
    buf += std::to_string(id) + " 0 obj\n" + body + "\nendobj\n";
  };
  object(1, "<< /Type /Catalog /Pages 2 0 R >>");
  std::string kids;
  for (std::size_t p = 0; p < n; ++p) kids += (p ? " " : "") + std::to_string(4 + 2 * p) + " 0 R";
  object(2, "<< /Type /Pages /Kids [" + kids + "] /Count " + std::to_string(n) + " >>");
  object(3, "<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>");
  const std::string page_w = num(doc.width_mm * pt), page_h = num(doc.height_mm * pt);
  for (std::size_t p = 0; p < n; ++p) {
    const std::size_t page_id = 4 + 2 * p, content_id = page_id + 1;
    object(page_id, "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 " + page_w + " " + page_h +
                        "] /Resources << /Font << /F1 3 0 R >> >> /Contents " + std::to_string(content_id) + " 0 R >>");
    // Draw in mm with y down, like the SVG: one transform maps it to PDF points.
    std::string c = std::string("q\n") + kPtPerMm + " 0 0 -" + kPtPerMm + " 0 " + page_h + " cm\n1 j 0 J\n";
    PdfState gs;
    for (const Group& g : doc.pages[p].groups)
      for (const Item& it : g.items) pdf_item(it, gs, c);
    c += "Q\n";
    object(content_id, "<< /Length " + std::to_string(c.size()) + " >>\nstream\n" + c + "endstream");
  }
  const std::size_t xref = buf.size();
  buf += "xref\n0 " + std::to_string(count + 1) + "\n0000000000 65535 f \n";
  for (std::size_t id = 1; id <= count; ++id) {
    char line[24];
    std::snprintf(line, sizeof line, "%010zu 00000 n \n", offset[id]);
    buf += line;
  }
  buf += "trailer\n<< /Size " + std::to_string(count + 1) + " /Root 1 0 R >>\nstartxref\n" + std::to_string(xref) +
         "\n%%EOF\n";
  out.write(buf.data(), static_cast<std::streamsize>(buf.size()));
}

}  // namespace dcshell::sheets
