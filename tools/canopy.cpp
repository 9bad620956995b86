// canopy: grow tomato stands from L-system grammars, find and remove organ interpenetration.
#include "lsystem/error.hpp"
#include "tools/cli_common.hpp"
#include "tools/heap_pages.hpp"
#include "tools/process_rerun.hpp"
#include "tools/process_end.hpp"
#include "tools/process_memory.hpp"
#include "tools/signals.hpp"
#include "tools/standard_streams.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#ifdef CANOPY_WITH_MPI
#include "distributed/mpi_comm.hpp"
#endif
#include <new>

int main(int argc, char** argv) {
  canopy::cli::hold_standard_descriptors();
#ifdef CANOPY_WITH_MPI
  const bool under_mpi = canopy::mpi::launched();
#else
  const bool under_mpi = false;
#endif
  // Large heap pages where the run uses the GPU, OpenMP waits asleep for the commands that run
  // parallel work (tools/process_rerun.hpp); not under mpirun (a rank
  // that runs itself again is not what its launcher started; not tried there).
  try {
    if (!under_mpi)
      canopy::rerun_for_run(canopy::heap_pages_for(canopy::command_runs_on_gpu(argc, argv, "auto")),
                            canopy::command_runs_parallel(argc, argv), argv);
  } catch (const std::invalid_argument& e) {  // the environment's settings, read before any option
    fmt::print(stderr, "canopy: error: {}\n", e.what());
    return 2;
  }
  canopy::keep_freed_memory();
  // Before any thread starts: SIGINT and SIGTERM are taken by a thread that cleans up.
  canopy::cli::start_signal_thread();
  canopy::cli::end_on_terminate();
#ifdef CANOPY_WITH_MPI
  // Under mpirun every rank runs the same command; MPI is started only there.
  std::optional<canopy::mpi::Session> mpi;
  if (under_mpi) mpi.emplace();
#endif
  CLI::App app{"canopy: penetration-free plant stands from parametric L-system grammars", "canopy"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(CANOPY_VERSION));
  std::vector<canopy::cli::Command> commands{canopy::cli::add_derive(app), canopy::cli::add_stand(app),
                                             canopy::cli::add_detect(app), canopy::cli::add_sweep(app),
                                             canopy::cli::add_render(app), canopy::cli::add_light(app),
                                             canopy::cli::add_info(app)};
  canopy::cli::one_value_per_use(app);
  canopy::cli::refuse_empty_values(app);
  // "--csv=" is an empty value, but CLI11 takes the next word as the value ("--csv= --threads=1"
  // wrote a file named "--threads=1"): an option of the command given so is passed as the option
  // and an empty word, which refuse_empty_values refuses as it refuses "--csv ''". Other words
  // ending in '=' (an unknown option, the value of the word before) are left to the parser.
  std::vector<std::string> words;
  const CLI::App* command = nullptr;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (!command)
      for (const CLI::App* sub : app.get_subcommands({}))
        if (sub->get_name() == a) command = sub;
    const bool option_without_value = command && a.size() > 3 && a.starts_with("--") &&
                                      a.find('=') == a.size() - 1 &&
                                      command->get_option_no_throw(std::string(a.substr(0, a.size() - 1)));
    if (a == "--") {
      words.insert(words.end(), argv + i, argv + argc);
      break;
    }
    if (option_without_value)
      words.insert(words.end(), {std::string(a.substr(0, a.size() - 1)), std::string()});
    else words.emplace_back(a);
  }
  std::reverse(words.begin(), words.end());  // CLI11 takes the words last first
  try {
    app.parse(words);
  } catch (const CLI::ParseError& e) {
    // --help and --version print and exit 0 as CLI11 does; a bad command line is one line in
    // the form of every other error, with CLI11's exit code.
    if (e.get_exit_code() == 0) return canopy::cli::checked_output(app.exit(e));
    fmt::print(stderr, "{}\n", canopy::cli::parse_error_line(e));
    return e.get_exit_code();
  }
  try {
    for (auto& c : commands)
      if (c.app->parsed()) return canopy::end_process(canopy::cli::checked_output(c.run()), under_mpi);
  } catch (const canopy::GrammarError& e) {
    fmt::print(stderr, "canopy: error: {}\n", e.what());
    return 1;
  } catch (const canopy::ModuleCapError& e) {
    fmt::print(stderr, "canopy: error: {}\n", e.what());
    return 1;
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "canopy: error: {}\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "canopy: error: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "canopy: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
