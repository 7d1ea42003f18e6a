#pragma once
// Errors raised at the engine's boundaries (loaders, ray files, parameters). Hot code asserts.
#include <stdexcept>
#include <string>

namespace edacrt {

/// Bad input from outside: a file, a ray set, a parameter. The message names what was wrong
/// and where ("scene.obj:12: face index 9 out of range (8 vertices)").
class InputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// A command line that asks for something impossible: a flag's value out of range, flags that
/// do not go together. Reported as bad input is, with the usage error's exit status (2).
class UsageError : public InputError {
  public:
    using InputError::InputError;
};

}  // namespace edacrt
