#pragma once
/// The detection options shared by `canopy stand` and `canopy detect`, and the backend factory.
#include "collision/backend.hpp"
#include "tools/cli_common.hpp"

#include <nlohmann/json.hpp>

#include <memory>
#include <string>

namespace canopy::cli {

struct DetectOptions {
  std::string level = "exact";
  double clearance = 0;
  std::string collide = "all";  // every organ kind the grammar emits, fruit and flowers included
  std::string backend = "auto";
  int threads = 0;
  std::string max_device_memory;  // "", bytes, or with K, M, G

  void add_to(CLI::App& app);
  DetectRequest request() const;
};

/// The backend `name` asks for: cpu, cuda, or auto (where a GPU is present the CUDA backend whole,
/// its device attempts included, with the CPU's from a CUDA failure on; else the CPU's: resolution/
/// auto_backend.hpp); `note` says what was picked and why. The command line, the Python module and
/// the benchmark programs all get their backend here. With several GPUs, `device_hint` modulo their count
/// picks one (a rank's local rank: one GPU per rank).
/// Throws std::invalid_argument naming --backend unless `name` is cpu, cuda or auto (the Python
/// module hands names over unchecked; the command line checks them as it parses).
void check_backend_name(const std::string& name);

std::unique_ptr<DetectionBackend> make_backend(const std::string& name, std::string& note,
                                               int device_hint = 0);

/// Per-level counts as JSON: {"plant": {"between": n, "within": m, "total": t}, ...}, null for
/// levels not computed.
nlohmann::ordered_json counts_json(const Contacts& c);
/// The terminal table of a detection.
void print_contacts_table(const Contacts& c, const std::string& backend);

}  // namespace canopy::cli
