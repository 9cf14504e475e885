// The cost guards of the FEM commands through kimp-fem: a 1 mm contact mesh is refused with its
// estimate and the key to change by `kimp fem`, `kimp mesh`, `kimp study` and their --check, and
// goes ahead with --accept-cost; a 5 km wall is refused as implausible by --check; the default
// study and the shipped FEM scenes pass the limits.
#include <chrono>
#include <csignal>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <sys/types.h>
#include <sys/wait.h>
#include <thread>
#include <vector>

#include "tests/support/files.h"
#include "tests/support/kimp_run.h"
#include "tests/support/messages.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::testing;

  /// The default FEM scene (elastic slab, backfill) meshed at 1 mm, at the contact and elsewhere.
  const char *one_millimetre_scene = "mesh:\n  h_contact: \"1 mm\"\n  h_max: \"1 mm\"\n";

  /// Waits up to `seconds` for `file` to hold `text`; whether it did.
  bool wait_for_text(const fs::path &file, const std::string &text, double seconds)
  {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end)
    {
      if (exists_now(file) && read_text(file).find(text) != std::string::npos)
        return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }
} // namespace

// `kimp fem` with a 1 mm mesh logged its own estimate (~1e7 DoFs, ~40 h), then meshed and took
// 3 GB within a minute. Now it is refused before the output is written, with the estimate
// and the keys to change, by a run and by --check alike; --accept-cost goes ahead (the run is
// stopped once it has started).
TEST(CostGuardsCli, OneMillimetreFemMeshIsRefusedWithTheEstimate)
{
  TempDir dir("e2e_cost_fem");
  dir.write("scene.yaml", one_millimetre_scene);
  for (const std::string &arguments :
       {std::string("fem scene.yaml -o out"), std::string("fem scene.yaml --check")})
  {
    const KimpRun run = run_kimp(arguments, dir.path());
    std::string   line;
    ASSERT_NO_FATAL_FAILURE(one_error_line(run.exit_code, run.err, line)) << arguments;
    EXPECT_EQ(line.rfind("error: kimp fem: estimated cost above the limits (", 0), 0u) << line;
    for (const char *part : {"DoFs in H1.25 > 1e+06",
                             "h > 6 h on one core",
                             "largest H1.25: ",
                             "a coarser mesh.h_contact",
                             "--accept-cost runs it anyway"})
      EXPECT_NE(line.find(part), std::string::npos) << part << "\n" << line;
    EXPECT_TRUE(files_below(dir.path() / "out").empty()) << arguments;
  }

  // --check --accept-cost: valid, with the warning.
  const KimpRun checked = run_kimp("fem scene.yaml --check --accept-cost", dir.path());
  EXPECT_EQ(checked.exit_code, 0) << checked.err;
  EXPECT_NE(checked.out.find("scene.yaml: valid"), std::string::npos) << checked.out;
  EXPECT_NE(checked.err.find("going ahead (--accept-cost)"), std::string::npos) << checked.err;

  // A run with --accept-cost (and a step budget that lets it through) starts: its results file
  // is being written while it meshes; stopped there.
  dir.write("accepted.yaml", std::string(one_millimetre_scene) + "dynamics:\n  max_steps: 1e9\n");
  const fs::path out = dir.path() / "accepted";
  const pid_t pid = start_kimp("fem " + dir.file("accepted.yaml").string() + " -o " + out.string() +
                                 " --accept-cost",
                               dir.path() / "log.txt");
  const bool  started = wait_for_text(dir.path() / "log.txt", "H1.25: estimate ", 60);
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(started) << read_text(dir.path() / "log.txt");
  EXPECT_NE(read_text(dir.path() / "log.txt").find("going ahead (--accept-cost)"),
            std::string::npos)
    << read_text(dir.path() / "log.txt");
}

// `kimp mesh` (DoFs only) and `kimp study` (every FEM case it may run) are guarded the same way;
// the study logs its estimate, which it never did.
TEST(CostGuardsCli, MeshAndStudyAreGuardedAndTheDefaultsPass)
{
  TempDir dir("e2e_cost_mesh_study");
  dir.write("scene.yaml", one_millimetre_scene);
  KimpRun     run = run_kimp("mesh scene.yaml -o out", dir.path());
  std::string line;
  ASSERT_NO_FATAL_FAILURE(one_error_line(run.exit_code, run.err, line));
  EXPECT_EQ(line.rfind("error: kimp mesh: estimated cost above the limits (", 0), 0u) << line;
  EXPECT_EQ(line.find(" h > 6 h"), std::string::npos) << "mesh has no time limit: " << line;

  dir.write("study.yaml",
            "fem:\n  fidelity_h_contact: [\"1 mm\"]\n  mesh:\n    h_contact: \"1 mm\"\n"
            "    h_max: \"1 mm\"\naccuracy_study: false\naccuracy:\n  h_contact: [\"1 mm\"]\n");
  run = run_kimp("study study.yaml --check", dir.path());
  ASSERT_NO_FATAL_FAILURE(one_error_line(run.exit_code, run.err, line));
  EXPECT_EQ(line.rfind("error: kimp study: estimated cost above the limits (", 0), 0u) << line;

  // The default study: estimated, logged and within the limits.
  run = run_kimp("study --check", dir.path());
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("study estimate (FEM): "), std::string::npos) << run.err;
  // Every shipped FEM scene passes too.
  for (const char *scene : {"fem_default.yaml", "fem_inelastic.yaml", "fem_quick.yaml"})
  {
    const KimpRun shipped =
      run_kimp("fem " + (source_dir() / "data/scenes" / scene).string() + " --check", dir.path());
    EXPECT_EQ(shipped.exit_code, 0) << scene << "\n" << shipped.err;
  }
  const KimpRun shipped_study =
    run_kimp("study " + (source_dir() / "data/scenes/wall_height_study.yaml").string() + " --check",
             dir.path());
  EXPECT_EQ(shipped_study.exit_code, 0) << shipped_study.err;
}

// A wall thickness of "5 km" passed --check and started meshing 6 M nodes. It is refused as
// implausible by --check, with the admissible range; so is a 200 m wall.
TEST(CostGuardsCli, FiveKilometreWallIsRefusedByCheck)
{
  TempDir dir("e2e_cost_wall");
  dir.write("scene.yaml", "geometry:\n  wall_thickness: \"5 km\"\n");
  KimpRun     run = run_kimp("fem scene.yaml --check", dir.path());
  std::string line;
  ASSERT_NO_FATAL_FAILURE(one_error_line(run.exit_code, run.err, line));
  EXPECT_EQ(line,
            "error: scene.yaml:2: geometry.wall_thickness = 5000 m: must be in [0.02 m, 5 m] "
            "(outside it implausible for a moat wall)");

  dir.write("tall.yaml", "wall_heights: [\"200 m\"]\n");
  run = run_kimp("mesh tall.yaml --check", dir.path());
  ASSERT_NO_FATAL_FAILURE(one_error_line(run.exit_code, run.err, line));
  EXPECT_EQ(line,
            "error: tall.yaml:1: wall_heights[0] = 200 m: must be in [0.1 m, 20 m] (outside it "
            "implausible for a moat wall)");
}
