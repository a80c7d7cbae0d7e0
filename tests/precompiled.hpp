// The test executables' precompiled header (CMakeLists.txt): the heavy third-party headers most test
// files reach (Catch2's single header, Eigen through the theory's types) and the standard library's
// common ones, parsed once for all test targets instead of once per test file. Only external headers:
// a test file still includes what it uses (tests/cli/house_rules.py reads the includes).
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>
