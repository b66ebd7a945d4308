// What the CSV tables (the trade-off studies in studies/, npr/leaf_clusters.cpp's report) share:
// a number printed with a printf format, and a text field quoted as RFC 4180 asks. Header-only.
#pragma once

#include <cstdio>
#include <string>

namespace sylva {

// `v` printed with the printf format `fmt` (one double conversion), at most 127 characters.
inline std::string format_number(const char* fmt, double v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// `text` as one CSV field: empty stays empty; otherwise in double quotes, inner quotes doubled.
inline std::string csv_quoted(const std::string& text) {
  if (text.empty()) return text;
  std::string out = "\"";
  for (char c : text)
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace sylva
