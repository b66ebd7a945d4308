// The header of a Stanford PLY file: "ply", "format ascii|binary_little_endian|
// binary_big_endian 1.0", elements with counts and their (scalar or list) properties,
// "end_header". Read by ply_read.cpp; every line that is not in the format is an error.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sylva {

enum class PlyType { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

size_t ply_size(PlyType t);
double ply_max(PlyType t);  // the largest value of an integer type (colours are scaled by it)
bool ply_integer(PlyType t);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // of the value, or of a list's items
  bool list = false;
  PlyType count_type = PlyType::Uint8;  // of a list's length
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  enum class Format { Ascii, LittleEndian, BigEndian } format = Format::Ascii;
  std::vector<PlyElement> elements;
  size_t data_offset = 0;  // the first byte after "end_header\n"
  const PlyElement* find(std::string_view name) const;
};

PlyHeader read_ply_header(std::string_view bytes, const std::string& path);

}  // namespace sylva
