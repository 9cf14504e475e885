// `kimp gui [--port P] [--host H] [--open] [--max-runs N]`: the local web interface (scene editor,
// runs, results).
// Parses the command's options and calls kimp::server.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <thread>
#include <unistd.h>

#include "base/logging.h"
#include "cli/commands.h"
#include "io/records.h"

#include "server/server.h"

namespace kimp::cli
{
  void register_gui_command(CLI::App &app)
  {
    struct Options
    {
      server::GuiOptions gui;
      bool               open = false;
      std::string        records_dir;
    };
    // One run per core at a time by default (a 2-core laptop runs 2, the others queue).
    const unsigned cores   = std::max(1u, std::thread::hardware_concurrency());
    auto           options = std::make_shared<Options>();
    CLI::App      *command = app.add_subcommand(
      "gui",
      "local web interface: scene editor, ground motions, runs with progress, interactive results "
           "and animation (serves http://127.0.0.1:PORT/ until Ctrl-C)");
    command->add_option("--port", options->gui.port, "TCP port, 1-65535 (0: any free port)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
    command
      ->add_option("--host",
                   options->gui.host,
                   "interface to listen on; anything but 127.0.0.1 exposes kimp to the network")
      ->capture_default_str();
    command->add_flag("--open", options->open, "open the page in the default browser");
    command
      ->add_option("--runs-dir",
                   options->gui.runs_dir,
                   "directory of the runs (one kimp gui at a time: it is locked; runs a killed "
                   "server left are listed as interrupted)")
      ->capture_default_str();
    command->add_option("--records-dir",
                        options->records_dir,
                        "directory of the PEER records (listed on the page and passed to every "
                        "run; default KIMP_RECORDS_DIR)");
    command
      ->add_option("--max-runs",
                   options->gui.max_runs,
                   "runs at a time; further runs wait in a queue (default: one per core)")
      ->check(CLI::Range(1, 64));
    command->preparse_callback(
      [options, cores](std::size_t)
      {
        *options              = Options{};
        options->gui.max_runs = cores;
      });
    command->callback(
      [options]()
      {
        server::GuiOptions gui = options->gui;
        gui.records_dir =
          io::records_directory(options->records_dir.empty() ?
                                  std::nullopt :
                                  std::optional<std::filesystem::path>(options->records_dir));
        // Runs are child processes of this very executable.
        gui.kimp_executable = std::filesystem::read_symlink("/proc/self/exe");
        server::run_gui(gui,
                        options->open,
                        [](const std::string &url) {
                          std::cout << "kimp gui: open " << url << " (Ctrl-C stops)" << std::endl;
                        });
      });
  }
} // namespace kimp::cli
