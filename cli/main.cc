// kimp: impact stiffness for pounding of seismically isolated buildings (command-line entry).
// The lean executable: no deal.II, gmsh or MPI; the FEM commands and MPI jobs are run by
// `kimp-fem`.
#include <cerrno>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <unistd.h>

#include "app/mpi_ranks.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/main_support.h"
#include "io/output_dir.h"

namespace
{
#ifdef KIMP_FEM_EXECUTABLE
  /// The command named on the command line: the first argument that is not an option (the
  /// global options -v, -q, --version and --help take no value), or nullptr.
  const char *command_name(int argc, char **argv)
  {
    for (int i = 1; i < argc; ++i)
      if (argv[i][0] != '-')
        return argv[i];
    return nullptr;
  }

  bool is_fem_command(const char *name)
  {
    for (const kimp::cli::FemCommandInfo &info : kimp::cli::fem_command_infos())
      if (std::strcmp(name, info.name) == 0)
        return true;
    return false;
  }

  /// Replaces this process by the FEM executable beside this one (/proc/self/exe), with the same
  /// arguments and environment: same process id, so `mpirun -np N kimp study` works unchanged.
  /// Returns (exit code 1) only if that fails.
  int exec_fem_executable(char **argv, const char *command)
  {
    std::string   self(4096, '\0');
    const ssize_t n    = readlink("/proc/self/exe", self.data(), self.size() - 1);
    std::string   path = KIMP_FEM_EXECUTABLE;
    if (n > 0)
    {
      self.resize(static_cast<std::size_t>(n));
      path = self.substr(0, self.rfind('/') + 1) + KIMP_FEM_EXECUTABLE;
    }
    execv(path.c_str(), argv);
    std::cerr << "error: kimp " << command << " runs in the FEM executable " << path
              << ", which could not be started (" << std::strerror(errno)
              << "); build the target kimp-fem (KIMP_WITH_FEM=ON) beside kimp" << std::endl;
    return 1;
  }

  /// The FEM commands in --help; choosing one never reaches them (main execs kimp-fem first).
  void register_fem_forwarders(CLI::App &app)
  {
    for (const kimp::cli::FemCommandInfo &info : kimp::cli::fem_command_infos())
      app.add_subcommand(info.name, info.description)->allow_extras();
  }
#endif
} // namespace

int main(int argc, char **argv)
{
  // A closed pipe (`kimp ... | head -1`) must not kill the run before it writes its files; a
  // SIGTERM (the GUI's cancel) or SIGINT removes the run's temporary files and lock. kimp-fem
  // installs them again after MPI's start-up.
  kimp::io::install_signal_handlers();
#ifdef KIMP_FEM_EXECUTABLE
  // An MPI job (`mpirun -np N kimp sweep`) runs in kimp-fem too: this executable has no MPI.
  if (const char *command = command_name(argc, argv);
      (command && is_fem_command(command)) || kimp::app::launched_by_mpi())
    return exec_fem_executable(argv, command ? command : "under MPI");
#endif
  return kimp::cli::end_process(kimp::cli::run_main(argc,
                                                    argv,
                                                    [](CLI::App &app)
                                                    {
#ifdef KIMP_FEM_EXECUTABLE
                                                      register_fem_forwarders(app);
#endif
                                                      kimp::cli::register_commands(app);
                                                    }));
}
