#include "core/scene/text_scan.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace sylva {
namespace {

bool blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

// Whether a decimal number that from_chars found outside a double's range is too large rather
// than too small: the power of ten of its first significant digit is positive (it is at least
// 308 or at most -324). `w` is what from_chars read: sign, digits, point, exponent.
bool beyond_max(std::string_view w) {
  size_t i = !w.empty() && (w[0] == '-' || w[0] == '+') ? 1 : 0;
  int64_t whole = 0, zeros = 0;  // significant digits before the point; zeros after it
  bool point = false, significant = false;
  for (; i < w.size() && w[i] != 'e' && w[i] != 'E'; ++i) {
    if (w[i] == '.') {
      point = true;
    } else if (significant || w[i] != '0') {
      significant = true;
      whole += point ? 0 : 1;
    } else if (point) {
      ++zeros;
    }
  }
  const bool negative = i + 1 < w.size() && w[i + 1] == '-';
  int64_t exponent = 0;
  for (size_t k = i + 1; k < w.size(); ++k)
    if (w[k] >= '0' && w[k] <= '9')
      exponent = std::min<int64_t>(exponent * 10 + (w[k] - '0'), 1 << 30);
  const int64_t power = whole > 0 ? whole - 1 : -(zeros + 1);
  return power + (negative ? -exponent : exponent) > 0;
}

}  // namespace

std::string TextScan::quote(std::string_view w) {
  std::string s = "'";
  for (char c : w.substr(0, 40))
    s += static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f ? '?' : c;
  s.append(w.size() > 40 ? "...'" : "'");
  return s;
}

void TextScan::skip_blanks(bool stop_at_newline) {
  while (m_pos < m_text.size()) {
    const char c = m_text[m_pos];
    if (m_comment && c == m_comment) {
      while (m_pos < m_text.size() && m_text[m_pos] != '\n')
        ++m_pos;
      continue;
    }
    if (!blank(c) || (stop_at_newline && c == '\n')) return;
    if (c == '\n') ++m_line;
    ++m_pos;
  }
}

bool TextScan::word(std::string_view& w) {
  skip_blanks(false);
  if (m_pos == m_text.size()) return false;
  const size_t start = m_pos;
  while (m_pos < m_text.size() && !blank(m_text[m_pos]) &&
         !(m_comment && m_text[m_pos] == m_comment))
    ++m_pos;
  w = m_text.substr(start, m_pos - start);
  m_word_line = m_line;
  return true;
}

bool TextScan::line(std::vector<std::string_view>& words) {
  words.clear();
  skip_blanks(false);
  if (m_pos == m_text.size()) return false;
  const size_t line = m_line;
  for (std::string_view w; m_line == line;) {
    skip_blanks(true);
    if (m_pos == m_text.size() || m_text[m_pos] == '\n') break;
    word(w);
    words.push_back(w);
  }
  m_word_line = line;
  return true;
}

double TextScan::number() {
  std::string_view w;
  if (!word(w)) fail("the file ends where a number was expected");
  return number(w);
}

double TextScan::number(std::string_view w) const {
  const bool plus = !w.empty() && w[0] == '+';  // from_chars takes no '+'
  const std::string_view digits = w.substr(plus ? 1 : 0);
  double v = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (digits.empty() || (plus && digits[0] == '-') || end != digits.data() + digits.size() ||
      (ec != std::errc() && ec != std::errc::result_out_of_range))
    fail("expected a number, got " + quote(w));
  if (ec == std::errc::result_out_of_range) {  // from_chars leaves v as it was
    v = beyond_max(digits) ? std::numeric_limits<double>::infinity() : 0.0;
    if (digits[0] == '-') v = -v;
  }
  return v;
}

float TextScan::finite_float(std::string_view w) const {
  const float f = float(number(w));
  if (!std::isfinite(f))
    fail("expected a finite number (magnitude at most 3.4e38), got " + quote(w));
  return f;
}

uint64_t TextScan::count(std::string_view w, const char* what, uint64_t max) const {
  uint64_t v = 0;
  const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
  if (w.empty() || end != w.data() + w.size() || ec != std::errc() || v > max)
    fail(std::string("expected ") + what + " (a whole number up to " + std::to_string(max) +
         "), got " + quote(w));
  return v;
}

void TextScan::fail(const std::string& what) const {
  throw InputError(m_path, where() + ": " + what);
}

}  // namespace sylva
