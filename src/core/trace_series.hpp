// A run's trace datasets as the run holds them in memory (RunRequest::keep, models.hpp).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace granwave {

// Each dataset under its path in the trace file ("/time", "/crystal/layer_stress_zz", ...; not
// /system), with the file's shape and values.
struct TraceSeries {
  struct Dataset {
    std::string path;
    std::vector<std::size_t> shape;
    std::vector<double> values;        // a float64 dataset, or
    std::vector<std::int64_t> counts;  // an int64 one (/chain/full_rate/beads)
  };
  std::vector<Dataset> datasets;
};

}  // namespace granwave
