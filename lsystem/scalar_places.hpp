#pragma once
/// Where each byte of a YAML scalar's value was written. A scalar's value is not its source text:
/// double quotes turn escapes (`\t`, `\u00e9`) into bytes and drop a backslash before a line
/// break, single quotes write a quote as `''`, and a quoted, plain or folded scalar broken over
/// lines reads each break as a space, without the indentation around it. A grammar error inside
/// a production written so must still name its line and column in the file.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace canopy {

struct SourcePlace {
  int line = 0, column = 0;  // 1-based
};

/// The place of every byte of `value`, and one more for its end, found by walking the scalar's
/// source from `start` (the first character of the node: its quote, its block indicator `|` or
/// `>`, or its first character when plain; at `line`, `column`) beside the value: source
/// characters that equal the value's are its places, escapes and `''` stand for what they
/// decode to, and white space and line breaks the value dropped are passed over. Empty where the
/// source does not give the value so (the caller falls back to an estimate).
std::vector<SourcePlace> scalar_places(std::string_view text, std::size_t start, int line, int column,
                                       const std::string& value);

}  // namespace canopy
