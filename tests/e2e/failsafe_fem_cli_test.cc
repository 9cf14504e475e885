// End-to-end failures of the FEM commands (mesh, fem, study through kimp-fem) that must not damage
// anything: a closed pipe, a SIGTERM while the FEM runs, a full disk while the mesh or the results
// are written, a damaged FEM cache; the FEM cost estimate against the solver and absurd meshes
// refused before meshing.
#include <chrono>
#include <csignal>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/types.h>
#include <sys/wait.h>
#include <thread>
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

  /// data/scenes/fem_quick.yaml: rigid slab, 5 cm at the contact, about a second of FEM.
  const char *fem_quick_scene = "wall_heights: [\"1.25 m\"]\n"
                                "mesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5}\n"
                                "slab: {rigid: true, velocity: \"1.0 m/s\"}\n"
                                "dynamics: {end_time: \"40 ms\", output_interval: \"0.02 ms\"}\n";

  /// A one-height study on the quick FEM scene, without charts or extra studies.
  const char *quick_study = "fem:\n"
                            "  wall_heights: [\"1.0 m\"]\n"
                            "  mesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5}\n"
                            "  slab: {rigid: true}\n"
                            "  dynamics: {end_time: \"40 ms\", output_interval: \"0.02 ms\"}\n"
                            "  fidelity: fixed\n"
                            "  velocities: []\n"
                            "records:\n"
                            "  - record: synthetic\n"
                            "    duration: \"4 s\"\n"
                            "fit:\n"
                            "  separation_fraction: 10\n"
                            "peer_records: false\n"
                            "charts: false\n"
                            "stability_map: false\n"
                            "accuracy_study: false\n";

  /// The quick scene running for about 15 s (3e6 steps): a long end time, no stop at separation.
  const char *fem_long_scene =
    "wall_heights: [\"1.25 m\"]\n"
    "mesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5}\n"
    "slab: {rigid: true, velocity: \"1.0 m/s\"}\n"
    "dynamics: {end_time: \"20 s\", separation_hold_time: \"20 s\", output_interval: \"1 ms\", "
    "max_steps: 1e7}\n"
    "output: {frame_interval: \"0 s\"}\n";

  /// The files below `dir` whose name marks a temporary file or the lock.
  std::vector<std::string> temporaries_below(const fs::path &dir)
  {
    std::vector<std::string> found;
    for (const std::string &file : files_below(dir))
      if (file.find(".tmp-") != std::string::npos || file.find(".kimp.lock") != std::string::npos)
        found.push_back(file);
    return found;
  }

  /// The full-disk tests: the quick FEM scene as scene.yaml in `dir`; they need prlimit
  /// (util-linux) to limit the size of a file.
  class FailsafeFullDisk : public ::testing::Test
  {
  protected:
    void SetUp() override
    {
      KIMP_SKIP_WITHOUT_PROGRAM("prlimit", "util-linux");
      dir.write("scene.yaml", fem_quick_scene);
    }

    const TempDir dir{"e2e_failsafe_full_disk"};
  };
} // namespace

// The FEM commands run in kimp-fem, whose MPI start-up put SIGPIPE back to its default: `kimp fem
// ... | head -1` died with exit 141 and left fem.h5.tmp-<pid>. Now they finish and write
// everything.
TEST(FailsafeCli, ClosedPipeDoesNotStopMeshFemOrStudy)
{
  TempDir dir("e2e_failsafe_pipe_fem");
  dir.write("scene.yaml", fem_quick_scene);
  dir.write("study.yaml", quick_study);
  EXPECT_EQ(run_kimp_into_closed_pipe("mesh scene.yaml -o mesh_out", dir.path()), 0)
    << read_text(dir.path() / "log.txt");
  for (const char *file : {"summary.json", "mesh/H1.25.msh", "mesh/H1.25.vtu"})
    EXPECT_TRUE(fs::exists(dir.path() / "mesh_out" / file)) << file;
  EXPECT_EQ(run_kimp_into_closed_pipe("fem scene.yaml -o fem_out", dir.path()), 0)
    << read_text(dir.path() / "log.txt");
  for (const char *file : {"fem.h5", "summary.json", "fem_histories.csv", "mesh/H1.25.msh"})
    EXPECT_TRUE(fs::exists(dir.path() / "fem_out" / file)) << file;
  EXPECT_EQ(run_kimp_into_closed_pipe("study study.yaml -o study_out", dir.path()), 0)
    << read_text(dir.path() / "log.txt");
  for (const char *file : {"k_table.csv", "summary.json", "report.md", "fem/H1.00.h5"})
    EXPECT_TRUE(fs::exists(dir.path() / "study_out" / file)) << file;
  for (const char *out : {"mesh_out", "fem_out", "study_out"})
    EXPECT_TRUE(temporaries_below(dir.path() / out).empty())
      << out << ": " << temporaries_below(dir.path() / out).front();
}

// SIGTERM (the GUI's cancel) while the FEM runs: the handler removes the temporary results file,
// the mesh this run wrote and the lock, and the process ends by the signal. Before,
// fem.h5.tmp-<pid> and the lock stayed until the next run.
TEST(FailsafeCli, TerminatedFemRunLeavesNoFile)
{
  TempDir dir("e2e_failsafe_term");
  dir.write("long.yaml", fem_long_scene);
  const fs::path out = dir.path() / "out";
  const pid_t    pid = start_kimp("fem " + dir.file("long.yaml").string() + " -o " + out.string(),
                               dir.path() / "log.txt");
  ASSERT_TRUE(wait_for_file(out / "mesh" / "H1.25.msh", 60)) << read_text(dir.path() / "log.txt");
  ASSERT_TRUE(exists_now(out / ("fem.h5.tmp-" + std::to_string(pid))));
  ASSERT_TRUE(exists_now(out / ".kimp.lock"));
  std::this_thread::sleep_for(std::chrono::milliseconds(500)); // into the time loop
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM)
    << "status " << status << "\n"
    << read_text(dir.path() / "log.txt");
  EXPECT_TRUE(files_below(out).empty()) << "left: " << files_below(out).front();
}

// A full disk while `kimp mesh` writes: at 5 kB the mesh file itself cannot be written (gmsh
// reports nothing; the file is checked); at 20 kB the mesh (9.7 kB) and its VTU preview (4 kB) fit
// but the PNG (65 kB) does not, and the mesh and VTU written before are removed again. Before, a
// 0-byte H1.25.msh (and the VTU and an empty PNG) stayed under the final names.
TEST_F(FailsafeFullDisk, MeshLeavesNoFile)
{
  std::string line;
  ASSERT_NO_FATAL_FAILURE(
    one_line_under_file_limit("mesh scene.yaml -o small", dir.path(), 5000, line));
  EXPECT_NE(line.find("could not write the mesh file"), std::string::npos) << line;
  EXPECT_TRUE(files_below(dir.path() / "small").empty())
    << "left: " << files_below(dir.path() / "small").front();

  std::string log;
  EXPECT_EQ(run_kimp_with_file_limit("mesh scene.yaml -o larger", dir.path(), 20000, log), 1)
    << log;
  EXPECT_NE(log.find("failed to draw"), std::string::npos) << log;
  EXPECT_TRUE(files_below(dir.path() / "larger").empty())
    << "left: " << files_below(dir.path() / "larger").front();
}

// `kimp fem` with room for the mesh (9.7 kB) but not for fem.h5 (0.4 MB): the mesh written before
// is removed, so the command leaves nothing (before: mesh/H1.25.msh stayed).
TEST_F(FailsafeFullDisk, FemLeavesNoFile)
{
  std::string line;
  ASSERT_NO_FATAL_FAILURE(
    one_line_under_file_limit("fem scene.yaml -o out", dir.path(), 100000, line));
  expect_results_file_too_large_error(line, dir.path() / "out");
}

namespace
{
  /// The numbers of the log line "<case>: estimate N DoFs, up to S steps of DT s ...".
  struct LoggedEstimate
  {
    double n_dofs = 0.0, n_steps = 0.0, dt = 0.0;
  };

  LoggedEstimate logged_estimate(const std::string &log, const std::string &case_name)
  {
    const std::string marker = case_name + ": estimate ";
    const std::size_t at     = log.find(marker);
    LoggedEstimate    e;
    if (at == std::string::npos)
      return e;
    std::istringstream in(log.substr(at + marker.size()));
    std::string        word;
    in >> e.n_dofs >> word >> word >> word >> e.n_steps >> word >> word >> e.dt;
    return e;
  }
} // namespace

// The FEM estimate logged before meshing against what the solver then did: the DoFs exactly, the
// time step (the solver's stability limit times cfl_safety, from the grid and the penalty) within
// the 3 significant digits of the log line, for a rigid slab (wall face nodes are the slaves)
// and an elastic one (slab front nodes against the wall). Steps: end_time / dt, an upper bound.
TEST(FailsafeCli, FemEstimateMatchesTheSolver)
{
  constexpr double digits = 5e-3; // relative: the log prints 3 significant digits
  for (const bool rigid : {true, false})
  {
    TempDir dir("e2e_failsafe_estimate");
    dir.write("scene.yaml",
              rigid ? fem_quick_scene : replaced(fem_quick_scene, "rigid: true", "rigid: false"));
    const KimpRun run = run_kimp("fem scene.yaml -o out", dir.path());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const LoggedEstimate  e       = logged_estimate(run.err, "H1.25");
    const nlohmann::json  summary = read_json(dir.path() / "out" / "summary.json");
    const nlohmann::json &c       = summary.at("cases").at(0);
    EXPECT_EQ(e.n_dofs, c.at("n_dofs").get<double>()) << "rigid " << rigid << "\n" << run.err;
    EXPECT_NEAR(e.dt, c.at("dt").get<double>(), digits * c.at("dt").get<double>())
      << "rigid " << rigid;
    EXPECT_NEAR(e.n_steps, 0.04 / c.at("dt").get<double>(), digits * e.n_steps)
      << "rigid " << rigid;
    EXPECT_GE(e.n_steps, c.at("n_steps").get<double>()) << "rigid " << rigid;
  }
}

// mesh.h_contact: 1e-6 m is about 1e11 DoFs and 3e8 steps: refused before meshing with the
// estimate and the keys to change, by the cost limits (then the step budget). With both lifted
// (--accept-cost, dynamics.max_steps) the mesher runs out of memory, which is one line too
// (before: "error: H1.25: meshing: std::bad_alloc").
TEST(FailsafeCli, AbsurdFemMeshIsRefusedOrOneLine)
{
  TempDir           dir("e2e_failsafe_fem_budget");
  const std::string scene = replaced(fem_quick_scene, "\"5 cm\"", "\"1e-6 m\"");
  dir.write("scene.yaml", scene);
  const KimpRun run = run_kimp("fem scene.yaml -o out", dir.path());
  std::string   line;
  ASSERT_NO_FATAL_FAILURE(one_error_line(run.exit_code, run.err, line));
  EXPECT_EQ(line.rfind("error: kimp fem: estimated cost above the limits (1e+11 DoFs in H1.25 > "
                       "1e+06, ",
                       0),
            0u)
    << line;
  EXPECT_NE(line.find("largest H1.25: 1e+11 DoFs, up to 2.95e+08 steps of "), std::string::npos)
    << line;
  EXPECT_NE(line.find("--accept-cost runs it anyway"), std::string::npos) << line;
  EXPECT_TRUE(files_below(dir.path() / "out").empty());

  // Accepted (one warning line), the step budget still refuses it.
  const KimpRun accepted = run_kimp("fem scene.yaml -o out --accept-cost", dir.path());
  EXPECT_EQ(accepted.exit_code, 1) << accepted.err;
  std::vector<std::string> lines = non_info_lines(accepted.err);
  ASSERT_EQ(lines.size(), 2u) << accepted.err;
  EXPECT_NE(lines[0].find("going ahead (--accept-cost)"), std::string::npos) << lines[0];
  EXPECT_EQ(lines[1].rfind("error: H1.25: the estimate (1e+11 DoFs, up to 2.95e+08 steps of ", 0),
            0u)
    << lines[1];
  EXPECT_NE(lines[1].find("exceeds the step budget dynamics.max_steps = 1e+06"), std::string::npos)
    << lines[1];

  KIMP_SKIP_WITHOUT_PROGRAM("prlimit", "util-linux");
  dir.write("lifted.yaml", replaced(scene, "dynamics: {", "dynamics: {max_steps: 1e30, "));
  // 8 GB of address space at most, so the allocation fails at once whatever the machine.
  const int exit_code =
    run_command("cd '" + dir.path().string() + "' && prlimit --as=8000000000 " + kimp_executable() +
                  " fem lifted.yaml -o lifted --accept-cost",
                dir.path() / "log.txt");
  const std::string log = read_text(dir.path() / "log.txt");
  EXPECT_EQ(exit_code, 1) << log;
  lines = non_info_lines(log);
  ASSERT_EQ(lines.size(), 2u) << log;
  EXPECT_NE(lines[0].find("going ahead (--accept-cost)"), std::string::npos) << lines[0];
  EXPECT_EQ(lines[1].rfind("error: H1.25: meshing: out of memory: ", 0), 0u) << lines[1];
  EXPECT_TRUE(files_below(dir.path() / "lifted").empty());
}

// A truncated FEM cache file (a copy cut short, a full disk before the writes were atomic) made
// every later `kimp study` into the directory fail; now it is computed again with a warning.
TEST(FailsafeCli, DamagedFemCacheIsComputedAgain)
{
  TempDir dir("e2e_failsafe_cache");
  dir.write("study.yaml", quick_study);
  ASSERT_EQ(run_kimp("study study.yaml -o out", dir.path()).exit_code, 0);
  const fs::path    cache = dir.path() / "out" / "fem" / "H1.00.h5";
  const std::size_t full  = fs::file_size(cache);
  fs::resize_file(cache, full / 3);
  const KimpRun again = run_kimp("study study.yaml -o out", dir.path());
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.err.find("warning: H1.00: FEM cache out/fem/H1.00.h5 is unreadable"),
            std::string::npos)
    << again.err;
  EXPECT_EQ(fs::file_size(cache), full) << "the cache was not written again";
  EXPECT_EQ(again.err.find("FEM result reused"), std::string::npos) << again.err;
}
