// `granwave observables [--json]`: the crystal's table of observables (crystal/observables.hpp) --
// every dataset a crystal trace can hold, its `[output] fields` name, shape, unit and how it is
// sampled and reduced. The crosscheck reads its field list from the JSON (crosscheck/xclib/observables.py).
#include <iostream>
#include <ostream>

#include "cli/verbs.hpp"
#include "core/error.hpp"
#include "core/json.hpp"
#include "crystal/observables.hpp"

namespace granwave::cli {

namespace {
constexpr const char* kObservablesHelp = R"(usage: granwave observables [--json]

The crystal trace's observables, one table (src/crystal/observables.cpp): for each dataset its path,
the `[output] fields` name that selects it, its shape ([nt] or [nt, nlayers]), its unit and how it is
sampled and reduced. /time [nt] s and /crystal/layer_z [nlayers] m are always written.
  --json   one object, schema "granwave-observables/1": {"schema", "crystal": [{"name", "path",
           "field", "shape", "unit", "sampled"}, ...], "fields": [the allowed `[output] fields`]}
)";

const char* shape_name(crystal::Shape s) { return s == crystal::Shape::per_layer ? "[nt, nlayers]" : "[nt]"; }
}  // namespace

int cmd_observables(const Args& args, std::ostream& out) {
  if (wants_help(args)) {
    out << kObservablesHelp;
    return 0;
  }
  const bool json = has_flag(args, "--json");
  for (const auto& a : args)
    if (a != "--json") throw InputError("observables: unknown argument '" + a + "' (allowed: --json)");
  if (json) {
    Json list = Json::array();
    for (const auto& o : crystal::observables()) {
      const Json shape = o.shape == crystal::Shape::per_layer ? Json{"nt", "nlayers"} : Json{"nt"};
      list.push_back({{"name", o.name}, {"path", o.path()}, {"field", o.field}, {"shape", shape}, {"unit", o.unit},
                      {"sampled", o.sampled}});
    }
    out << json_text({{"schema", "granwave-observables/1"}, {"crystal", list}, {"fields", crystal::output_fields()}});
    return 0;
  }
  out << "crystal trace observables (`[output] fields` name in brackets):\n";
  for (const auto& o : crystal::observables())
    out << "  " << o.path() << " " << shape_name(o.shape) << " " << o.unit << " [" << o.field << "]: " << o.sampled << "\n";
  return 0;
}

int cmd_observables(const Args& args) { return cmd_observables(args, std::cout); }

}  // namespace granwave::cli
