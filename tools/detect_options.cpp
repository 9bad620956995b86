#include "tools/detect_options.hpp"
#include "resolution/auto_backend.hpp"
#include "tools/stand_options.hpp"
#include "tools/sweep_spec.hpp"

#include <fmt/format.h>
#ifdef CANOPY_HAVE_CUDA
#include "cuda/detect_cuda.hpp"
#include "cuda/device.hpp"
#endif

namespace canopy::cli {

void DetectOptions::add_to(CLI::App& app) {
  const OptionGroup group(app, kDetectGroup);
  app.add_option("--level", level, "Contact level: plant, leaf, organ or exact (default exact)")
      ->check(CLI::IsMember({"plant", "leaf", "organ", "exact"}));
  app.add_option("--clearance", clearance,
                 "Organs closer than this many metres count as a contact (default 0, at most 100)")
      ->check(kFinite)
      ->check(number_in(0, kMaxClearance))
      ->check(metres_note("--clearance"));
  app.add_option("--collide", collide,
                 "Organ kinds that take part, comma separated (internode, petiole, rachis, leaflet, "
                 "peduncle, fruit, flower), "
                 "or all (default all: every organ of the stand's files)");
  app.add_option(
         "--backend", backend,
         "Detection backend: cpu, cuda or auto (default auto: CUDA when a GPU is present); for canopy "
         "light also where drawn passes run")
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}));
  app.add_option("--threads", threads,
                 "CPU threads for every phase of the run (default: all cores, or OMP_NUM_THREADS)")
      ->transform(thread_count());
  app.add_option("--max-device-memory", max_device_memory,
                 "CUDA: device memory detection may use, e.g. 512M or 2G (default: what is free); lists that "
                 "would not fit "
                 "are made in batches");
}

DetectRequest DetectOptions::request() const {
  check_backend_name(backend);
  DetectRequest r;
  r.level = *parse_contact_level(level);
  r.clearance = static_cast<float>(clearance);
  r.collide = parse_collide_kinds(collide);
  r.threads = threads;
  if (!max_device_memory.empty()) {
    std::size_t used = 0;
    const double v = leading_number(max_device_memory, used);
    const std::string unit = used ? max_device_memory.substr(used) : "";
    const double scale = unit.empty() ? 1 : unit == "K" ? 1e3 : unit == "M" ? 1e6 : unit == "G" ? 1e9 : -1;
    if (!used || scale < 0 || !(v > 0))
      throw std::invalid_argument(
          fmt::format("--max-device-memory: '{}' is not a size such as 512M or 2G", max_device_memory));
    if (!(v * scale <= 1e15))  // a petabyte: more than any device holds, and a size_t still
      throw std::invalid_argument(
          fmt::format("--max-device-memory: '{}' is more than 1e15 bytes (1000000G)", max_device_memory));
    r.max_device_bytes = static_cast<std::size_t>(v * scale);
  }
  return r;
}

void check_backend_name(const std::string& name) {
  if (name != "cpu" && name != "cuda" && name != "auto")
    throw std::invalid_argument(fmt::format("--backend: '{}' is not cpu, cuda or auto", name));
}

std::unique_ptr<DetectionBackend> make_backend(const std::string& name, std::string& note, int device_hint) {
  if (name == "cpu") {
    auto cpu = make_cpu_backend();
    note = fmt::format("cpu on {} (asked for)", cpu->device());
    return cpu;
  }
#ifdef CANOPY_HAVE_CUDA
  const auto report = cuda::query_devices();
  std::string why = report.unavailable_reason;
  if (!report.devices.empty()) {
    const int device = device_hint % static_cast<int>(report.devices.size());
    note = fmt::format("cuda on {} ({})", report.devices[static_cast<std::size_t>(device)].name,
                       name == "cuda" ? "asked for" : "auto: a GPU is present");
    if (name == "cuda") return cuda::make_cuda_backend(device);
    // auto: the CUDA backend whole (its device attempts too), the CPU's from a CUDA failure on.
    try {
      return make_auto_backend(cuda::make_cuda_backend(device), make_cpu_backend);
    } catch (const BackendFailure& e) {
      why = e.what();
    }
  }
#else
  (void)device_hint;
  const std::string why = "this build has no CUDA backend";
#endif
  if (name == "cuda")
    throw std::runtime_error(fmt::format("--backend cuda: no usable GPU ({}); use --backend cpu", why));
  auto cpu = make_cpu_backend();
  note = fmt::format("cpu on {} (auto: no usable GPU: {})", cpu->device(), why);
  return cpu;
}

nlohmann::ordered_json counts_json(const Contacts& c) {
  nlohmann::ordered_json j;
  for (std::size_t l = 0; l < 4; ++l) {
    const auto& k = c.counts[l];
    j[std::string(kContactLevelNames[l])] =
        k ? nlohmann::ordered_json{{"between", k->between}, {"within", k->within}, {"total", k->total()}}
          : nlohmann::ordered_json(nullptr);
  }
  return j;
}

void print_contacts_table(const Contacts& c, const std::string& backend) {
  fmt::print("detection ({}): bounds built in {:.3f} s\n", backend, c.build_s);
  fmt::print("  {:<6} {:>12} {:>12} {:>12} {:>10}\n", "level", "between", "within", "total", "seconds");
  for (std::size_t l = 0; l < 4; ++l) {
    if (!c.counts[l]) continue;
    const auto& k = *c.counts[l];
    fmt::print("  {:<6} {:>12} {:>12} {:>12} {:>10.3f}\n", kContactLevelNames[l], k.between, k.within,
               k.total(), c.seconds[l]);
  }
}

}  // namespace canopy::cli
