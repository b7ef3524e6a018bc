// Error policy: bad input at the edges (files, JSON, CLI) throws InputError naming the file,
// the field and the problem; the CLI prints it and exits non-zero. Bugs use TANDEM_ASSERT.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace tandem {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& field, const std::string& problem)
      : std::runtime_error(compose(file, field, problem)), problem_(problem) {}
  // The problem alone, for rethrowing under a more precise file and field.
  const std::string& problem() const { return problem_; }

 private:
  std::string problem_;
  static std::string compose(const std::string& file, const std::string& field,
                             const std::string& problem) {
    std::string s = file.empty() ? std::string("input") : file;
    if (!field.empty()) s += ": " + printable(field);
    return s + ": " + printable(problem);
  }
  // Messages may quote what a broken file holds: keep control bytes off the terminal.
  static std::string printable(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (unsigned char c : text) {
      if (c == '\n') {
        out += "; ";
      } else if (c < 0x20 || c == 0x7f) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02x", c);
        out += hex;
      } else {
        out += char(c);
      }
    }
    return out;
  }
};

}  // namespace tandem

#define TANDEM_ASSERT(cond)                                                             \
  do {                                                                                  \
    if (!(cond)) {                                                                      \
      std::fprintf(stderr, "%s:%d: assertion failed: %s\n", __FILE__, __LINE__, #cond); \
      std::abort();                                                                     \
    }                                                                                   \
  } while (0)
