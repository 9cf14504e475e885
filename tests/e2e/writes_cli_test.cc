// End-to-end writes that fail outside kimp's own files: a file size limit set as a user sets it
// (`ulimit -f`, SIGXFSZ at its default action), standard output on a full disk (/dev/full) and
// standard output into a pipe whose reader has gone (`--print-defaults | head -1`). Each ends
// with exit 1 and one line (the pipe: quietly, as a Unix filter) and leaves no file, temporary
// file or lock.
#include <csignal>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <vector>

#include "tests/support/files.h"
#include "tests/support/kimp_run.h"
#include "tests/support/messages.h"
#include "tests/support/scene_texts.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::testing;

  /// The commands with an annotated default scene or file (--print-defaults, --print-schema).
  std::vector<std::string> commands_with_defaults()
  {
    std::vector<std::string> commands{"lumped", "collide", "sweep"};
#ifdef KIMP_WITH_FEM
    for (const char *fem_command : {"mesh", "fem", "study"})
      commands.emplace_back(fem_command);
#endif
    return commands;
  }

  /// Every way of printing to stdout without a run: the listings of every command, the help of
  /// the commands without one, the version and the help of kimp.
  std::vector<std::string> printing_commands()
  {
    std::vector<std::string> printing{"--version", "--help"};
    for (const std::string &command : commands_with_defaults())
      for (const char *flag : {" --print-defaults", " --print-schema"})
        printing.push_back(command + flag);
    for (const char *command : {"fit", "export-opensees", "report", "gui"})
      printing.push_back(std::string(command) + " --help");
    return printing;
  }

  /// A small lumped scene (two cases, 6 s): lumped.h5 is about 1.4 MB.
  const std::string small_scene = two_case_walled_scene("0.002 s");

  /// `kimp <command> scene.yaml -o out` in `dir` under a file size limit of `limit_bytes` fails
  /// in one line naming the results file and EFBIG, and leaves nothing in out/.
  void
  expect_results_file_too_large(const fs::path &dir, const std::string &command, long limit_bytes)
  {
    std::string log;
    const int   exit_code =
      run_kimp_under_ulimit(command + " scene.yaml -o out", dir, limit_bytes, log);
    std::string line;
    ASSERT_NO_FATAL_FAILURE(one_error_line(exit_code, log, line));
    expect_results_file_too_large_error(line, dir / "out");
  }
} // namespace

// `ulimit -f` as a user sets it: the write that crosses the limit used to kill kimp by SIGXFSZ
// (exit 153, no message) and leave lumped.h5.tmp-<pid> and the lock. Now it fails with EFBIG
// like a full disk: one line, nothing left.
TEST(WritesCli, LumpedUnderAFileSizeLimitFailsWithOneLine)
{
  KIMP_SKIP_WITHOUT_PROGRAM("prlimit", "util-linux");
  TempDir dir("e2e_writes_ulimit");
  dir.write("scene.yaml", small_scene);
  ASSERT_NO_FATAL_FAILURE(expect_results_file_too_large(dir.path(), "lumped", 60000));
}

#ifdef KIMP_WITH_FEM
// `kimp fem` (kimp-fem, MPI) under `ulimit -f`: the MPI start-up used to fail on its own
// shared-memory files with 15 lines of MPI errors. Now MPI starts, the mesh (9.7 kB) is written
// and the results file (0.4 MB) is refused in one line, and the mesh is removed again.
TEST(WritesCli, FemUnderAFileSizeLimitFailsWithOneLine)
{
  KIMP_SKIP_WITHOUT_PROGRAM("prlimit", "util-linux");
  TempDir dir("e2e_writes_ulimit_fem");
  dir.write("scene.yaml",
            "wall_heights: [\"1.25 m\"]\n"
            "mesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5}\n"
            "slab: {rigid: true, velocity: \"1.0 m/s\"}\n"
            "dynamics: {end_time: \"40 ms\", output_interval: \"0.02 ms\"}\n");
  ASSERT_NO_FATAL_FAILURE(expect_results_file_too_large(dir.path(), "fem", 100000));
}
#endif

// Standard output on a full disk: every listing used to exit 0 with the file cut at the first
// 4 kB (still a valid scene for --check) or empty. Now each exits 1 with one line.
TEST(WritesCli, StdoutOnAFullDiskExitsOneWithOneLine)
{
  if (!fs::exists("/dev/full"))
    GTEST_SKIP() << "no /dev/full";
  TempDir dir("e2e_writes_full_stdout");
  dir.write("scene.yaml", small_scene);
  ASSERT_EQ(run_kimp("lumped scene.yaml -o out", dir.path()).exit_code, 0);
  std::vector<std::string> printing = printing_commands();
  printing.emplace_back("report --json out");
  printing.emplace_back("lumped scene.yaml --check");
  for (const std::string &arguments : printing)
  {
    // In a subshell: run_command()'s own redirection of the output then stays outside.
    const int exit_code = run_command("(cd '" + dir.path().string() + "' && " + kimp_executable() +
                                        " " + arguments + " 2> stderr.txt > /dev/full)",
                                      "/dev/null");
    const std::string err = read_text(dir.path() / "stderr.txt");
    std::string       line;
    ASSERT_NO_FATAL_FAILURE(one_error_line(exit_code, err, line)) << arguments;
    EXPECT_EQ(line, "error: cannot write to standard output: No space left on device") << arguments;
  }
}

// `kimp <command> --print-defaults | head -1`: the first line, nothing on stderr and the exit
// status of a Unix filter (0, or ended by SIGPIPE when head left before the last write). Before,
// mesh, fem and study (kimp-fem: MPI and PETSc) sprayed 5 kB of PETSc errors.
TEST(WritesCli, ListingIntoHeadEndsQuietly)
{
  TempDir dir("e2e_writes_head");
  for (const std::string &arguments : printing_commands())
  {
    const KimpRun full = run_kimp(arguments, dir.path());
    ASSERT_EQ(full.exit_code, 0) << arguments << "\n" << full.err;
    const std::string first_line = full.out.substr(0, full.out.find('\n') + 1);
    const int         status =
      run_command("bash -c \"cd '" + dir.path().string() + "' && " + kimp_executable() + " " +
                    arguments + " 2> stderr.txt | head -1 > head.txt; exit \\${PIPESTATUS[0]}\"",
                  "/dev/null");
    EXPECT_TRUE(status == 0 || status == 128 + SIGPIPE) << arguments << ": status " << status;
    EXPECT_EQ(read_text(dir.path() / "stderr.txt"), "") << arguments;
    EXPECT_EQ(read_text(dir.path() / "head.txt"), first_line) << arguments;
  }
}

// The same into a pipe whose reader has gone before kimp writes (every write fails with EPIPE):
// kimp ends quietly by SIGPIPE, as `cat` or `seq` would. Before, the lean commands exited 0 as if
// everything had been written, and kimp-fem's sprayed PETSc errors.
TEST(WritesCli, ListingIntoAClosedPipeEndsBySigpipeQuietly)
{
  TempDir dir("e2e_writes_closed_pipe");
  for (const std::string &arguments : printing_commands())
  {
    const KimpProcess run = run_kimp_process(arguments, dir.path(), StdoutTo::closed_pipe);
    EXPECT_EQ(run.signal, SIGPIPE) << arguments << ": exit code " << run.exit_code << "\n"
                                   << run.err;
    EXPECT_EQ(run.err, "") << arguments;
  }
}
