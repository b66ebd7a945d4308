#include "core/io/svg_writer.h"

#include <glib.h>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "core/color.h"
#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/io/codecs_png.h"
#include "core/params.h"

namespace sylva {

void check_dpi(double dpi, const std::string& where) {
  if (!std::isfinite(dpi) || dpi < 0.0 || dpi > 10000.0)
    throw InputError(where, "must be in [0, 10000] pixels per inch (0 = sizes in px)");
}

namespace {

// A number with two decimals, trailing zeros dropped ("12.5", "3", "-0.25").
std::string num(double v) {
  if (!std::isfinite(v)) v = 0.0;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  std::string s = buf;
  while (!s.empty() && s.back() == '0')
    s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

void path_data(std::ostringstream& o, const std::vector<glm::vec2>& pts, bool closed) {
  o << 'M' << num(pts[0].x) << ' ' << num(pts[0].y);
  for (size_t i = 1; i < pts.size(); ++i)
    o << 'L' << num(pts[i].x) << ' ' << num(pts[i].y);
  if (closed) o << 'Z';
}

void write_stroke(std::ostringstream& o, const Stroke& s) {
  const std::string opacity = s.opacity < 1.0f ? " opacity=\"" + num(s.opacity) + "\"" : "";
  o << "    <path d=\"";
  if (s.filled) {
    path_data(o, s.points, true);
    for (const std::vector<glm::vec2>& hole : s.holes)
      if (!hole.empty()) path_data(o, hole, true);
    o << "\" fill=\"currentColor\" fill-rule=\"evenodd\" stroke=\"none\"" << opacity << "/>\n";
    return;
  }
  if (s.constant_width() && s.points.size() > 1) {
    path_data(o, s.points, s.closed);
    o << "\" stroke-width=\"" << num(s.width) << '"' << opacity << "/>\n";
    return;
  }
  for (const std::vector<glm::vec2>& ring : stroke_outline(s))
    path_data(o, ring, true);
  o << "\" fill=\"currentColor\" stroke=\"none\"" << opacity << "/>\n";
}

// The drawing's paint as a layer holding one embedded PNG (base64 data URI).
void write_paint(std::ostringstream& o, const StrokeDrawing& d) {
  SYLVA_CHECK(d.paint.type() == CV_8UC4 && d.paint.size() == d.size,
              "svg_document: the paint must be CV_8UC4 at the drawing's size");
  std::string png;
  SYLVA_CHECK(encode_png(d.paint, PngEncodeOptions{}, png), "svg_document: PNG encoding failed");
  const std::unique_ptr<gchar, decltype(&g_free)> text(
      g_base64_encode(reinterpret_cast<const guchar*>(png.data()), png.size()), &g_free);
  o << "  <g inkscape:groupmode=\"layer\" id=\"layer-paint\" inkscape:label=\"paint\">\n"
    << "    <image id=\"paint\" x=\"0\" y=\"0\" width=\"" << d.size.width << "\" height=\""
    << d.size.height << "\" preserveAspectRatio=\"none\" xlink:href=\"data:image/png;base64,"
    << text.get() << "\"/>\n  </g>\n";
}

std::string length(double px, double dpi) {
  return dpi > 0.0 ? num(px / dpi * 25.4) + "mm" : num(px);
}

}  // namespace

std::string svg_document(const StrokeDrawing& d, const VectorPage& page) {
  check_dpi(page.dpi, "dpi");
  const std::string ink = hex_color(d.color);
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" "
       "xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
       "xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" version=\"1.1\" width=\""
    << length(d.size.width, page.dpi) << "\" height=\"" << length(d.size.height, page.dpi)
    << "\" viewBox=\"0 0 " << d.size.width << ' ' << d.size.height << "\">\n";
  if (page.paper)
    o << "  <g inkscape:groupmode=\"layer\" id=\"layer-paper\" inkscape:label=\"paper\">\n"
      << "    <rect id=\"paper\" x=\"0\" y=\"0\" width=\"" << d.size.width << "\" height=\""
      << d.size.height << "\" fill=\"" << hex_color(*page.paper) << "\"/>\n  </g>\n";
  if (!d.paint.empty()) write_paint(o, d);
  int groups[kLineClassCount] = {};
  for (size_t i = 0; i < d.strokes.size();) {
    const LineClass cls = d.strokes[i].cls;
    const std::string name = line_class_name(cls);
    // A class drawn again after another (not in Sylva's own drawings) gets a layer "-2", ...
    const int n = ++groups[size_t(cls)];
    std::string id = "layer-";
    id += name;
    if (n > 1) {
      id += '-';
      id += std::to_string(n);
    }
    o << "  <g inkscape:groupmode=\"layer\" id=\"" << id << "\" inkscape:label=\"" << name
      << "\" color=\"" << ink << "\" fill=\"none\" stroke=\"" << ink
      << "\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
    for (; i < d.strokes.size() && d.strokes[i].cls == cls; ++i)
      if (!d.strokes[i].points.empty()) write_stroke(o, d.strokes[i]);
    o << "  </g>\n";
  }
  o << "</svg>\n";
  return o.str();
}

void write_svg(const std::string& path, const StrokeDrawing& d, const VectorPage& page) {
  write_file_atomic(path, svg_document(d, page));
}

}  // namespace sylva
