#pragma once
// Tellus's public API: results. Result<T> is a value or an Error whose message says what went
// wrong and where (the file, the tile, the argument); Status is success or an Error. Tellus
// returns these for bad input and failures instead of throwing or exiting.
#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace tellus {

struct Error {
  std::string message;
};

template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::move(value)) {}      // NOLINT: implicit by design
  Result(Error error) : state_(std::move(error)) {}  // NOLINT: implicit by design

  bool ok() const { return std::holds_alternative<T>(state_); }
  explicit operator bool() const { return ok(); }

  T& value() & {
    assert(ok() && "Result::value() called on an error");
    return std::get<T>(state_);
  }
  const T& value() const& {
    assert(ok() && "Result::value() called on an error");
    return std::get<T>(state_);
  }
  T&& value() && {
    assert(ok() && "Result::value() called on an error");
    return std::get<T>(std::move(state_));
  }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

  const Error& error() const {
    assert(!ok() && "Result::error() called on a value");
    return std::get<Error>(state_);
  }

 private:
  std::variant<T, Error> state_;
};

// Status: success or an Error (Result<void>).
class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error error) : error_(std::move(error)), failed_(true) {}  // NOLINT: implicit by design
  static Status success() { return {}; }

  bool ok() const { return !failed_; }
  explicit operator bool() const { return ok(); }
  const Error& error() const {
    assert(failed_ && "Status::error() called on success");
    return error_;
  }

 private:
  Error error_;
  bool failed_ = false;
};

}  // namespace tellus
