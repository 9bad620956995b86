#include "resolution/auto_backend.hpp"

#include "resolution/attempt_runner_host.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <atomic>
#include <mutex>
#include <optional>

namespace canopy {
namespace {

/// Turns the preferred backend's failure into the switch to the fallback (AutoBackend::fall_back).
using OnFailure = std::function<void(const std::string& why)>;

/// The preferred backend's runner, and the host's answers from its first failure on. The host
/// runner keeps no state between calls (it reads the lane's tables whole), so it can take over
/// a lane in the middle of a batch.
class FallbackRunner : public AttemptRunner {
 public:
  explicit FallbackRunner(OnFailure on_failure) : on_failure_(std::move(on_failure)) {}

  /// The preferred backend's runner for this round (the same one every round of a resolution).
  void bind(AttemptRunner* first) {
    if (first != first_) told_ = false;  // a runner of its own that has not seen every organ
    first_ = first;
    if (!host_ || host_->lanes() != first->lanes())
      host_.emplace(lib_, omp_get_max_threads(), first->lanes());
  }

  void update_organs(const Stand& stand, std::span<const Obb> boxes, std::span<const std::uint32_t> changed,
                     bool all) override {
    host_->update_organs(stand, boxes, changed, all);  // pointers only: ready to take over
    if (failed_) return;
    try {
      first_->update_organs(stand, boxes, changed, all || !told_);
      told_ = true;
    } catch (const BackendFailure& e) {
      fail(e.what());
    }
  }
  std::size_t lanes() const override { return host_->lanes(); }  // the first runner's, fixed at bind
  std::string hardware() const override { return failed_ ? host_->hardware() : first_->hardware(); }
  void clear(std::size_t lane) override {
    if (failed_) return;
    try {
      first_->clear(lane);
    } catch (const BackendFailure& e) {
      fail(e.what());
    }
  }
  std::vector<std::uint32_t> touching(std::size_t lane, const AttemptTables& tables,
                                      std::span<const AttemptGroup> groups,
                                      const AttemptSettings& settings) override {
    if (!failed_) {
      try {
        return first_->touching(lane, tables, groups, settings);
      } catch (const BackendFailure& e) {
        fail(e.what());
      }
    }
    return host_->touching(lane, tables, groups, settings);
  }
  /// The preferred runner's; after a failure, nothing more is asked of it (the host runner's
  /// counts are of the calls it took over).
  void keep_statistics(bool on) override {
    if (failed_) return;
    try {
      first_->keep_statistics(on);
    } catch (const BackendFailure& e) {
      fail(e.what());
    }
  }
  AttemptStats take_statistics() override {
    if (!failed_) {
      try {
        return first_->take_statistics();
      } catch (const BackendFailure& e) {
        fail(e.what());
      }
    }
    return host_->take_statistics();
  }

 private:
  /// Lanes fail on threads of their own: the first failure is said, every one switches.
  void fail(const std::string& why) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!failed_) on_failure_(why);
    failed_ = true;
  }

  OnFailure on_failure_;
  AttemptRunner* first_ = nullptr;
  bool told_ = false;
  std::atomic<bool> failed_{false};
  std::mutex mutex_;
  PrototypeLibrary lib_;
  std::optional<HostAttemptRunner> host_;
};

class AutoBackend : public DetectionBackend, public AttemptSource {
 public:
  AutoBackend(std::unique_ptr<DetectionBackend> preferred, BackendMaker fallback)
      : first_(std::move(preferred)), make_fallback_(std::move(fallback)),
        runner_([this](const std::string& why) { fall_back(why); }) {}

  std::string name() const override { return second_ ? second_->name() : first_->name(); }
  /// After a fallback: the fallback's device, and what failed where.
  std::string device() const override {
    return second_ ? fmt::format("{} (the {} backend on {} failed: {})", second_->device(), first_->name(),
                                 first_->device(), why_)
                   : first_->device();
  }
  Contacts detect(const Stand& s, const DetectRequest& r) override {
    if (!second_) {
      try {
        return first_->detect(s, r);
      } catch (const BackendFailure& e) {
        fall_back(e.what());
      }
    }
    second_has_tree_ = true;
    return second_->detect(s, r);
  }
  Contacts redetect(const Stand& s, const DetectRequest& r,
                    const std::vector<std::uint32_t>& moved) override {
    if (!second_) {
      try {
        return first_->redetect(s, r, moved);
      } catch (const BackendFailure& e) {
        fall_back(e.what());
      }
    }
    if (!second_has_tree_) {  // the fallback has no tree yet: it builds one (and detects the active plants)
      second_has_tree_ = true;
      return second_->detect(s, r);
    }
    return second_->redetect(s, r, moved);
  }
  /// The preferred backend's runner, through FallbackRunner; the fallback's (if any) after a failure.
  AttemptRunner* attempt_runner(const Stand& s) override {
    if (!second_) {
      try {
        AttemptSource* source = attempt_source(*first_);
        if (AttemptRunner* first = source ? source->attempt_runner(s) : nullptr) {
          runner_.bind(first);
          return &runner_;
        }
        return nullptr;
      } catch (const BackendFailure& e) {
        fall_back(e.what());
      }
    }
    AttemptSource* source = second_has_tree_ ? attempt_source(*second_) : nullptr;
    return source ? source->attempt_runner(s) : nullptr;
  }

 private:
  /// Called once, on the thread that met the failure (a lane's, for the runner); the callers
  /// of detect, redetect and attempt_runner see the switch at their next call.
  void fall_back(const std::string& why) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (second_) return;
    second_ = make_fallback_();
    why_ = why;
    fmt::print(stderr, "canopy: note: the {} backend failed ({}); going on with the {} backend\n",
               first_->name(), why, second_->name());
  }

  std::unique_ptr<DetectionBackend> first_;
  BackendMaker make_fallback_;
  std::unique_ptr<DetectionBackend> second_;
  bool second_has_tree_ = false;
  std::string why_;
  std::mutex mutex_;
  FallbackRunner runner_;
};

}  // namespace

std::unique_ptr<DetectionBackend> make_auto_backend(std::unique_ptr<DetectionBackend> preferred,
                                                    BackendMaker fallback) {
  return std::make_unique<AutoBackend>(std::move(preferred), std::move(fallback));
}

}  // namespace canopy
