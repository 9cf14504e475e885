// Input the lean `kimp` refuses before it runs, through the real executable: subnormal values of
// keys typed as text (impact.k, integration.dt) in a scene, a case and a sweep, refused by --check
// as a run would; AT2 and two-column records whose DT is implausible, or that last less than 1 s,
// refused with the file and the value; a 1 MB bad value quoted in at most 100 characters, in a
// scene error and in a command-line error.
#include <cstddef>
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

  /// `kimp <arguments>` in `dir` must exit 1 with one error line (besides info lines) holding
  /// every text of `parts`; nothing is written below `dir`/out.
  void expect_refused(const std::string              &arguments,
                      const TempDir                  &dir,
                      const std::vector<std::string> &parts)
  {
    const KimpRun run = run_kimp(arguments, dir.path());
    std::string   line;
    ASSERT_NO_FATAL_FAILURE(one_error_line(run.exit_code, run.err, line)) << arguments;
    for (const std::string &part : parts)
      EXPECT_NE(line.find(part), std::string::npos) << arguments << "\n" << line;
    EXPECT_TRUE(files_below(dir.path() / "out").empty()) << arguments;
  }

  /// An AT2 file of `npts` samples of 0.01 g at `dt_text` seconds ("1e-7").
  std::string at2(std::size_t npts, const std::string &dt_text)
  {
    std::string text = "PEER TEST\nStation, 1/2/2003, 90\nACCELERATION TIME SERIES IN UNITS OF G\n"
                       "NPTS= " +
                       std::to_string(npts) + ", DT= " + dt_text + " SEC\n";
    for (std::size_t i = 0; i < npts; ++i)
      text += " 0.01\n";
    return text;
  }

  /// The lumped scene of two walled cases, run on `record` instead of the synthetic motion.
  std::string scene_on_record(const std::string &record)
  {
    return replaced(two_case_walled_scene("0.01 s"),
                    "  record: synthetic\n  duration: \"6 s\"\n",
                    "  record: " + record + "\n");
  }

  /// The longest run of `c` in `text`.
  std::size_t longest_run(const std::string &text, char c)
  {
    std::size_t longest = 0, run = 0;
    for (const char x : text)
    {
      run     = x == c ? run + 1 : 0;
      longest = std::max(longest, run);
    }
    return longest;
  }
} // namespace

// impact.k and integration.dt are typed as text ("auto", a unit that depends on the law): they
// skipped the range check. Before, `impact.k: "1e-320 kN/mm"` ran and exited 0 with impacts at
// zero force, and `integration.dt: "1e-320 s"` passed --check and was refused only when run.
TEST(InputGuardsCli, SubnormalTextKeysAreRefusedByCheckInASceneAndACase)
{
  TempDir dir("e2e_guards_subnormal");
  dir.write("k.yaml", "impact:\n  k: \"1e-320 kN/mm\"\n");
  expect_refused("lumped k.yaml --check",
                 dir,
                 {"error: k.yaml:2: impact.k = 1e-320 kN/mm: must be 0 or a normal number"});
  expect_refused("lumped k.yaml -o out",
                 dir,
                 {"error: k.yaml:2: impact.k = 1e-320 kN/mm: must be 0 or a normal number"});

  dir.write("dt.yaml", "integration:\n  dt: \"1e-320 s\"\n");
  expect_refused("lumped dt.yaml --check",
                 dir,
                 {"error: dt.yaml:2: integration.dt = 1e-320 s: must be in [1e-09 s, 1 s]",
                  "implausible"});

  dir.write("case.yaml",
            "cases:\n"
            "  - name: a\n"
            "  - name: b\n"
            "    k: \"1e-320 kN/mm\"\n");
  expect_refused("lumped case.yaml --check",
                 dir,
                 {"error: case.yaml:4: cases[1].k = 1e-320 kN/mm: must be 0 or a normal number"});

  // A bumper's k_b and the collide command's laws share the declaration.
  dir.write("collide.yaml", "laws:\n  - name: a\n    k: \"1e-320 kN/mm\"\n");
  const KimpRun collide = run_kimp("collide collide.yaml --check", dir.path());
  EXPECT_EQ(collide.exit_code, 1) << collide.output();
  EXPECT_NE(collide.err.find("k = 1e-320 kN/mm: must be 0 or a normal number"), std::string::npos)
    << collide.err;
}

// Every swept value is read as the scene it makes, before anything runs: the sweep is refused at
// the line of its parameter with the scene's rule. Before, the 1e-320 kN/mm case ran and the
// sweep exited 0.
TEST(InputGuardsCli, SubnormalSweptValueIsRefusedBeforeRunning)
{
  TempDir dir("e2e_guards_sweep");
  dir.write("base.yaml", two_case_walled_scene("0.01 s"));
  dir.write("sweep.yaml",
            "scene: base.yaml\n"
            "parameters:\n"
            "  impact.k: [\"2500 kN/mm\", \"1e-320 kN/mm\"]\n");
  expect_refused("sweep sweep.yaml -o out --no-charts",
                 dir,
                 {"sweep.yaml:3", "impact.k = 1e-320 kN/mm", "must be 0 or a normal number"});
  EXPECT_FALSE(fs::exists(dir.path() / "out")) << "refused after the output directory was made";
}

// An AT2 header's DT was taken on trust: DT = 1e-7 s made a 0.75 ms record (exit 0, no warning),
// DT = 100 s ran 130 M steps into a 450 MB file. Both are refused with the file and the value,
// so is a record that lasts less than 1 s, and a two-column file whose times step 10 us.
TEST(InputGuardsCli, ImplausibleRecordsAreRefusedWithTheFileAndTheValue)
{
  TempDir dir("e2e_guards_records");
  struct RecordCase
  {
    std::string              name;
    std::size_t              npts;
    std::string              dt_text;
    std::vector<std::string> parts; ///< besides "<name>.yaml:7: ground_motion.record = '"
  };
  const std::vector<RecordCase> records{
    {"fast",
     7500,
     "1e-7",
     {"fast.AT2:4: DT = 1e-07 s", "expected a sampling interval in [0.0001 s, 0.1 s]"}},
    {"slow", 100, ".1000E+03", {"slow.AT2:4: DT = 100 s"}},
    {"short", 50, ".0100", {"short.AT2': lasts 0.5000 s", "expected 1 s to 3600 s"}},
  };
  for (const RecordCase &c : records)
  {
    dir.write(c.name + ".AT2", at2(c.npts, c.dt_text));
    dir.write(c.name + ".yaml", scene_on_record(c.name + ".AT2"));
    std::vector<std::string> parts{c.name + ".yaml:7: ground_motion.record = '"};
    parts.insert(parts.end(), c.parts.begin(), c.parts.end());
    expect_refused("lumped " + c.name + ".yaml -o out", dir, parts);
  }

  std::string two_column = "# t a\n";
  for (int i = 0; i < 200; ++i)
    two_column += std::to_string(i * 1e-5) + " 0.1\n";
  dir.write("fine.txt", two_column);
  dir.write("fine.yaml",
            replaced(scene_on_record("fine.txt"),
                     "  record: fine.txt\n",
                     "  record: fine.txt\n  record_unit: g\n"));
  expect_refused("lumped fine.yaml -o out",
                 dir,
                 {"fine.yaml:7: ground_motion.record = '", "fine.txt:201: time step "});
}

// A bad value of 1 MB was echoed whole in the error. Now at most 80 characters of it are quoted,
// in a scene error (a quantity, a quantity typed as text) and in a command-line error (an argument
// of 100 kB: Linux refuses a single argument above 128 kB).
TEST(InputGuardsCli, HugeBadValueIsQuotedInAtMostOneHundredCharacters)
{
  TempDir           dir("e2e_guards_quote");
  const std::string huge(1 << 20, 'x');
  for (const std::string &key : {std::string("cor"), std::string("k")})
  {
    dir.write("huge.yaml", "impact:\n  " + key + ": \"1 " + huge + "\"\n");
    const KimpRun run = run_kimp("lumped huge.yaml --check", dir.path());
    EXPECT_EQ(run.exit_code, 1) << key;
    EXPECT_LE(longest_run(run.err, 'x'), 100u) << key;
    EXPECT_NE(run.err.find("... (10485"), std::string::npos) << run.err.substr(0, 2000);
    EXPECT_LT(run.err.size(), 2000u) << key << ": " << run.err.substr(0, 2000);
  }
  const KimpRun cli =
    run_kimp("sweep s.yaml -o out --max-steps " + huge.substr(0, 100000), dir.path());
  EXPECT_EQ(cli.exit_code, 2) << cli.err.substr(0, 2000);
  EXPECT_LE(longest_run(cli.err, 'x'), 100u);
  EXPECT_NE(cli.err.find("... (100000 bytes)"), std::string::npos) << cli.err.substr(0, 2000);
}
