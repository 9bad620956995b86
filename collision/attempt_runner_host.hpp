#pragma once
/// The attempts of a batched turn search answered on the host, group by group on all threads:
/// the reference the device runner must equal, and what lets the batched scan be tested where
/// there is no GPU. (The CPU backend's own planning keeps the candidate-by-candidate search,
/// which stops at the first touching pair and is faster on the host.)
#include "collision/attempt_batch.hpp"
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

namespace canopy {

class HostAttemptRunner : public AttemptRunner {
 public:
  HostAttemptRunner(PrototypeLibrary& lib, int threads) : lib_(lib), threads_(threads) {}
  void update_organs(const Stand& stand, std::span<const Obb> boxes, std::span<const std::uint32_t>, bool) override {
    stand_ = &stand, boxes_ = boxes;
  }
  void clear() override {}
  std::vector<std::uint32_t> touching(const AttemptTables& tables, std::span<const AttemptGroup> groups,
                                      const AttemptSettings& settings) override;

 private:
  const Stand* stand_ = nullptr;
  std::span<const Obb> boxes_;
  PrototypeLibrary& lib_;
  int threads_;
};

}  // namespace canopy
