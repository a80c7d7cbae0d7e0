// Errors that carry their exit code (docs/design.md §2.3): 2 = bad input, 1 = failed run.
#pragma once
#include <stdexcept>
#include <string>

namespace granwave {

// Bad input: names the file, the key and what is allowed. Exit code 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A run that went wrong (NaN, blow-up, I/O failure). Exit code 1.
struct RunError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace granwave
