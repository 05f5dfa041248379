#pragma once
// Reading the fuzzer's bytes as a few little-endian parameters followed by a payload, for the
// libFuzzer targets.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

namespace tellus::fuzz {

class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  // The next T from the input, 0 when the input is exhausted.
  template <typename T>
  T take() {
    T value{};
    const std::size_t n = std::min(sizeof(T), size_ - offset_);
    std::memcpy(&value, data_ + offset_, n);
    offset_ += n;
    return value;
  }
  // Everything not taken yet.
  std::span<const std::byte> rest() const {
    return {reinterpret_cast<const std::byte*>(data_ + offset_), size_ - offset_};
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
};

}  // namespace tellus::fuzz
