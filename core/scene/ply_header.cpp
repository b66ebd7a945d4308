#include "core/scene/ply_header.h"

#include "core/error.h"
#include "core/scene/text_scan.h"

namespace sylva {
namespace {

struct TypeName {
  const char* name;
  PlyType type;
};
constexpr TypeName kTypes[] = {
    {"char", PlyType::Int8},      {"uchar", PlyType::Uint8},    {"short", PlyType::Int16},
    {"ushort", PlyType::Uint16},  {"int", PlyType::Int32},      {"uint", PlyType::Uint32},
    {"float", PlyType::Float32},  {"double", PlyType::Float64}, {"int8", PlyType::Int8},
    {"uint8", PlyType::Uint8},    {"int16", PlyType::Int16},    {"uint16", PlyType::Uint16},
    {"int32", PlyType::Int32},    {"uint32", PlyType::Uint32},  {"float32", PlyType::Float32},
    {"float64", PlyType::Float64}};

PlyType type_of(const TextScan& scan, std::string_view w) {
  for (const TypeName& t : kTypes)
    if (w == t.name) return t.type;
  scan.fail(TextScan::quote(w) + " is not a PLY property type");
}

void add_property(const TextScan& scan, const std::vector<std::string_view>& w, PlyHeader& h) {
  if (h.elements.empty()) scan.fail("a property before any element");
  PlyProperty p;
  if (w.size() == 5 && w[1] == "list") {
    p.list = true;
    p.count_type = type_of(scan, w[2]);
    if (!ply_integer(p.count_type)) scan.fail("a list's length must have an integer type");
    p.type = type_of(scan, w[3]);
  } else if (w.size() == 3) {
    p.type = type_of(scan, w[1]);
  } else {
    scan.fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
  }
  p.name = std::string(w.back());
  h.elements.back().properties.push_back(std::move(p));
}

void set_format(const TextScan& scan, const std::vector<std::string_view>& w, PlyHeader& h) {
  if (w.size() != 3 || w[2].substr(0, 1) != "1")
    scan.fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  if (w[1] == "ascii")
    h.format = PlyHeader::Format::Ascii;
  else if (w[1] == "binary_little_endian")
    h.format = PlyHeader::Format::LittleEndian;
  else if (w[1] == "binary_big_endian")
    h.format = PlyHeader::Format::BigEndian;
  else
    scan.fail(TextScan::quote(w[1]) + " is not a PLY format");
}

void check_elements(const TextScan& scan, const PlyHeader& h) {
  for (const PlyElement& e : h.elements)
    if (e.count > 0 && e.properties.empty())
      scan.fail("element '" + e.name + "' has " + std::to_string(e.count) +
                " items but no properties");
}

}  // namespace

size_t ply_size(PlyType t) {
  static constexpr size_t kSize[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return kSize[int(t)];
}
double ply_max(PlyType t) {
  static constexpr double kMax[] = {127, 255, 32767, 65535, 2147483647.0, 4294967295.0, 1, 1};
  return kMax[int(t)];
}
bool ply_integer(PlyType t) {
  return t != PlyType::Float32 && t != PlyType::Float64;
}

const PlyElement* PlyHeader::find(std::string_view name) const {
  for (const PlyElement& e : elements)
    if (e.name == name) return &e;
  return nullptr;
}

PlyHeader read_ply_header(std::string_view bytes, const std::string& path) {
  TextScan scan(bytes, path);
  std::vector<std::string_view> w;
  if (!scan.line(w) || w.size() != 1 || w[0] != "ply")
    throw InputError(path, "not a PLY file (the first line is not 'ply')");
  PlyHeader h;
  bool format = false;
  while (scan.line(w)) {
    if (w[0] == "end_header" && w.size() == 1) {
      if (!format) scan.fail("the header has no 'format' line");
      check_elements(scan, h);
      const size_t at = scan.offset();
      h.data_offset = at + (at < bytes.size() && bytes[at] == '\n' ? 1 : 0);
      return h;
    }
    if (w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format") {
      set_format(scan, w, h);
      format = true;
    } else if (w[0] == "element" && w.size() == 3) {
      h.elements.push_back(
          {std::string(w[1]), scan.count(w[2], "an element count", UINT32_MAX), {}});
    } else if (w[0] == "property") {
      add_property(scan, w, h);
    } else {
      scan.fail("not a PLY header line: " + TextScan::quote(w[0]));
    }
  }
  throw InputError(path, "the PLY header has no 'end_header'");
}

}  // namespace sylva
