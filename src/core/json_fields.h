// Strict reading of a JSON object: every key is read with a default at the point of use, and
// finish() rejects keys nobody read (misspellings), naming the file and the field path.
#pragma once
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/math.h"

namespace tandem {

using Json = nlohmann::json;

// Parses a whole JSON file; errors name the file and the line/byte of the problem.
Json readJsonFile(const std::string& path);

class JsonFields {
 public:
  JsonFields(const Json& j, std::string file, std::string where);

  bool has(const std::string& key) const { return j_.contains(key); }
  const Json& raw(const std::string& key);  // marks the key used; it must exist
  float number(const std::string& key, float def, float lo = -1e30f, float hi = 1e30f);
  int integer(const std::string& key, int def, int lo, int hi);
  bool boolean(const std::string& key, bool def);
  std::string string(const std::string& key, const std::string& def);
  // One of named values: `choices` pairs each accepted string with its value; a missing key
  // gives `def` (or, with none, fails as a wrong value would: "expected a, b or c, got ''").
  template <class E>
  E choice(const std::string& key, std::optional<E> def,
           std::initializer_list<std::pair<const char*, E>> choices) {
    std::string got;
    if (!has(key) && def) {
      used_.insert(key);
      return *def;
    }
    if (has(key)) got = string(key, "");
    std::string expected;
    size_t k = 0;
    for (const auto& [name, value] : choices) {
      if (got == name) return value;
      expected += (k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ") + std::string(name);
      ++k;
    }
    fail(key, "expected " + expected + ", got '" + got + "'");
  }
  Vec3 vec3(const std::string& key, Vec3 def);
  Vec2 vec2(const std::string& key, Vec2 def);
  // Name of the field for error messages, e.g. "objects[2].position".
  std::string field(const std::string& key) const {
    return where_.empty() ? key : where_ + "." + key;
  }
  const std::string& file() const { return file_; }
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;
  void finish() const;  // throws on unknown keys

 private:
  const Json& j_;
  std::string file_, where_;
  std::set<std::string> used_;
};

}  // namespace tandem
