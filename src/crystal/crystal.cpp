// Entry points of the crystal model (src/models.hpp): check, build, run.
#include <ostream>

#include "core/error.hpp"
#include "crystal/packing.hpp"
#include "io/h5.hpp"
#include "models.hpp"

namespace granwave::crystal {

void check(const config::Case&, std::ostream&) { throw RunError("crystal check: not yet"); }
void build(const config::Case& c, const std::string& system_path) {
  const Packing p = make_packing(c);
  io::H5Writer w(system_path);
  io::write_provenance(w);
  write_system(w, p, c.name);
  w.commit();
}
int run(const config::Case&, const RunRequest&, std::ostream&) { throw RunError("crystal run: not yet"); }

}  // namespace granwave::crystal
