#pragma once
/// The derived string as flat arrays: one symbol id per module and the parameters of all modules
/// back to back (each symbol has one parameter count, so no per-module offsets are stored).
/// Memory is proportional to the string; growing it allocates nothing per module.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

namespace canopy {

using Symbol = std::uint16_t;

/// A growable array of trivially copyable values that never initialises what it reserves.
template <typename T>
class PodBuffer {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  PodBuffer() = default;
  PodBuffer(const PodBuffer& o) { append(o.data_, o.size_); }
  PodBuffer& operator=(const PodBuffer& o) {
    if (this != &o) {
      size_ = 0;
      append(o.data_, o.size_);
    }
    return *this;
  }
  PodBuffer(PodBuffer&& o) noexcept : data_(o.data_), size_(o.size_), cap_(o.cap_) {
    o.data_ = nullptr;
    o.size_ = o.cap_ = 0;
  }
  PodBuffer& operator=(PodBuffer&& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(cap_, o.cap_);
    return *this;
  }
  ~PodBuffer() { std::free(data_); }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const T* data() const { return data_; }
  T* data() { return data_; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }
  void clear() { size_ = 0; }

  void reserve(std::size_t n) {
    if (n <= cap_) return;
    T* p = static_cast<T*>(std::realloc(data_, n * sizeof(T)));
    if (!p) throw std::bad_alloc();
    data_ = p;
    cap_ = n;
  }
  /// Makes room for `n` more values and returns where they go; commit with grow(n).
  T* room(std::size_t n) {
    if (size_ + n > cap_) reserve(std::max(size_ + n, cap_ + cap_ / 2 + 64));
    return data_ + size_;
  }
  void grow(std::size_t n) { size_ += n; }
  void push_back(T v) {
    *room(1) = v;
    ++size_;
  }
  void append(const T* p, std::size_t n) {
    if (n == 0) return;
    std::memcpy(room(n), p, n * sizeof(T));
    size_ += n;
  }
  void resize(std::size_t n) {
    reserve(n);
    size_ = n;
  }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t cap_ = 0;
};

struct ModuleString {
  PodBuffer<Symbol> symbols;
  PodBuffer<double> params;
  std::size_t size() const { return symbols.size(); }
};

/// Module names and their parameter counts, shared by a grammar and the strings it derives.
struct SourcePos;

class SymbolTable {
 public:
  /// The id of `name`, added if new (std::length_error past 65,535 names).
  Symbol intern(const std::string& name);
  /// The same for a name a grammar writes at `at`: past the limit, a GrammarError located there.
  Symbol intern(const std::string& name, const SourcePos& at);
  /// The id of `name` or -1.
  int find(const std::string& name) const;
  const std::string& name(Symbol s) const { return names_[s]; }
  /// Parameter count, or -1 while no use of the symbol has been seen.
  int arity(Symbol s) const { return arity_[s]; }
  void set_arity(Symbol s, int n) { arity_[s] = n; }
  std::size_t size() const { return names_.size(); }
  /// Ids of the brackets, which every table has.
  Symbol open_bracket() const { return 0; }
  Symbol close_bracket() const { return 1; }

  SymbolTable();

 private:
  std::vector<std::string> names_;
  std::vector<int> arity_;
  std::unordered_map<std::string, Symbol> index_;
};

}  // namespace canopy
