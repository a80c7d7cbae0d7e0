// Version and provenance strings, compiled into this one translation unit (core/version.hpp).
#include "core/version.hpp"

#include "git_describe.h"  // GRANWAVE_GIT_DESCRIBE, written at each build (cmake/git_describe.cmake)

namespace granwave {
const char* version() { return GRANWAVE_VERSION; }
const char* git_describe() { return GRANWAVE_GIT_DESCRIBE; }
}  // namespace granwave
