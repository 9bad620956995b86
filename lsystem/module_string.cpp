#include "lsystem/module_string.hpp"

#include "lsystem/error.hpp"

#include <stdexcept>

namespace canopy {

SymbolTable::SymbolTable() {
  intern("[");
  intern("]");
  arity_[0] = arity_[1] = 0;
}

Symbol SymbolTable::intern(const std::string& name) {
  if (auto it = index_.find(name); it != index_.end()) return it->second;
  if (names_.size() >= 0xffff) throw std::length_error("too many distinct module names (at most 65535)");
  const auto id = static_cast<Symbol>(names_.size());
  names_.push_back(name);
  arity_.push_back(-1);
  index_.emplace(name, id);
  return id;
}

Symbol SymbolTable::intern(const std::string& name, const SourcePos& at) {
  if (names_.size() >= 0xffff && !index_.count(name))
    fail_at(at, "too many distinct module names (at most 65535): '{}' is one more", name);
  return intern(name);
}

int SymbolTable::find(const std::string& name) const {
  auto it = index_.find(name);
  return it == index_.end() ? -1 : it->second;
}

}  // namespace canopy
