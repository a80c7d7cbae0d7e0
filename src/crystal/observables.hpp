// The one table of the crystal's observables (docs/design.md §2.2): every series a run samples
// and its trace file holds -- name, shape, unit, how it is sampled and reduced -- with the
// sampling function that fills it. The trace writer, the in-memory series (Python's arrays), the
// allowed `[output] fields`, the guards' sizes and `granwave observables` are read from it.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace granwave::config {
struct Case;
}

namespace granwave::crystal {

class Dynamics;

// [nt] (one value per sample) or [nt, nlayers] (one per layer, row-major).
enum class Shape { series, per_layer };

// One dataset of the trace.
struct Observable {
  std::string group;    // "/crystal" or "/energy"
  std::string name;     // the dataset's name in its group (unique over the table)
  std::string field;    // the `[output] fields` name that selects it ("energy": all of /energy)
  Shape shape = Shape::series;
  std::string unit;     // SI, "1" for a pure number
  std::string sampled;  // how it is sampled and reduced
  std::string path() const { return group + "/" + name; }
};

// An observer: one sampling function and the observables it fills, in trace order. At each sample
// `sample(dyn, out)` writes observable k's values to out[k]: per_layer, nlayers values (under a slab
// plan, those of this rank's layers: rank 0 gathers them); series, one value, the same on every rank
// (a collective call). A sum runs over flat arrays in a fixed order, so that a value does not
// depend on the thread or rank count.
struct Observer {
  std::vector<Observable> observables;
  void (*sample)(const Dynamics& dyn, double* const* out);
};

// The table, in the trace file's order.
const std::vector<Observer>& observers();
// Its observables, flattened, in the same order.
const std::vector<Observable>& observables();
// The allowed names of `[output] fields`, in table order, each once.
std::vector<std::string> output_fields();
// Whether the case's `[output] fields` select `o` (no fields: all).
bool selected(const config::Case& c, const Observable& o);
// Refuses (InputError naming output.fields and the allowed names) a field that is no observable's.
void check_output_fields(const config::Case& c);

}  // namespace granwave::crystal
