// Stand.grow's positions: rows x, y, rotation, seed from a NumPy array or a list of rows, each
// seed taken as the whole number it is. A float64 array holds whole numbers exactly only up to
// 2^53, and canopy's own seeds (plants.csv) are 63-bit hashes: an integer array, or a list of
// Python ints, keeps them; a float past 2^53 is refused instead of rounded to another plant.
#include "tools/python/positions_array.hpp"

#include "tools/python/keywords.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace canopy::python {

namespace {

/// Seed `d` of row `i`, given as a float: a whole number a float holds exactly.
std::uint64_t seed_of_float(double d, py::ssize_t i) {
  const auto refuse = [&](const char* why) {
    throw std::invalid_argument(fmt::format("positions: row {}: the seed {}, got {:.17g}", i, why, d));
  };
  if (!(d >= 0 && std::floor(d) == d && d < 0x1p64)) refuse("must be a non-negative integer below 2^64");
  if (d > 0x1p53)
    refuse(
        "lies past 2^53, where a float64 holds only some whole numbers (it would be read as another "
        "seed): give the positions as an integer array (dtype=np.uint64) or a list of rows with "
        "Python ints");
  return static_cast<std::uint64_t>(d);
}

/// Seed `v` of row `i`: an integer (Python's or NumPy's), or a float.
std::uint64_t seed_of(const py::handle& v, py::ssize_t i) {
  const auto refuse = [&](const std::string& why) {
    throw std::invalid_argument(
        fmt::format("positions: row {}: the seed {}, got {}", i, why, py::repr(v).cast<std::string>()));
  };
  if (is_bool(v)) refuse("must be a whole number, not a bool");
  if (const std::optional<std::string> whole = integer_text(v)) {
    if (const auto s = parse_seed(*whole)) return *s;
    refuse("must be a non-negative integer below 2^64");
  }
  double d = 0;
  try {
    d = v.cast<double>();
  } catch (const py::cast_error&) {
    refuse("must be a whole number");
  }
  return seed_of_float(d, i);
}

double number_of(const py::handle& v, py::ssize_t i, const char* what) {
  try {
    return v.cast<double>();
  } catch (const py::cast_error&) {
    throw std::invalid_argument(fmt::format("positions: row {}: {} must be a number, got {}", i, what,
                                            py::repr(v).cast<std::string>()));
  }
}

}  // namespace

std::vector<PlantPlacement> placements_of(const py::object& positions) {
  std::vector<PlantPlacement> out;
  const auto shape_error = [] {
    return std::invalid_argument("positions: an array of rows x, y, rotation, seed (N x 4)");
  };
  // A list (or tuple) of rows is read row by row: NumPy would make one float64 array of a row of
  // floats and a large int, rounding the int. Anything else (an array, a DataFrame, what NumPy
  // reads) becomes an array first, as np.asarray makes it.
  const bool rows_given = py::isinstance<py::list>(positions) || py::isinstance<py::tuple>(positions);
  py::array arr;
  if (!rows_given) {
    try {
      arr = py::module_::import("numpy").attr("asarray")(positions);
    } catch (const py::error_already_set&) {
      throw shape_error();
    }
    if (arr.ndim() != 2 || arr.shape(1) != 4) throw shape_error();
    const char kind = arr.dtype().kind();
    if (kind == 'f' && arr.dtype().itemsize() > 8)
      throw std::invalid_argument(
          "positions: a long double array: give the seeds as integers (an integer array, dtype=np.uint64, or "
          "a "
          "list of rows) and the positions as float64");
    // A float array (the common case, and large): read through a typed view, seeds checked.
    if (kind == 'f') {
      const auto a = py::array_t<double, py::array::forcecast>::ensure(arr).unchecked<2>();
      out.reserve(static_cast<std::size_t>(a.shape(0)));
      for (py::ssize_t i = 0; i < a.shape(0); ++i) {
        PlantPlacement p;
        p.x = a(i, 0), p.y = a(i, 1), p.rotation_deg = a(i, 2);
        p.seed = seed_of_float(a(i, 3), i);
        out.push_back(p);
      }
      return out;
    }
  }
  // Rows (integer or object arrays as lists of Python values, lists of rows): each seed exact.
  py::sequence rows;
  try {
    rows = py::reinterpret_borrow<py::sequence>(rows_given ? positions : arr.attr("tolist")());
  } catch (const py::error_already_set&) {
    throw shape_error();
  }
  const auto n = static_cast<py::ssize_t>(py::len(rows));
  out.reserve(static_cast<std::size_t>(n));
  for (py::ssize_t i = 0; i < n; ++i) {
    const py::object row = rows[static_cast<std::size_t>(i)];
    if (!py::isinstance<py::sequence>(row) || py::isinstance<py::str>(row) || py::len(row) != 4)
      throw shape_error();
    const py::sequence r = py::reinterpret_borrow<py::sequence>(row);
    PlantPlacement p;
    p.x = number_of(r[0], i, "x"), p.y = number_of(r[1], i, "y");
    p.rotation_deg = number_of(r[2], i, "the rotation");
    p.seed = seed_of(r[3], i);
    out.push_back(p);
  }
  return out;
}

}  // namespace canopy::python
