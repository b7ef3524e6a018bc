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
    if (!field.empty()) s += ": " + field;
    return s + ": " + problem;
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
