// Temporary weak stand-ins so the binary links while the models and verbs are being written
// in parallel; each real definition overrides its stand-in. Removed once all have landed.
#include "cli/verbs.hpp"
#include "core/error.hpp"
#include "models.hpp"

#define GRANWAVE_PENDING(what) throw granwave::RunError(std::string(what) + " is not built yet")

namespace granwave {
namespace chain {
[[gnu::weak]] void check(const config::Case&, std::ostream&) { GRANWAVE_PENDING("the chain model"); }
[[gnu::weak]] void build(const config::Case&, const std::string&) { GRANWAVE_PENDING("the chain model"); }
[[gnu::weak]] int run(const config::Case&, const RunRequest&, std::ostream&) { GRANWAVE_PENDING("the chain model"); }
}  // namespace chain
namespace crystal {
[[gnu::weak]] void check(const config::Case&, std::ostream&) { GRANWAVE_PENDING("the crystal model"); }
[[gnu::weak]] void build(const config::Case&, const std::string&) { GRANWAVE_PENDING("the crystal model"); }
[[gnu::weak]] int run(const config::Case&, const RunRequest&, std::ostream&) { GRANWAVE_PENDING("the crystal model"); }
}  // namespace crystal
namespace cli {
[[gnu::weak]] int cmd_analyze(const Args&) { GRANWAVE_PENDING("granwave analyze"); }
[[gnu::weak]] int cmd_theory(const Args&) { GRANWAVE_PENDING("granwave theory"); }
[[gnu::weak]] int cmd_sweep(const Args&) { GRANWAVE_PENDING("granwave sweep"); }
[[gnu::weak]] int cmd_figures(const Args&) { GRANWAVE_PENDING("granwave figures"); }
[[gnu::weak]] int figures_crystal(const Args&) { GRANWAVE_PENDING("granwave figures crystal"); }
}  // namespace cli
}  // namespace granwave
