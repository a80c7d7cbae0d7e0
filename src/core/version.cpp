#include "core/version.hpp"

namespace granwave {
const char* version() { return GRANWAVE_VERSION; }
const char* git_describe() { return GRANWAVE_GIT_DESCRIBE; }
}  // namespace granwave
