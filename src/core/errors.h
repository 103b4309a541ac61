#pragma once
//! \file errors.h
//! \brief The project's exception hierarchy and the checked-precondition macro.
//!
//! The library reports failure only by throwing one of these; the CLI maps them to exit codes
//! (ARCHITECTURE §4): InputError (and OutputError) -> 2, GeometryError/SolverError -> 3, anything else -> 4.

#include <stdexcept>
#include <string>

namespace polycube::core {

//! Base of every polycube exception.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! Bad input: malformed, truncated, unsupported or inconsistent file or data.
class InputError : public Error {
 public:
  using Error::Error;
  //! "file:line: what" (line omitted when <= 0, file omitted when empty).
  InputError(const std::string& file, long line, const std::string& what);
};

//! A file could not be written (no space left, no permission, a folder in the way): the user's
//! to fix like bad input (exit code 2), whichever stage was writing.
class OutputError : public InputError {
 public:
  using InputError::InputError;
};

//! The geometry does not allow the requested operation (open surface, inverted map, ...).
class GeometryError : public Error {
 public:
  using Error::Error;
};

//! A numerical or combinatorial solver failed to reach a valid result.
class SolverError : public Error {
 public:
  using Error::Error;
};

//! The user cancelled a long operation through the progress interface.
class Cancelled : public Error {
 public:
  Cancelled() : Error("cancelled") {}
};

//! A violated internal invariant (a bug).
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

namespace detail {
[[noreturn]] void throw_internal(const char* cond, const char* file, int line, const std::string& msg);
}  // namespace detail

}  // namespace polycube::core

//! Check an internal precondition; throws InternalError naming the condition, file and line.
#define PC_REQUIRE(cond, msg)                                                          \
  do {                                                                                 \
    if (!(cond)) ::polycube::core::detail::throw_internal(#cond, __FILE__, __LINE__, (msg)); \
  } while (false)
