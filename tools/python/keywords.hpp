#pragma once
// Python keyword options read by the command's own parser: canopy.stand(..., per_row=5) is
// `canopy stand ... --per-row 5`, with the same names, checks, exclusions and messages, so the
// module can neither take what the command line refuses nor miss an option it has.
#include <CLI/CLI.hpp>
#include <pybind11/pybind11.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#pragma GCC visibility push(hidden)
namespace canopy::python {

namespace py = pybind11;

/// True or False, NumPy's bool too (not 1 or "yes": a flag is not a count, nor a seed a bool).
bool is_bool(py::handle v);

/// The decimal text of an integer, Python's or NumPy's (through operator.index); none for a bool
/// (is_bool) or anything that is not an integer (a float, a string). Seeds are read through it,
/// so that 64-bit values never pass through a double.
std::optional<std::string> integer_text(py::handle v);

/// Parses `kwargs` with `app` (a command's options registered on an app of its own), then
/// `positionals` as its arguments. A keyword is the option of its name with dashes for
/// underscores (`renames` maps a Python name to another option: suns -> sun); None is an option
/// not given. A flag takes True or False (False of `periodic`, an option of which only
/// `--no-periodic` exists, gives that); a list or tuple is one use per item for a repeatable
/// option (`--set`, `--sun`), else one value joined by commas; a dict gives NAME=VALUE uses; paths
/// may be str, bytes or os.PathLike. Throws std::invalid_argument with the command line's message
/// (`--per-row: needs a whole number from 1 to ...`), or "COMMAND: unknown option 'NAME'".
void parse_keywords(CLI::App& app, const std::string& command, const std::vector<std::string>& positionals,
                    const py::dict& kwargs, const std::map<std::string, std::string>& renames = {});

}  // namespace canopy::python
#pragma GCC visibility pop
