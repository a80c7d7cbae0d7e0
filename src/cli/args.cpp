// The verbs' argument parsing (cli/verbs.hpp): flags, option values, positionals, layer ranges.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "cli/verbs.hpp"
#include "core/error.hpp"

namespace granwave::cli {

bool wants_help(const Args& args) {
  return std::any_of(args.begin(), args.end(), [](const std::string& a) { return a == "--help" || a == "-h"; });
}

std::string option_value(const Args& args, const std::string& short_name, const std::string& long_name) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    if ((!short_name.empty() && args[i] == short_name) || args[i] == long_name) {
      if (i + 1 >= args.size()) throw InputError("option " + args[i] + " needs a value");
      return args[i + 1];
    }
    if (args[i].rfind(long_name + "=", 0) == 0) return args[i].substr(long_name.size() + 1);
  }
  return {};
}

bool has_flag(const Args& args, const std::string& name) { return std::find(args.begin(), args.end(), name) != args.end(); }

void parse_layers(const std::string& s, const char* what, int* lo, int* hi) {
  const auto colon = s.find(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    *lo = std::stoi(s.substr(0, colon));
    *hi = std::stoi(s.substr(colon + 1));
  } catch (const std::exception&) {
    throw InputError("--layers " + s + ": expected LO:HI (" + what + ")");
  }
  if (*lo < 0 || *hi <= *lo) throw InputError("--layers " + s + ": need 0 <= LO < HI");
}

std::vector<std::string> positionals(const Args& args, const std::vector<std::string>& valued) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (std::find(valued.begin(), valued.end(), args[i]) != valued.end()) {
      ++i;
      continue;
    }
    if (args[i].rfind("-", 0) == 0) continue;
    out.push_back(args[i]);
  }
  return out;
}

}  // namespace granwave::cli
