// Version and provenance, compiled into one translation unit only (so that a new commit
// recompiles one file, not the whole tree).
#pragma once

namespace granwave {
const char* version();       // the project version (CMake project VERSION)
const char* git_describe();  // `git describe --always --dirty --tags` at configure time
}  // namespace granwave
