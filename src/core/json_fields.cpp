#include "core/json_fields.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace tandem {

Json readJsonFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "file not found or unreadable");
  std::stringstream ss;
  ss << in.rdbuf();
  try {
    return Json::parse(ss.str());
  } catch (const Json::exception& e) {  // parse errors and number overflow alike
    throw InputError(path, "", std::string("malformed JSON: ") + e.what());
  }
}

JsonFields::JsonFields(const Json& j, std::string file, std::string where)
    : j_(j), file_(std::move(file)), where_(std::move(where)) {
  if (!j_.is_object())
    throw InputError(file_, where_.empty() ? "(root)" : where_, "expected a JSON object");
}

void JsonFields::fail(const std::string& key, const std::string& problem) const {
  throw InputError(file_, field(key), problem);
}

const Json& JsonFields::raw(const std::string& key) {
  used_.insert(key);
  if (!j_.contains(key)) fail(key, "missing");
  return j_.at(key);
}

float JsonFields::number(const std::string& key, float def, float lo, float hi) {
  used_.insert(key);
  if (!j_.contains(key)) return def;
  const Json& v = j_.at(key);
  if (!v.is_number()) fail(key, "expected a number, got " + std::string(v.type_name()));
  double d = v.get<double>();
  if (!std::isfinite(d)) fail(key, "must be finite");
  if (d < lo || d > hi) {
    std::ostringstream os;
    os << "value " << d << " out of range [" << lo << ", " << hi << "]";
    fail(key, os.str());
  }
  return float(d);
}

int JsonFields::integer(const std::string& key, int def, int lo, int hi) {
  used_.insert(key);
  if (!j_.contains(key)) return def;
  const Json& v = j_.at(key);
  if (!v.is_number_integer()) fail(key, "expected an integer, got " + std::string(v.type_name()));
  long long d = v.get<long long>();
  if (d < lo || d > hi)
    fail(key, "value " + std::to_string(d) + " out of range [" + std::to_string(lo) + ", " +
                  std::to_string(hi) + "]");
  return int(d);
}

bool JsonFields::boolean(const std::string& key, bool def) {
  used_.insert(key);
  if (!j_.contains(key)) return def;
  const Json& v = j_.at(key);
  if (!v.is_boolean()) fail(key, "expected true or false, got " + std::string(v.type_name()));
  return v.get<bool>();
}

std::string JsonFields::string(const std::string& key, const std::string& def) {
  used_.insert(key);
  if (!j_.contains(key)) return def;
  const Json& v = j_.at(key);
  if (!v.is_string()) fail(key, "expected a string, got " + std::string(v.type_name()));
  return v.get<std::string>();
}

namespace {
template <int N>
void readArray(JsonFields& f, const Json& v, const std::string& key, float* out) {
  if (!v.is_array() || v.size() != N)
    f.fail(key, "expected an array of " + std::to_string(N) + " numbers");
  for (int i = 0; i < N; ++i) {
    if (!v[i].is_number()) f.fail(key, "expected an array of " + std::to_string(N) + " numbers");
    double d = v[i].get<double>();
    if (!std::isfinite(d)) f.fail(key, "must be finite");
    // Beyond a float's range the value would become infinite where it is used.
    if (std::abs(d) > double(std::numeric_limits<float>::max()))
      f.fail(key, "out of range: numbers must lie within +-3.4e38");
    out[i] = float(d);
  }
}
}  // namespace

Vec3 JsonFields::vec3(const std::string& key, Vec3 def) {
  used_.insert(key);
  if (!j_.contains(key)) return def;
  float v[3];
  readArray<3>(*this, j_.at(key), key, v);
  return {v[0], v[1], v[2]};
}

Vec2 JsonFields::vec2(const std::string& key, Vec2 def) {
  used_.insert(key);
  if (!j_.contains(key)) return def;
  float v[2];
  readArray<2>(*this, j_.at(key), key, v);
  return {v[0], v[1]};
}

void JsonFields::finish() const {
  for (auto it = j_.begin(); it != j_.end(); ++it)
    if (!used_.count(it.key())) fail(it.key(), "unknown field");
}

}  // namespace tandem
