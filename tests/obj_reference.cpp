#include "tests/obj_reference.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace sylva::test {
namespace {

struct Fault {
  size_t line;
};

bool digit(char c) {
  return c >= '0' && c <= '9';
}

// [+-] (digits [. digits] | . digits) [(e|E) [+-] digits], as a finite float.
float real(const std::string& s, size_t line) {
  size_t i = s.size() > 0 && (s[0] == '+' || s[0] == '-') ? 1 : 0, mantissa = 0;
  for (; i < s.size() && digit(s[i]); ++i)
    ++mantissa;
  if (i < s.size() && s[i] == '.')
    for (++i; i < s.size() && digit(s[i]); ++i)
      ++mantissa;
  if (mantissa == 0) throw Fault{line};
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    size_t exponent = 0;
    for (; i < s.size() && digit(s[i]); ++i)
      ++exponent;
    if (exponent == 0) throw Fault{line};
  }
  if (i != s.size()) throw Fault{line};
  const float f = float(std::strtod(s.c_str(), nullptr));
  if (!std::isfinite(f)) throw Fault{line};
  return f;
}

// A 1-based or negative index among `count`, 0-based.
size_t index(const std::string& s, size_t count, size_t line) {
  const bool minus = !s.empty() && s[0] == '-';
  const std::string d = minus ? s.substr(1) : s;
  if (d.empty() || !std::all_of(d.begin(), d.end(), digit)) throw Fault{line};
  const std::string significant = d.substr(std::min(d.find_first_not_of('0'), d.size()));
  if (significant.empty() || significant.size() > 12) throw Fault{line};  // 0, or beyond count
  const size_t v = size_t(std::stoull(significant));
  if (v == 0 || v > count) throw Fault{line};
  return minus ? count - v : v - 1;
}

struct State {
  MeshData m;
  std::vector<glm::vec2> vt;
  std::vector<glm::vec3> vn;
  std::vector<bool> colored, named_uv, named_normal;
};

void face(State& s, const std::vector<std::string>& w, size_t line) {
  if (w.size() < 4) throw Fault{line};
  std::vector<size_t> v, t, n;
  for (size_t k = 1; k < w.size(); ++k) {
    std::vector<std::string> parts(1);
    for (char c : w[k])
      if (c == '/')
        parts.emplace_back();
      else
        parts.back() += c;
    if (parts.size() > 3) throw Fault{line};
    v.push_back(index(parts[0], s.m.positions.size(), line));
    const bool uv = parts.size() == 2 || (parts.size() == 3 && !parts[1].empty());
    t.push_back(uv ? index(parts[1], s.vt.size(), line) : SIZE_MAX);
    n.push_back(parts.size() == 3 ? index(parts[2], s.vn.size(), line) : SIZE_MAX);
  }
  for (size_t k = 1; k + 1 < v.size(); ++k)
    s.m.indices.insert(s.m.indices.end(), {uint32_t(v[0]), uint32_t(v[k]), uint32_t(v[k + 1])});
  for (size_t k = 0; k < v.size(); ++k) {
    if (t[k] != SIZE_MAX && !s.named_uv[v[k]]) {
      s.named_uv[v[k]] = true;
      s.m.uvs[v[k]] = s.vt[t[k]];
    }
    if (n[k] != SIZE_MAX && !s.named_normal[v[k]]) {
      s.named_normal[v[k]] = true;
      s.m.normals[v[k]] = s.vn[n[k]];
    }
  }
}

void statement(State& s, const std::vector<std::string>& w, size_t line) {
  std::vector<float> x;
  if (w[0] == "v" || w[0] == "vt" || w[0] == "vn") {
    const size_t n = w.size() - 1;
    const bool fits = w[0] == "v"    ? n == 3 || n == 4 || n == 6
                      : w[0] == "vt" ? n >= 1 && n <= 3
                                     : n == 3;
    if (!fits) throw Fault{line};
    for (size_t k = 1; k < w.size(); ++k)
      x.push_back(real(w[k], line));
  }
  if (w[0] == "v") {
    s.m.positions.emplace_back(x[0], x[1], x[2]);
    s.m.uvs.emplace_back(0.0f);
    s.m.normals.emplace_back(0.0f);
    s.named_uv.push_back(false);
    s.named_normal.push_back(false);
    s.colored.push_back(x.size() == 6);
    glm::vec4 c(0.0f, 0.0f, 0.0f, 1.0f);
    for (size_t k = 3; x.size() == 6 && k < 6; ++k)
      c[int(k - 3)] = std::clamp(x[k], 0.0f, 1.0f);
    s.m.colors.push_back(c);
  } else if (w[0] == "vt") {
    s.vt.emplace_back(x[0], x.size() > 1 ? x[1] : 0.0f);
  } else if (w[0] == "vn") {
    s.vn.emplace_back(x[0], x[1], x[2]);
  } else if (w[0] == "f") {
    face(s, w, line);
  }
}

}  // namespace

ObjReference read_obj_reference(std::string_view text) {
  ObjReference r;
  const size_t nul = text.find('\0');
  if (nul != std::string_view::npos) {
    r.error_line = 1 + size_t(std::count(text.begin(), text.begin() + nul, '\n'));
    return r;
  }
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // a UTF-8 byte order mark
  State s;
  size_t line = 0;
  try {
    for (size_t at = 0; at <= text.size();) {
      const size_t end = std::min(text.find('\n', at), text.size());
      ++line;
      std::string content(text.substr(at, end - at));
      content = content.substr(0, content.find('#'));
      std::istringstream in(content);
      std::vector<std::string> words;
      for (std::string w; in >> w;)
        words.push_back(w);
      if (!words.empty()) statement(s, words, line);
      at = end + 1;
    }
  } catch (const Fault& f) {
    r.error_line = f.line;
    return r;
  }
  if (!std::all_of(s.colored.begin(), s.colored.end(), [](bool c) { return c; }))
    s.m.colors.clear();
  if (std::find(s.named_uv.begin(), s.named_uv.end(), true) == s.named_uv.end()) s.m.uvs.clear();
  if (std::find(s.named_normal.begin(), s.named_normal.end(), true) == s.named_normal.end())
    s.m.normals.clear();
  r.ok = true;
  r.mesh = std::move(s.m);
  return r;
}

}  // namespace sylva::test
