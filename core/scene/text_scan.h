// Words and numbers of a text mesh file (OFF, ASCII PLY, ASCII STL), each with the line it is
// on, so that an error says where: InputError(path, "line 12: expected a number, got 'x'").
// `comment` (e.g. '#' for OFF) starts a comment that runs to the end of its line.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sylva {

class TextScan {
 public:
  // `first_line` numbers the text's first line (a part of a file, after a header).
  TextScan(std::string_view text, std::string path, char comment = 0, size_t first_line = 1)
      : m_text(text),
        m_path(std::move(path)),
        m_comment(comment),
        m_line(first_line),
        m_word_line(first_line) {}

  // The next word, or false at the end of the text.
  bool word(std::string_view& w);
  // The words of the next line that has any (comments dropped), or false at the end.
  bool line(std::vector<std::string_view>& words);
  // The next word as a number; the end of the text or a word that is not one is an error.
  // A number is decimal (an optional sign, digits with an optional point, an optional
  // exponent), "inf" or "nan" (callers that need finite values check them); one beyond a
  // double's range is +-inf, one below it +-0.
  double number();
  double number(std::string_view w) const;
  // A number as a float that is finite (no inf, nan or magnitude over 3.4e38); else an error.
  float finite_float(std::string_view w) const;
  // A whole number in [0, max], named `what` in the error.
  uint64_t count(std::string_view w, const char* what, uint64_t max) const;

  size_t offset() const { return m_pos; }  // bytes consumed
  size_t remaining() const { return m_text.size() - m_pos; }
  std::string where() const { return "line " + std::to_string(m_word_line); }
  const std::string& path() const { return m_path; }
  [[noreturn]] void fail(const std::string& what) const;  // InputError(path, "line N: what")
  // A word as an error shows it: in quotes, at most 40 characters, control bytes as '?'.
  static std::string quote(std::string_view w);

 private:
  void skip_blanks(bool stop_at_newline);
  std::string_view m_text;
  std::string m_path;
  char m_comment;
  size_t m_pos = 0;
  size_t m_line;       // the line m_pos is on
  size_t m_word_line;  // the line of the last word returned
};

}  // namespace sylva
