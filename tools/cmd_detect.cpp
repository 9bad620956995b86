// canopy detect: detection alone on a stand written by canopy stand (organs.csv + plants.csv).
#include "geometry/atomic_file.hpp"
#include "geometry/clock.hpp"
#include "geometry/export.hpp"
#include "geometry/thread_limit.hpp"
#include "tools/cli_common.hpp"
#include "tools/folder_counts.hpp"
#include "tools/detect_options.hpp"
#include "tools/stand_run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>

namespace canopy::cli {
Command add_detect(CLI::App& root) {
  struct Options {
    std::string dir;
    std::string csv;
    DetectOptions detect;
  };
  auto o = std::make_shared<Options>();
  CLI::App* app = root.add_subcommand(
      "detect", "Detect contacts in a stand folder written by canopy stand and print a table");
  app->add_option("DIR", o->dir, "Stand folder (with organs.csv and plants.csv)")->required();
  app->add_option("--csv", o->csv, "Also write the contacts to this file (contacts.csv columns)");
  o->detect.add_to(*app);
  return {app, [o]() {
            const ThreadLimit thread_limit(o->detect.threads);
            if (!o->csv.empty())
              refuse_stand_file("--csv", o->csv), refuse_file_place("--csv", o->csv, "CSV");
            const auto t0 = std::chrono::steady_clock::now();
            const FolderIdentity before = folder_identity(o->dir, "organs.csv");
            const Stand stand = read_stand(o->dir);
            print_notes(folder_count_notes(o->dir, stand, before));
            const double read_s = seconds_since(t0);
            std::string note;
            auto backend = make_backend(o->detect.backend, note);
            const Contacts c = backend->detect(stand, o->detect.request());
            // The file first: a write that fails (a full disk) leaves nothing on standard output,
            // as every error does.
            if (!o->csv.empty()) {
              AtomicFile f(o->csv);
              write_contacts_csv(stand, c, f);
              f.commit();
            }
            fmt::print("stand: {} plants, {} organs (read in {:.3f} s)\n", stand.plant_count(),
                       stand.organ_count(), read_s);
            print_contacts_table(c, note);
            if (!o->csv.empty()) fmt::print("wrote {}\n", o->csv);
            return 0;
          }};
}

}  // namespace canopy::cli
