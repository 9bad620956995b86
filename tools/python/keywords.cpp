#include "tools/python/keywords.hpp"

#include "tools/cli_common.hpp"
#include "tools/python/common.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace canopy::python {
namespace {

/// Options that name a file or folder: their values are paths (str, bytes or os.PathLike, as
/// os.fspath takes them; anything else is a TypeError, as a path argument is).
bool is_path_option(const std::string& name) { return name == "--out" || name == "--positions"; }

/// A list of values: any iterable but a string, bytes, a dict or a path (a list, tuple, range,
/// set or NumPy array).
bool is_sequence(py::handle v) {
  if (py::isinstance<py::str>(v) || py::isinstance<py::bytes>(v) || py::isinstance<py::dict>(v) ||
      py::hasattr(v, "__fspath__") || !py::hasattr(v, "__iter__"))
    return false;
  // A NumPy array of no dimensions (np.array(2)) has __iter__ but is one value.
  return !(py::hasattr(v, "ndim") && py::int_(v.attr("ndim")).cast<int>() == 0);
}

}  // namespace

bool is_bool(py::handle v) {
  if (py::isinstance<py::bool_>(v)) return true;
  const std::string type = py::str(py::type::handle_of(v).attr("__name__"));
  const std::string module = py::str(py::getattr(py::type::handle_of(v), "__module__", py::str("")));
  return module == "numpy" && (type == "bool_" || type == "bool");
}

std::optional<std::string> integer_text(py::handle v) {
  if (is_bool(v)) return std::nullopt;
  try {
    return py::str(py::module_::import("operator").attr("index")(v)).cast<std::string>();
  } catch (const py::error_already_set&) {
    return std::nullopt;
  }
}

namespace {

/// One word of the command line: bytes and paths as they are (a file name need not be UTF-8),
/// anything else as Python prints it (floats as their shortest round trip).
std::string word(py::handle v) {
  // A NUL would cut the word where the system reads it (a path, a grammar's name), as
  // Python's open() refuses it.
  std::string w = py::isinstance<py::bytes>(v)   ? v.cast<std::string>()
                  : py::hasattr(v, "__fspath__") ? path_of(v)
                                                 : py::str(v).cast<std::string>();
  if (w.find('\0') != std::string::npos) throw py::value_error("embedded null byte in a value");
  return w;
}

/// The item of a list: a pair (elevation, azimuth) is "60,180".
std::string item_word(py::handle v) {
  if (!is_sequence(v)) return word(v);
  std::string s;
  for (py::handle x : v) s += (s.empty() ? "" : ",") + word(x);
  return s;
}

std::string dashed(std::string name) {
  std::replace(name.begin(), name.end(), '_', '-');
  return "--" + name;
}

}  // namespace

void parse_keywords(CLI::App& app, const std::string& command, const std::vector<std::string>& positionals,
                    const py::dict& kwargs, const std::map<std::string, std::string>& renames) {
  cli::one_value_per_use(app);
  cli::refuse_empty_values(app);
  std::vector<std::string> words;
  // periodic=True beside no_periodic=True said nothing (periodic is no flag of its own, only
  // its negation is; where both are flags, the parser refuses the pair): the two must agree.
  for (auto item : kwargs) {
    const std::string key = py::str(item.first);
    if (key.starts_with("no_") && !item.second.is_none() && kwargs.contains(key.substr(3)) &&
        !kwargs[py::str(key.substr(3))].is_none() && app.get_option_no_throw(dashed(key)) &&
        !app.get_option_no_throw(dashed(key.substr(3))) &&
        PyObject_IsTrue(item.second.ptr()) == PyObject_IsTrue(kwargs[py::str(key.substr(3))].ptr()))
      throw std::invalid_argument(fmt::format("{}: give {} or {}, not both", command, key.substr(3), key));
  }
  for (auto item : kwargs) {
    const std::string key = py::str(item.first);
    const py::handle v = item.second;
    if (v.is_none()) continue;
    const auto renamed = renames.find(key);
    const std::string name = dashed(renamed == renames.end() ? key : renamed->second);
    const CLI::Option* opt = key == "help" ? nullptr : app.get_option_no_throw(name);
    const CLI::Option* negation = app.get_option_no_throw("--no-" + name.substr(2));
    if (!opt && !negation) throw std::invalid_argument(fmt::format("{}: unknown option '{}'", command, key));
    if (!opt || opt->get_expected_max() == 0) {  // a flag
      if (!is_bool(v))
        throw std::invalid_argument(
            fmt::format("{}: {} takes True or False, got {}", command, key, py::repr(v).cast<std::string>()));
      if (PyObject_IsTrue(v.ptr()) == 1) {
        if (!opt) continue;  // periodic=True: the default, no flag says it
        words.push_back(name);
      } else if (negation && negation->get_expected_max() == 0) {
        words.push_back(negation->get_name());
      }
      continue;
    }
    std::vector<std::string> values;
    if (is_path_option(name)) {
      values.push_back(path_of(v));
    } else if (py::isinstance<py::dict>(v)) {
      for (auto kv : v.cast<py::dict>()) values.push_back(word(kv.first) + "=" + word(kv.second));
    } else if (is_sequence(v)) {
      for (py::handle x : v) values.push_back(item_word(x));
    } else {
      values.push_back(word(v));
    }
    // NAME=VALUE, so a value that starts with '-' is not taken for an option; an empty value as a
    // word of its own, which the parser checks (it passes "--positions=" as no value at all).
    const auto use = [&](const std::string& x) {
      if (x.empty()) words.insert(words.end(), {name, x});
      else words.push_back(name + "=" + x);
    };
    if (opt->get_expected_max() > 1) {  // repeatable: one use per value
      for (const std::string& x : values) use(x);
    } else {
      std::string joined;
      for (const std::string& x : values) joined += (joined.empty() ? "" : ",") + x;
      use(joined);
    }
  }
  words.push_back("--");  // what follows is an argument even where it starts with '-'
  words.insert(words.end(), positionals.begin(), positionals.end());
  std::reverse(words.begin(), words.end());  // CLI11 takes the words last first
  try {
    app.parse(words);
  } catch (const CLI::ParseError& e) {
    std::string m = cli::parse_error_line(e);
    const std::string prefix = "canopy: error: ";
    if (m.starts_with(prefix)) m.erase(0, prefix.size());
    throw std::invalid_argument(m);
  }
}

}  // namespace canopy::python
