// granwave._granwave: the command line's verbs in-process, for the Python package python/granwave/.
// Each function runs the program's own code (src/cli/, src/models.hpp) and returns what the verb
// prints with --json; run also the run's series as numpy arrays over the run's own buffers. The
// GIL is released while they run.
#include <chrono>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <toml++/toml.h>

#include "cli/verbs.hpp"
#include "config/case.hpp"
#include "core/error.hpp"
#include "io/h5.hpp"
#include "models.hpp"
#include "packing/prepared_state.hpp"
#include "sweep/study.hpp"

namespace py = pybind11;
using namespace granwave;

namespace {

// Rethrows `e`; an HDF5 failure that escapes io/ is bad input, as in main.cpp.
[[noreturn]] void rethrow(std::exception_ptr e) {
  try {
    std::rethrow_exception(e);
  } catch (const std::exception&) {  // py::error_already_set too
    throw;
  } catch (...) {
    if (const std::string why = io::hdf5_exception_message(); !why.empty()) throw InputError("HDF5: " + why);
    throw;
  }
}

// Runs `f` without the GIL.
template <class F>
auto released(F&& f) {
  py::gil_scoped_release release;
  try {
    return f();
  } catch (...) {
    rethrow(std::current_exception());
  }
}

// A verb's --json (or text) output.
std::string verb(int (*cmd)(const cli::Args&, std::ostream&), const std::vector<std::string>& args) {
  return released([&] {
    std::ostringstream out;
    cmd(args, out);
    return out.str();
  });
}

// A Python value of a case dict as a TOML node (bool before int: Python's bool is an int).
toml::table table_of(const py::dict& d, const std::string& where);
void insert(toml::table& t, const std::string& key, const py::handle& v, const std::string& where);

toml::array array_of(const py::handle& seq, const std::string& where) {
  toml::array a;
  for (const auto& item : seq) {
    if (py::isinstance<py::bool_>(item)) a.push_back(item.cast<bool>());
    else if (py::isinstance<py::int_>(item)) a.push_back(item.cast<std::int64_t>());
    else if (py::isinstance<py::float_>(item)) a.push_back(item.cast<double>());
    else if (py::isinstance<py::str>(item)) a.push_back(item.cast<std::string>());
    else if (py::isinstance<py::dict>(item)) a.push_back(table_of(item.cast<py::dict>(), where));
    else if (py::isinstance<py::list>(item) || py::isinstance<py::tuple>(item)) a.push_back(array_of(item, where));
    else throw InputError(where + ": a list item of type " + std::string(py::str(item.get_type().attr("__name__"))) +
                          " has no TOML value");
  }
  return a;
}

void insert(toml::table& t, const std::string& key, const py::handle& v, const std::string& where) {
  const std::string at = where.empty() ? key : where + "." + key;
  if (py::isinstance<py::bool_>(v)) t.insert_or_assign(key, v.cast<bool>());
  else if (py::isinstance<py::int_>(v)) t.insert_or_assign(key, v.cast<std::int64_t>());
  else if (py::isinstance<py::float_>(v)) t.insert_or_assign(key, v.cast<double>());
  else if (py::isinstance<py::str>(v)) t.insert_or_assign(key, v.cast<std::string>());
  else if (py::isinstance<py::dict>(v)) t.insert_or_assign(key, table_of(v.cast<py::dict>(), at));
  else if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) t.insert_or_assign(key, array_of(v, at));
  else throw InputError(at + ": a value of type " + std::string(py::str(v.get_type().attr("__name__"))) + " has no TOML value");
}

toml::table table_of(const py::dict& d, const std::string& where) {
  toml::table t;
  for (const auto& [k, v] : d) insert(t, py::str(k).cast<std::string>(), v, where);
  return t;
}

// The run hook: every `interval` of wall time it takes the GIL, lets Python handle its signals
// (KeyboardInterrupt stops the run by the exception it raises) and calls `callback`.
struct Stepper {
  std::chrono::steady_clock::duration interval;
  py::object callback;
  std::chrono::steady_clock::time_point next = std::chrono::steady_clock::now();
  void operator()(long done, long total) {
    const auto now = std::chrono::steady_clock::now();
    if (now < next && done < total) return;
    next = now + interval;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (!callback.is_none()) callback(done, total);
  }
};

// The kept series as numpy arrays keyed by their path without the leading "/": views of the
// series' own buffers, which one capsule (the arrays' base) frees with the last of them.
py::dict arrays_of(std::unique_ptr<TraceSeries> kept) {
  py::dict out;
  if (kept->datasets.empty()) return out;
  TraceSeries* owner = kept.release();
  const py::capsule base(owner, [](void* p) { delete static_cast<TraceSeries*>(p); });
  for (auto& d : owner->datasets) {
    const std::vector<py::ssize_t> shape(d.shape.begin(), d.shape.end());
    if (!d.counts.empty())
      out[py::str(d.path.substr(1))] = py::array_t<std::int64_t>(shape, d.counts.data(), base);
    else
      out[py::str(d.path.substr(1))] = py::array_t<double>(shape, d.values.data(), base);
  }
  return out;
}

// A study on a thread of its own while the calling thread, every `check_seconds`, takes the GIL,
// lets Python handle its signals and calls callback(done, total) (members). KeyboardInterrupt
// (or the callback's exception) asks the study to stop, waits for it (members end at their next
// output sample) and is raised; the study's own rules leave no partial file (sweep/study.hpp).
std::string supervised_sweep(const std::vector<std::string>& args, const py::object& callback, double check_seconds) {
  sweep::StudyControl control;
  std::mutex m;
  std::condition_variable cv;
  bool finished = false;
  std::string text;
  std::exception_ptr error;
  std::thread worker([&] {
    try {
      std::ostringstream out;
      cli::cmd_sweep(args, out, &control);
      text = out.str();
    } catch (...) {
      error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(m);
    finished = true;
    cv.notify_all();
  });
  const auto interval = std::chrono::duration<double>(check_seconds);
  std::exception_ptr raised;  // KeyboardInterrupt, or what the callback raised
  for (;;) {
    bool done;
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(m);
      done = cv.wait_for(lock, interval, [&] { return finished; });
    }
    if (done) break;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!callback.is_none()) callback(control.done.load(), control.total.load());
    } catch (...) {
      raised = std::current_exception();
      control.stop = true;
      break;
    }
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (raised) std::rethrow_exception(raised);
  if (error) rethrow(error);
  if (!callback.is_none()) callback(control.done.load(), control.total.load());
  return text;
}

}  // namespace

PYBIND11_MODULE(_granwave, m) {
  m.doc() = "granwave's verbs in-process (use the package granwave, not this module)";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const RunError& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });

  m.def(
      "parse_case",
      [](const std::string& text, const std::string& origin) {
        const config::Case c = config::parse_case(text, origin);
        const char* model = c.model == config::Model::chain ? "chain" : c.model == config::Model::crystal ? "crystal" : "impact";
        return py::make_tuple(c.name, model);
      },
      "Validate a case text as `granwave check` loads it; (name, model). ValueError with the program's message.");

  m.def(
      "toml_text", [](const py::dict& d) {
        std::ostringstream o;
        o << table_of(d, "");
        return o.str() + "\n";
      },
      "A case dict as TOML text (floats as the shortest text that reads back as the same double).");

  m.def(
      "run",
      [](const std::string& text, const std::string& origin, const std::string& trace_path, const std::string& system_path,
         py::object callback, double check_seconds, bool in_memory) {
        // A random packing's system file holds it as prepared: taken instead of preparing it again.
        std::optional<packing::PreparedState> prepared = packing::prepared_of_system(system_path);
        const config::Case c = config::parse_case(text, origin, config::CaseParse::everything, prepared ? &*prepared : nullptr);
        prepared.reset();
        RunRequest req;
        req.trace_path = trace_path;
        req.system_path = system_path;
        req.json = true;
        req.quiet = true;
        req.in_memory = in_memory;
        auto kept = std::make_unique<TraceSeries>();
        req.keep = [&kept](TraceSeries&& s) { *kept = std::move(s); };
        Stepper step{std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(check_seconds)),
                     std::move(callback)};
        req.progress = [&step](long done, long total) { step(done, total); };
        std::string json = released([&] {
          std::ostringstream out;
          cli::run_case(c, req, out);
          return out.str();
        });
        return py::make_tuple(json, arrays_of(std::move(kept)));
      },
      py::arg("text"), py::arg("origin"), py::arg("trace_path"), py::arg("system_path") = "", py::arg("callback") = py::none(),
      py::arg("check_seconds") = 0.005, py::arg("in_memory") = false,
      "`granwave run CASE --json -o TRACE` of a case text: (the JSON it prints, {dataset path: array}).\n"
      "The arrays are the run's own series (no copy), the trace file's datasets but /system. in_memory:\n"
      "the trace file is built and measured in memory only (an impact run measures its series and\n"
      "builds none), TRACE only names it. Every check_seconds the run takes the GIL, handles signals\n"
      "(KeyboardInterrupt stops it, no file written) and calls callback(done, total).");

  m.def("analyze", [](const std::vector<std::string>& a) { return verb(cli::cmd_analyze, a); }, "`granwave analyze ARGS`'s output");
  m.def("theory", [](const std::vector<std::string>& a) { return verb(cli::cmd_theory, a); }, "`granwave theory ARGS`'s output");
  m.def("build", [](const std::vector<std::string>& a) { return verb(cli::cmd_build, a); }, "`granwave build ARGS`'s output");
  m.def("probe", [](const std::vector<std::string>& a) { return verb(cli::cmd_probe, a); }, "`granwave probe ARGS`'s output");
  m.def("observables", [](const std::vector<std::string>& a) { return verb(cli::cmd_observables, a); },
        "`granwave observables ARGS`'s output");
  m.def("sweep", &supervised_sweep, py::arg("args"), py::arg("callback") = py::none(), py::arg("check_seconds") = 0.005,
        "`granwave sweep ARGS`'s output. The study runs on a thread of its own; every check_seconds this\n"
        "one handles signals and calls callback(members_done, members_total). KeyboardInterrupt stops the\n"
        "study (each running member at its next output sample) and is raised once it has stopped.");
}
