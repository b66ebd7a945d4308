// Errors: SYLVA_CHECK for programming mistakes (aborts with file:line), InputError for bad
// input (a file, option, preset key or scene) that main() reports in one line with exit 2.
#pragma once

#include <stdexcept>
#include <string>

namespace sylva {

// Bad input. `where` names the file, option or key; `what` says what is wrong and what is
// allowed. Printed by the CLI as "sylva: error: <where>: <what>".
class InputError : public std::runtime_error {
 public:
  InputError(std::string where, const std::string& what)
      : std::runtime_error(where.empty() ? what : where + ": " + what),
        m_where(std::move(where)),
        m_reason(what) {}
  const std::string& where() const { return m_where; }
  const std::string& reason() const { return m_reason; }  // what() without "where: "

 private:
  std::string m_where;
  std::string m_reason;
};

[[noreturn]] void check_failed(const char* expr, const char* file, int line,
                               const std::string& msg);

}  // namespace sylva

#define SYLVA_CHECK(cond, msg)                                            \
  do {                                                                    \
    if (!(cond)) ::sylva::check_failed(#cond, __FILE__, __LINE__, (msg)); \
  } while (0)
