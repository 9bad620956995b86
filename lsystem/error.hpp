#pragma once
/// Located errors: every grammar problem names file, line and column (1-based).
#include <fmt/format.h>

#include <stdexcept>
#include <string>

namespace canopy {

/// A place in a source file; line and column are 1-based, 0 means "unknown".
struct SourcePos {
  std::string file;
  int line = 0;
  int column = 0;

  /// The same place moved `offset` characters to the right on the same line.
  SourcePos shifted(int offset) const { return {file, line, column + offset}; }
  std::string str() const {
    if (line <= 0) return file;
    return fmt::format("{}:{}:{}", file, line, column);
  }
};

/// An error in a grammar file or in what it derives; what() is one line "file:line:col: message".
class GrammarError : public std::runtime_error {
 public:
  GrammarError(const SourcePos& pos, const std::string& message)
      : std::runtime_error(pos.str() + ": " + message), pos_(pos), message_(message) {}
  const SourcePos& pos() const { return pos_; }
  const std::string& message() const { return message_; }

 private:
  SourcePos pos_;
  std::string message_;
};

/// A grammar file that cannot be opened (Python sees FileNotFoundError).
class GrammarFileError : public GrammarError {
 public:
  using GrammarError::GrammarError;
};

/// A derivation that would exceed its module cap (a clear stop instead of running out of memory).
class ModuleCapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <typename... Args>
[[noreturn]] inline void fail_at(const SourcePos& pos, fmt::format_string<Args...> f, Args&&... args) {
  throw GrammarError(pos, fmt::format(f, std::forward<Args>(args)...));
}

}  // namespace canopy
