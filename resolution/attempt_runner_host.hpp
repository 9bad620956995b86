#pragma once
/// The attempts of a batched turn search answered on the host, group by group on all threads:
/// the reference the device runner must equal, and what lets the batched scan be tested where
/// there is no GPU. (The CPU backend's own planning keeps the candidate-by-candidate search,
/// which stops at the first touching pair and is faster on the host.)
#include "resolution/attempt_batch.hpp"
#include "geometry/prototype.hpp"
#include "geometry/stand.hpp"

#include <atomic>

namespace canopy {

class HostAttemptRunner : public AttemptRunner {
 public:
  /// `lanes`: how many batches it takes at once (it keeps no state per batch, so any number).
  HostAttemptRunner(PrototypeLibrary& lib, int threads, std::size_t lanes = 1)
      : lib_(lib), threads_(threads), lanes_(lanes) {}
  void update_organs(const Stand& stand, std::span<const Obb> boxes, std::span<const std::uint32_t>,
                     bool) override {
    stand_ = &stand, boxes_ = boxes;
  }
  std::size_t lanes() const override { return lanes_; }
  std::string hardware() const override { return "host"; }
  void clear(std::size_t) override {}
  std::vector<std::uint32_t> touching(std::size_t lane, const AttemptTables& tables,
                                      std::span<const AttemptGroup> groups,
                                      const AttemptSettings& settings) override;
  /// Nothing beyond its counts of calls and groups, which cost an atomic add per call.
  void keep_statistics(bool) override {}
  AttemptStats take_statistics() override;

 private:
  const Stand* stand_ = nullptr;
  std::span<const Obb> boxes_;
  PrototypeLibrary& lib_;
  int threads_;
  std::size_t lanes_;
  std::atomic<std::uint64_t> calls_{0}, groups_{0};  // lanes call from threads of their own
};

}  // namespace canopy
