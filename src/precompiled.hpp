// The libraries' and the verbs' precompiled header (CMakeLists.txt): the standard library's common
// headers and nlohmann::json (core/json.hpp), parsed once per build instead of once per unit. Only
// external headers, and not Eigen or toml++ (ARCHITECTURE.md says which folders may use them): a
// source file still includes what it uses (tests/cli/include_claims.py reads the includes).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>
