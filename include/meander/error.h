// Meander's error policy: every stage that can fail throws one of these,
// with a message that names the file, the line or element, and what is wrong.
// The CLI catches them once in main() and maps them to exit codes
// (InputError/TopologyError/IOError -> 1, UsageError -> 2).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace meander {

// Base of everything Meander throws on purpose.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// The content of an input is malformed ("bunny.obj:1042: face references vertex 9001 but only 8000 exist").
class InputError : public Error {
public:
  using Error::Error;
};

// A well-formed file that holds no polylines (no `l` elements, no edges): what a
// caller trying a file as a curve and then as a mesh (`meander render`) tells apart
// from a malformed curve file.
class NoPolylinesError : public InputError {
public:
  using InputError::InputError;
};

// A file cannot be opened, read, written or renamed.
class IOError : public Error {
public:
  using Error::Error;
};

// The mesh is well formed but its topology is refused
// ("edge (17,42) is shared by 3 faces: mesh is not manifold").
class TopologyError : public Error {
public:
  using Error::Error;
};

// An option value is out of range or inconsistent with the input.
class UsageError : public Error {
public:
  using Error::Error;
};

// A parameter's value is refused. The message starts with the parameter's name as the
// jobs spell it ("samples must be at least 1 (got 0)", parameters.h); the CLI shows the
// name as its option instead (--samples).
class ParameterError : public UsageError {
public:
  // `rest` follows the name: " must be at least 1 (got 0)", ": expected a string".
  ParameterError(std::string_view parameter, std::string_view rest)
      : UsageError(std::string(parameter) + std::string(rest)), parameter_(parameter) {}
  const std::string& parameter() const { return parameter_; }

private:
  std::string parameter_;
};

} // namespace meander
