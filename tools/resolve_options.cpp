#include "tools/resolve_options.hpp"

#include "tools/resolve_stats.hpp"
#include "tools/stand_options.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace canopy::cli {

void ResolveOptions::add_to(CLI::App& app) {
  const OptionGroup group(app, kResolveGroup);
  app.add_flag("--no-resolve", no_resolve,
               "Export the stand as grown, without turning organs out of contact");
  app.add_option("--max-rounds", max_rounds, "Resolution: detection rounds before giving up (default 30)")
      ->transform(whole_in(1, INT32_MAX));
  app.add_option(
         "--resolve-clearance", clearance,
         "Resolution: metres left between a turned organ and what it met (default 0.0001, at most 100)")
      ->check(kFinite)
      ->check(number_in(0, kMaxClearance))
      ->check(metres_note("--resolve-clearance"));
  app.add_option(
         "--resolve-level", level,
         "Resolution: turn organs until this level finds nothing: exact (default) or organ (OBBs; faster, "
         "turns organs that never touched)")
      ->check(CLI::IsMember({"exact", "organ"}));
  app.add_option("--resolve-candidates", candidates,
                 fmt::format("Resolution: organs per contact that may turn, in policy order (default {})",
                             candidates))
      ->transform(whole_in(1, INT32_MAX));
  app.add_option(
         "--resolve-axes", axis_fan,
         fmt::format(
             "Resolution: axes tried across an organ's width-normal plane besides the away axis (default {})",
             axis_fan))
      ->transform(whole_in(4, 64));
  app.add_option(
         "--resolve-step", scan_step,
         fmt::format("Resolution: degrees between the turns tried before bisection (default {})", scan_step))
      ->check(kFinite)
      ->check(number_in(0.5, 30));
  app.add_option("--bend-joints", bend_joints,
                 fmt::format("Resolution: joints of a petiole, rachis or peduncle chain a turn may be spread "
                             "over, so that it "
                             "bends instead of kinking (default {}; 1: never)",
                             bend_joints))
      ->transform(whole_in(1, 32));
  app.add_option("--bend-step", bend_step,
                 fmt::format("Resolution: degrees per joint a turn is spread to (default {})", bend_step))
      ->check(kFinite)
      ->check(number_in(0.5, 60));
  app.add_flag("--resolve-host-search", host_search,
               "Resolution: on a GPU (--backend cuda, or auto with a GPU), search candidate by candidate on "
               "the host's cores "
               "instead of running each level's attempts on the device in lanes of batches (the same turns; "
               "slower on the "
               "16-core GPU machines)");
  app.add_flag_callback(
      "--resolve-device-search", [this] { host_search = false; },
      "Resolution: each level's attempts on the device on a GPU (--backend cuda or auto; the default there)");
  app.add_option("--resolve-lanes", lanes,
                 fmt::format("Resolution: with the device's attempts, batches of contacts planned at once, "
                             "each on a thread and "
                             "stream of its own (default {}; 1 to 8; the same turns for any number)",
                             lanes))
      ->transform(whole_in(1, 8));
  app.add_flag("--resolve-stats", stats,
               "Resolution: print where its time went on stderr at its end: wall and CPU seconds and page "
               "faults phase by "
               "phase, each lane of planning, and the device's attempts (the same turns; measuring costs a "
               "little time)");
  // What tunes a resolution is refused without one (its values were echoed into report.json and
  // used by no one); --resolve-clearance stays: the compact glb's step follows it.
  CLI::Option* none = app.get_option("--no-resolve");
  for (const char* tuning : {"--max-rounds", "--resolve-level", "--resolve-candidates", "--resolve-axes",
                             "--resolve-step", "--bend-joints", "--bend-step", "--resolve-host-search",
                             "--resolve-device-search", "--resolve-lanes", "--resolve-stats"})
    none->excludes(app.get_option(tuning));
  // Two ways to say where a level's attempts run: one of them.
  app.get_option("--resolve-host-search")->excludes(app.get_option("--resolve-device-search"));
}

ResolveConfig ResolveOptions::config() const {
  ResolveConfig c;
  c.max_rounds = max_rounds;
  c.clearance = clearance;
  c.level = *parse_contact_level(level);
  c.candidates = candidates;
  c.axis_fan = axis_fan;
  c.scan_step_deg = scan_step;
  c.bend_joints = bend_joints;
  c.bend_step_deg = bend_step;
  return c;
}

nlohmann::ordered_json ResolveOptions::config_json() const {
  const ResolveConfig c = config();
  nlohmann::ordered_json order;
  for (std::size_t k = 0; k < 7; ++k)
    if (c.movable[k]) order[std::string(kOrganKindNames[k])] = c.kind_rank[k];
  return {{"enabled", !no_resolve},
          {"level", level},
          {"max_rounds", c.max_rounds},
          {"clearance", c.clearance},
          {"angle_tolerance_deg", c.angle_tolerance_deg},
          {"scan_step_deg", c.scan_step_deg},
          {"candidates", c.candidates},
          {"axis_fan", c.axis_fan},
          {"bend_joints", c.bend_joints},
          {"bend_step_deg", c.bend_step_deg},
          // Asked for: auto, the backend's bulk attempts where it has them (the device's on CUDA), the
          // host search otherwise; "resolution" says what planned.
          {"search", host_search ? "host" : "auto"},
          {"lanes", lanes},
          {"movable_rank", order},
          {"outer_first", c.outer_first}};
}

ResolveResult run_resolution(Stand& stand, DetectionBackend& backend, const DetectRequest& detect,
                             const ResolveOptions& o, const Contacts& initial,
                             std::function<void(const ResolveProgress&)> progress,
                             const ResolvePartition* partition) {
  ResolveRequest req;
  req.partition = partition;
  req.bulk_attempts = !o.host_search;
  req.bulk_lanes = static_cast<std::size_t>(o.lanes);
  req.detect = detect;
  req.config = o.config();
  req.statistics = o.stats;
  const bool tty = !progress && o.progress && isatty(fileno(stderr));
  if (progress) req.progress = std::move(progress);
  else if (tty)
    req.progress = [](const ResolveProgress& p) {
      fmt::print(stderr, "\r  resolving: round {}, {} contacts left, {} still being planned, {:.1f} s   ",
                 p.round, p.contacts, p.unplanned, p.seconds);
      std::fflush(stderr);
    };
  else if (o.progress && o.progress_lines)
    // A log or a pipe: nothing for a short resolution, then a line a round (a large clearance
    // made one run for minutes without a word).
    req.progress = [last = 0](const ResolveProgress& p) mutable {
      if (p.seconds < ResolveOptions::kQuietSeconds || p.round == last) return;
      last = p.round;
      fmt::print(stderr, "  resolving: round {}, {} contacts left, {:.1f} s\n", p.round, p.contacts,
                 p.seconds);
      std::fflush(stderr);
    };
  ResolveResult r = resolve(stand, backend, req, initial);
  if (tty) fmt::print(stderr, "\r{:90}\r", "");
  if (o.stats) fmt::print(stderr, "{}", resolve_stats_text(r.stats));
  return r;
}

nlohmann::ordered_json resolution_json(const ResolveResult& r) {
  nlohmann::ordered_json rounds = nlohmann::ordered_json::array();
  for (const ResolveRound& x : r.per_round)
    rounds.push_back({{"round", x.round},
                      {"contacts", x.contacts},
                      {"turned", x.turned},
                      {"plants_redetected", x.plants_redetected},
                      {"plan_s", x.plan_s},
                      {"detect_s", x.detect_s},
                      {"planning", x.planning}});
  nlohmann::ordered_json left = nlohmann::ordered_json::array();
  for (const UnresolvedContact& u : r.unresolved)
    left.push_back({{"organ_a", u.contact.organ_a},
                    {"organ_b", u.contact.organ_b},
                    {"plant_a", u.contact.plant_a},
                    {"plant_b", u.contact.plant_b},
                    {"reason", u.reason}});
  return {{"ran", true},
          {"iterations", r.rounds},
          {"converged", r.converged},
          {"stop", r.stop},
          {"contacts_before", r.contacts_before},
          {"contacts_after", r.contacts_after},
          {"organs_moved", r.organs_moved},
          {"organs_carried", r.organs_carried},
          {"mean_turn_deg", r.mean_turn_deg},
          {"max_turn_deg", r.max_turn_deg},
          {"max_joint_deg", r.max_joint_deg},
          {"bends", r.bends},
          {"bend_joints", r.bend_joints},
          {"kinks", r.kinks},
          {"unbent", r.unbent},
          {"unresolvable", r.unresolved.size()},
          {"remaining", left},
          {"joint_bytes", r.joint_bytes},
          {"planning", r.planning},
          {"search", r.search},
          {"lanes", r.lanes},
          {"rounds", rounds}};
}

nlohmann::ordered_json resolution_not_run_json(const Contacts& c) {
  ResolveResult none;
  const auto& k = c.counts[static_cast<std::size_t>(c.level)];
  none.contacts_before = none.contacts_after = k ? k->total() : c.pairs.size();
  none.converged = none.contacts_after == 0;
  none.stop = "not run (--no-resolve)";
  nlohmann::ordered_json j = resolution_json(none);
  j["ran"] = false;
  return j;
}

void print_resolution(const ResolveResult& r) {
  fmt::print(
      "resolution: {} -> {} contacts in {} rounds, {:.3f} s; {} organs turned (mean {:.2f} deg, max turn "
      "{:.2f} deg, "
      "largest joint {:.2f} deg), {} organs moved with them; {}\n",
      r.contacts_before, r.contacts_after, r.rounds, r.seconds, r.organs_moved, r.mean_turn_deg,
      r.max_turn_deg, r.max_joint_deg, r.organs_carried, r.stop);
  if (r.bends || r.kinks || r.unbent)
    fmt::print(
        "  {} turns bent over {} joints of their chains, {} left at one joint, {} past a joint's limit that "
        "no bend could take\n",
        r.bends, r.bend_joints, r.kinks, r.unbent);
  fmt::print("  planned with: {}\n", r.planning);
  fmt::print("  {:<6} {:>10} {:>8} {:>8} {:>9} {:>9}\n", "round", "contacts", "turned", "plants", "plan s",
             "detect s");
  for (const ResolveRound& x : r.per_round)
    fmt::print("  {:<6} {:>10} {:>8} {:>8} {:>9.3f} {:>9.3f}\n", x.round, x.contacts, x.turned,
               x.plants_redetected, x.plan_s, x.detect_s);
  const std::size_t show = std::min<std::size_t>(r.unresolved.size(), 10);
  for (std::size_t i = 0; i < show; ++i) {
    const UnresolvedContact& u = r.unresolved[i];
    fmt::print("  unresolved: organs {} and {} (plants {}, {}): {}\n", u.contact.organ_a, u.contact.organ_b,
               u.contact.plant_a, u.contact.plant_b, u.reason);
  }
  if (r.unresolved.size() > show)
    fmt::print("  ... and {} more (report.json lists them all)\n", r.unresolved.size() - show);
}

}  // namespace canopy::cli
