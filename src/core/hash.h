// A 64-bit content hash (FNV-1a over bytes), for cache keys: same content, same key, on every
// machine (values are hashed as their little-endian bytes; floats by bit pattern).
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/math.h"

namespace tandem {

class Hasher {
 public:
  Hasher& bytes(const void* p, size_t n) {
    const unsigned char* c = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h_ = (h_ ^ c[i]) * 0x100000001b3ull;
    return *this;
  }
  template <class T>
  Hasher& pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    return bytes(&v, sizeof(T));
  }
  Hasher& str(const std::string& s) { return pod(uint64_t(s.size())).bytes(s.data(), s.size()); }
  template <class T>
  Hasher& vec(const std::vector<T>& v) {
    return pod(uint64_t(v.size())).bytes(v.data(), v.size() * sizeof(T));
  }
  uint64_t value() const { return h_; }
  std::string hex() const;

 private:
  uint64_t h_ = 0xcbf29ce484222325ull;
};

inline std::string Hasher::hex() const {
  static const char* digits = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 0; i < 16; ++i) s[size_t(i)] = digits[(h_ >> (60 - 4 * i)) & 15u];
  return s;
}

}  // namespace tandem
