#pragma once
// Shared by the files of the canopy Python module: callbacks that carry Python exceptions through
// C++ loops, the stand object arrays view, and small conversions.
#include "collision/backend.hpp"
#include "tools/detect_options.hpp"
#include "tools/cli_common.hpp"
#include "tools/stand_run.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <charconv>
#include <map>
#include <optional>
#include <string>
#include <vector>

// Hidden, as pybind11's own types are: nothing here leaves the extension module.
#pragma GCC visibility push(hidden)
namespace canopy::python {

namespace py = pybind11;

/// Raised inside a long call when a Python callback raised: unwinds the C++ side, then the
/// Python error is restored.
struct CallbackRaised {};

/// Wraps a Python callable for a C++ loop: takes the GIL to call it; a Python exception is kept
/// (to be re-raised by `rethrow`) and the C++ work is stopped with CallbackRaised.
class Callback {
 public:
  /// Refuses what cannot be called before any work (progress=1 failed at its first call, after
  /// a sweep's first run was written).
  explicit Callback(py::object f) : f_(std::move(f)) {
    if (!f_.is_none() && !PyCallable_Check(f_.ptr()))
      throw py::type_error(
          fmt::format("progress must be callable (a function), got {}", py::repr(f_).cast<std::string>()));
  }
  ~Callback() {
    py::gil_scoped_acquire gil;
    error_.reset();
    f_ = py::object();
  }
  bool set() const { return !f_.is_none(); }
  template <typename... A>
  void operator()(A&&... args) {
    py::gil_scoped_acquire gil;
    try {
      f_(std::forward<A>(args)...);
    } catch (py::error_already_set& e) {
      error_.emplace(std::move(e));
      throw CallbackRaised{};
    }
  }
  [[noreturn]] void rethrow() {
    py::error_already_set e = std::move(*error_);
    error_.reset();
    throw e;
  }

 private:
  py::object f_;
  std::optional<py::error_already_set> error_;
};

/// A grammar's notes (Grammar::notes) as Python warnings (UserWarning), the GIL held.
inline void warn_notes(const std::vector<std::string>& notes) {
  for (const std::string& n : notes)
    if (PyErr_WarnEx(PyExc_UserWarning, n.c_str(), 1) != 0) throw py::error_already_set();
}

inline py::object json_to_py(const nlohmann::ordered_json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

/// A stand owned by Python: arrays handed out view its memory and keep this object alive.
struct PyStand {
  Stand stand;
  std::string grammar;
  std::optional<Contacts> before, after;  // export's contacts.csv and contacts_after.csv
  std::optional<RowLayout> layout;        // the rows it was grown in (its lattice is light's tile)
  std::vector<cli::RunInput> inputs;      // the files it was grown from: export never replaces them
  const char* in_use_by = nullptr;        // the call working on it with the GIL released (StandInUse)
};

/// Held by a call that works on a stand with the GIL released (detect, resolve, export, light):
/// another such call on the same stand meanwhile, from a progress callback or another Python
/// thread, is refused instead of reading or turning organs under the first. Made and dropped
/// with the GIL held, so the flag needs no lock.
class StandInUse {
 public:
  StandInUse(PyStand& s, const char* call) : s_(s) {
    if (s.in_use_by)
      throw std::runtime_error(
          fmt::format("{}: this stand is in use by {} (called from its progress callback or another thread); "
                      "call it once that returns",
                      call, s.in_use_by));
    s.in_use_by = call;
  }
  ~StandInUse() { s_.in_use_by = nullptr; }
  StandInUse(const StandInUse&) = delete;
  StandInUse& operator=(const StandInUse&) = delete;

 private:
  PyStand& s_;
};

/// A path from str, bytes or os.PathLike (bytes as they are: a file name need not be UTF-8).
/// (py::str of bytes is their repr, "b'...'", which named a file that does not exist.)
inline std::string path_of(py::handle h) {
  std::string path = py::module_::import("os").attr("fspath")(h).cast<std::string>();
  // As Python's open(): a NUL would cut the name where the system reads it.
  if (path.find('\0') != std::string::npos) throw py::value_error("embedded null byte in a path");
  return path;
}

/// A NumPy view of a stand's memory that NumPy may not write: the stand's arrays change only
/// through canopy's calls, which check what they are given (a NaN written into a transform was
/// used by detect() as it was).
inline py::array read_only(py::array a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

/// A whole-number argument checked by the command line's validator `check` (its message, as a
/// ValueError naming `name`); None: none given. Not an int nor an integer of NumPy's (a float, a
/// bool): a TypeError.
template <typename T>
std::optional<T> whole_arg(py::handle v, const char* name, const CLI::Validator& check) {
  if (v.is_none()) return std::nullopt;
  // An int or what stands for one (NumPy's integers: operator.index), not a bool or a float.
  if (PyBool_Check(v.ptr()) || !PyIndex_Check(v.ptr()))
    throw py::type_error(
        fmt::format("{}: needs an int, got {}", name, py::str(py::type::of(v)).cast<std::string>()));
  PyObject* index = PyNumber_Index(v.ptr());
  if (!index) throw py::error_already_set();  // its __index__ raised
  std::string text = py::str(py::reinterpret_steal<py::object>(index)).cast<std::string>();
  if (const std::string error = check(text); !error.empty())
    throw std::invalid_argument(fmt::format("{}: {}", name, error));
  T out{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  if (ec != std::errc{} || end != text.data() + text.size())
    throw std::invalid_argument(fmt::format("{}: {} does not fit", name, text));
  return out;
}

inline std::vector<std::string> overrides(const std::map<std::string, double>& set) {
  std::vector<std::string> v;
  for (const auto& [k, x] : set) v.push_back(fmt::format("{}={}", k, x));
  return v;
}

inline py::array contacts_array(const std::vector<Contact>& pairs) {
  py::dtype dt = py::dtype::from_args(
      py::list(py::make_tuple(py::make_tuple("organ_a", "<i4"), py::make_tuple("organ_b", "<i4"),
                              py::make_tuple("plant_a", "<i4"), py::make_tuple("plant_b", "<i4"))));
  py::array out(dt, std::vector<py::ssize_t>{static_cast<py::ssize_t>(pairs.size())});
  auto* p = static_cast<std::int32_t*>(out.mutable_data());
  for (std::size_t i = 0; i < pairs.size(); ++i)
    p[4 * i] = pairs[i].organ_a, p[4 * i + 1] = pairs[i].organ_b, p[4 * i + 2] = pairs[i].plant_a,
          p[4 * i + 3] = pairs[i].plant_b;
  return out;
}

inline std::unique_ptr<DetectionBackend> backend_named(const std::string& name, std::string& note) {
  cli::check_backend_name(name);  // 'bogus' ran as auto
  return cli::make_backend(name, note);
}

/// Registers canopy.Stand.
void bind_stand(py::module_& m);
/// Registers Stand.light and canopy.light (after bind_stand).
void bind_light(py::module_& m);

}  // namespace canopy::python
#pragma GCC visibility pop
