#pragma once
// Results that say why they failed. Each is false or true (explicit operator bool),
// carries a message, prints with <<, and converts to GoogleTest's
// ::testing::AssertionResult (or any type shaped like it) without this library
// linking GoogleTest, so that EXPECT_TRUE(outcome) prints the message on failure.
#include <concepts>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>

namespace physics_testing {

// Shaped like ::testing::AssertionResult: made from a bool, takes text with <<, and
// has a failure message.
template <class A>
concept AssertionLike = requires(A a, const std::string& text) {
  A(true);
  a << text;
  { a.failure_message() } -> std::convertible_to<const char*>;
};

class Outcome {
 public:
  static Outcome success() { return Outcome(true, {}); }
  static Outcome failure(std::string message) { return Outcome(false, std::move(message)); }

  bool ok() const { return ok_; }
  // Why it failed ("" on success).
  const std::string& message() const { return message_; }
  explicit operator bool() const { return ok_; }

  template <AssertionLike A>
  operator A() const {  // NOLINT(google-explicit-constructor): EXPECT_TRUE needs it implicit
    A result(ok_);
    if (!message_.empty()) result << message_;
    return result;
  }

 private:
  Outcome(bool ok, std::string message) : ok_(ok), message_(std::move(message)) {}
  bool ok_;
  std::string message_;
};

inline std::ostream& operator<<(std::ostream& out, const Outcome& outcome) {
  return outcome.ok() ? out << "ok" : out << "failed: " << outcome.message();
}

// A value, or the message saying why there is none.
template <class T>
class Expected {
 public:
  Expected(T value) : value_(std::move(value)) {}  // NOLINT: returning a T is success
  static Expected failure(std::string message) { return Expected(std::move(message)); }

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  const std::string& message() const { return message_; }
  Outcome outcome() const { return ok() ? Outcome::success() : Outcome::failure(message_); }

  // The value; std::logic_error with the message when there is none.
  T& value() {
    if (!value_) throw std::logic_error(message_);
    return *value_;
  }
  const T& value() const {
    if (!value_) throw std::logic_error(message_);
    return *value_;
  }
  T& operator*() { return value(); }
  const T& operator*() const { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

  template <AssertionLike A>
  operator A() const {  // NOLINT(google-explicit-constructor)
    return static_cast<A>(outcome());
  }

 private:
  explicit Expected(std::string message) : message_(std::move(message)) {}
  std::optional<T> value_;
  std::string message_;
};

template <class T>
std::ostream& operator<<(std::ostream& out, const Expected<T>& expected) {
  return out << expected.outcome();
}

}  // namespace physics_testing
