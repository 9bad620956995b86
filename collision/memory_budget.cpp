#include "collision/memory_budget.hpp"

#include "geometry/available_memory.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace canopy {

std::size_t memory_budget(std::size_t limit) { return limit ? limit : memory_available(); }

void refuse_plant_pairs(std::uint64_t most, std::size_t budget) {
  throw std::runtime_error(
      fmt::format("the plants' bounds meet in more than {} pairs (plants on or near one spot?): their "
                  "contact lists would need more than the "
                  "{} of memory available; spread the plants out or use fewer",
                  most, memory_text(static_cast<double>(budget))));
}

void check_resolution_fits(std::size_t contacts, std::size_t limit) {
  const std::size_t budget = memory_budget(limit);
  const double need = static_cast<double>(contacts) * kResolutionBytesPerContact;
  if (budget == 0 || need <= static_cast<double>(budget)) return;
  throw std::runtime_error(
      fmt::format("resolving {} contacts needs about {} of memory, more than the {} available "
                  "(plants overlap heavily); "
                  "run with --no-resolve, or spread the plants out or use fewer",
                  contacts, memory_text(need), memory_text(static_cast<double>(budget))));
}

MemoryCeiling::MemoryCeiling(std::size_t limit) : budget_(memory_budget(limit)), limited_(limit > 0) {
  if (budget_ > 0) ceiling_ = resident_memory() + budget_ / 10 * 9;
}

bool MemoryCeiling::over() const { return ceiling_ > 0 && resident_memory() > ceiling_; }

void MemoryCeiling::refuse(const char* what) const {
  throw std::runtime_error(
      fmt::format("{} grew past the {} of memory {} (the process holds {}): organs that turn "
                  "carry long chains, or plants overlap heavily; run with --no-resolve, or give fewer or "
                  "shorter plants",
                  what, memory_text(static_cast<double>(budget_)), limited_ ? "it may use" : "available",
                  memory_text(static_cast<double>(resident_memory()))));
}

}  // namespace canopy
