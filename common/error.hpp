#pragma once
/// @brief Errors a user can cause. They are always checked and reach the user as one line.
///
/// Programmer invariants use assert(); everything a file, a parameter or a diverging
/// solve can break throws one of these, with a message that says what and where.

#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace ligsim {

/// Base of every user-facing error.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Bad input: a missing or malformed file, an invalid parameter, an unusable mesh.
class InputError : public Error {
public:
  using Error::Error;
};

/// A computation that cannot finish: divergence, an inverted element, a non-finite value.
class SolverError : public Error {
public:
  using Error::Error;
};

/// Throws E with a fmt-formatted message.
template <class E = InputError, class... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args)
{
  throw E(fmt::format(format, std::forward<Args>(args)...));
}

} // namespace ligsim
