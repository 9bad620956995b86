#include "tools/detect_options.hpp"

#include <fmt/format.h>
#ifdef CANOPY_HAVE_CUDA
#include "cuda/detect_cuda.hpp"
#include "cuda/device.hpp"
#endif

namespace canopy::cli {

void DetectOptions::add_to(CLI::App& app) {
  app.add_option("--level", level, "Contact level: plant, leaf, organ or exact (default exact)")
      ->check(CLI::IsMember({"plant", "leaf", "organ", "exact"}));
  app.add_option("--clearance", clearance, "Organs closer than this many metres count as a contact (default 0)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--collide", collide,
                 "Organ kinds that take part, comma separated, or all (default leaflet,petiole,rachis,internode,peduncle)");
  app.add_option("--backend", backend, "Detection backend: cpu, cuda or auto (default auto: CUDA when a GPU is present)")
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}));
  app.add_option("--threads", threads, "CPU threads (default: all cores)")->check(CLI::NonNegativeNumber);
}

DetectRequest DetectOptions::request() const {
  DetectRequest r;
  r.level = *parse_contact_level(level);
  r.clearance = static_cast<float>(clearance);
  r.collide = parse_collide_kinds(collide);
  r.threads = threads;
  return r;
}

std::unique_ptr<DetectionBackend> make_backend(const std::string& name, std::string& note) {
  if (name == "cpu") {
    note = "cpu (asked for)";
    return make_cpu_backend();
  }
#ifdef CANOPY_HAVE_CUDA
  const auto report = cuda::query_devices();
  if (!report.devices.empty()) {
    note = fmt::format("cuda on {} ({})", report.devices[0].name, name == "cuda" ? "asked for" : "auto: a GPU is present");
    return cuda::make_cuda_backend(0);
  }
  const std::string why = report.unavailable_reason;
#else
  const std::string why = "this build has no CUDA backend";
#endif
  if (name == "cuda") throw std::invalid_argument(fmt::format("--backend cuda: no usable GPU ({}); use --backend cpu", why));
  note = fmt::format("cpu (auto: no usable GPU: {})", why);
  return make_cpu_backend();
}

nlohmann::ordered_json counts_json(const Contacts& c) {
  nlohmann::ordered_json j;
  for (std::size_t l = 0; l < 4; ++l) {
    const auto& k = c.counts[l];
    j[std::string(kContactLevelNames[l])] =
        k ? nlohmann::ordered_json{{"between", k->between}, {"within", k->within}, {"total", k->total()}} : nlohmann::ordered_json(nullptr);
  }
  return j;
}

void print_contacts_table(const Contacts& c, const std::string& backend) {
  fmt::print("detection ({}): bounds built in {:.3f} s\n", backend, c.build_s);
  fmt::print("  {:<6} {:>12} {:>12} {:>12} {:>10}\n", "level", "between", "within", "total", "seconds");
  for (std::size_t l = 0; l < 4; ++l) {
    if (!c.counts[l]) continue;
    const auto& k = *c.counts[l];
    fmt::print("  {:<6} {:>12} {:>12} {:>12} {:>10.3f}\n", kContactLevelNames[l], k.between, k.within, k.total(), c.seconds[l]);
  }
}

}  // namespace canopy::cli
