#pragma once
// FNV-1a, 64 bits (Fowler, Noll & Vo): a hash of bytes fed in pieces, for the fingerprint of a
// run's parameters and the checksum of a saved state. It tells an edited or damaged value from
// the one written; it is not a defence against forgery.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace scatterlab {

class Fnv1a {
 public:
  void add(std::span<const std::byte> bytes) {
    for (const std::byte b : bytes) {
      hash_ ^= static_cast<std::uint64_t>(b);
      hash_ *= 0x100000001b3ull;
    }
  }
  void add(std::string_view text) { add(std::as_bytes(std::span(text.data(), text.size()))); }
  // A value's bytes as they are in memory (little-endian on every platform scatterlab runs on).
  template <class T>
  void add_bytes_of(std::span<const T> values) {
    add(std::as_bytes(values));
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace scatterlab
