// Fuzz smoke test: seeded mutations of the shipped scenes (data/scenes) and of AT2 files (the
// shared records when found, else a built-in record) fed through the readers and validation the
// CLI uses, in process; then a few dozen whole `kimp lumped` runs on mutated inputs. Every
// outcome must be a value or a clean error naming the file: no other exception, no crash (signal
// exit), no hang (timeout), exit 1 on failure. Deterministic: fixed seeds, fixed counts.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "app/lumped/lumped_scene.h"
#include "io/at2_reader.h"
#include "io/scene_io.h"
#include "tests/support/files.h"
#include "tests/support/kimp_run.h"
#include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using kimp::app::LumpedScene;

  /// In-process mutations per shipped lumped scene and per AT2 file; whole-process runs.
  constexpr int scene_mutations_per_file = 60;
  constexpr int at2_mutations_per_file   = 60;
  constexpr int process_runs             = 24;
  /// A `kimp` run that takes longer is a hang (the runs are refused inputs or 1 s analyses).
  constexpr int process_timeout_s = 30;

  const std::vector<std::string> value_pool = {"1e308 m",
                                               "1e-320 m",
                                               "-5 cm",
                                               ".nan",
                                               "NaN m",
                                               "inf",
                                               "-inf s",
                                               "",
                                               "~",
                                               "[1, 2]",
                                               "{a: 1}",
                                               "'x'",
                                               "1e400",
                                               "0",
                                               "-0",
                                               "10 furlongs",
                                               "5 kg",
                                               "300 g",
                                               "true",
                                               "-1",
                                               "1e-20 cm",
                                               "99999999999999999999",
                                               "\"\"",
                                               "0x10",
                                               "1/0",
                                               "@",
                                               "!!binary AAAA",
                                               "*alias",
                                               "&a 5 cm",
                                               "[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]",
                                               std::string(500, 'x'),
                                               "{a: {b: {c: {d: {e: {f: 1}}}}}}",
                                               "5 cm # comment",
                                               "1e6"};

  const std::vector<std::string> line_pool = {"???",
                                              "\tkey: 1",
                                              ": no key",
                                              "- item",
                                              "unknown_key: 1",
                                              "%YAML 1.2",
                                              "---",
                                              "...",
                                              "a: [1, 2",
                                              "b: {c: 1",
                                              "  deeply:\n    nested:\n      key: 1",
                                              "'unterminated",
                                              "&x y: 1",
                                              "ground_motion: 5",
                                              "integration:\n  duration: -1 s",
                                              "cases: 7",
                                              "\xff\xfe\x01garbage"};

  std::vector<std::string> split_lines(const std::string &text)
  {
    std::vector<std::string> lines;
    std::size_t              begin = 0;
    while (begin <= text.size())
    {
      const std::size_t end = std::min(text.find('\n', begin), text.size());
      lines.push_back(text.substr(begin, end - begin));
      begin = end + 1;
    }
    return lines;
  }

  std::string join_lines(const std::vector<std::string> &lines)
  {
    std::string text;
    for (const std::string &line : lines)
      text += line + "\n";
    return text;
  }

  template <class T>
  const T &pick(std::mt19937 &rng, const std::vector<T> &items)
  {
    return items[std::uniform_int_distribution<std::size_t>(0, items.size() - 1)(rng)];
  }

  std::size_t index(std::mt19937 &rng, std::size_t n)
  {
    return n == 0 ? 0 : std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
  }

  /// `lines` joined, cut at a random length (0 to all of it) and split into lines again.
  std::vector<std::string> cut_at_random(const std::vector<std::string> &lines, std::mt19937 &rng)
  {
    std::string all = join_lines(lines);
    all.resize(index(rng, all.size() + 1));
    return split_lines(all);
  }

  /// One to three mutations of a YAML scene: delete, swap values, replace a value, insert
  /// garbage, duplicate, re-indent, nest deeply, truncate, flip bytes.
  std::string mutate_scene(const std::string &text, std::mt19937 &rng)
  {
    std::vector<std::string> lines = split_lines(text);
    const int                n     = 1 + static_cast<int>(index(rng, 3));
    for (int m = 0; m < n && !lines.empty(); ++m)
    {
      const std::size_t i     = index(rng, lines.size());
      std::string      &line  = lines[i];
      const std::size_t colon = line.find(':');
      switch (index(rng, 9))
      {
        case 0:
          lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(i));
          break;
        case 1:
        {
          std::string &other = lines[index(rng, lines.size())];
          const auto   c2    = other.find(':');
          if (colon != std::string::npos && c2 != std::string::npos)
          {
            const std::string a = line.substr(colon + 1), b = other.substr(c2 + 1);
            line  = line.substr(0, colon + 1) + b;
            other = other.substr(0, c2 + 1) + a;
          }
          break;
        }
        case 2:
          if (colon != std::string::npos)
            line = line.substr(0, colon + 1) + " " + pick(rng, value_pool);
          break;
        case 3:
          lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i), pick(rng, line_pool));
          break;
        case 4:
          lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i), line);
          break;
        case 5:
          line = std::string(index(rng, 7), ' ') + line;
          break;
        case 6:
          if (colon != std::string::npos)
          {
            const std::size_t depth = 1 + index(rng, 3000);
            line = line.substr(0, colon + 1) + " " + std::string(depth, '[') + "1" +
                   std::string(depth, ']');
          }
          break;
        case 7:
          lines = cut_at_random(lines, rng);
          break;
        default:
          if (!line.empty())
            line[index(rng, line.size())] = static_cast<char>(index(rng, 256));
      }
    }
    return join_lines(lines);
  }

  /// One to three mutations of an AT2 text: header units and series, NPTS, DT, values, lines,
  /// truncation, bytes.
  std::string mutate_at2(const std::string &text, std::mt19937 &rng)
  {
    static const std::vector<std::string> headers = {"ACCELERATION TIME SERIES IN UNITS OF CM/S/S",
                                                     "VELOCITY TIME SERIES IN UNITS OF CM/S",
                                                     "DISPLACEMENT TIME SERIES IN UNITS OF CM",
                                                     "ACCELERATION TIME SERIES IN UNITS OF FOO",
                                                     "ACCELERATION TIME SERIES",
                                                     "UNITS OF",
                                                     "ACCELERATION TIME SERIES IN UNITS OF M/S/S",
                                                     ""};
    static const std::vector<std::string> npts_lines = {"NPTS=     0, DT= .0100 SEC",
                                                        "NPTS=    -3, DT= .0100 SEC",
                                                        "NPTS= 99999999999999999999, DT= .01 SEC",
                                                        "NPTS= 1000000000000, DT= .01 SEC",
                                                        "NPTS=     5, DT= 1e-320 SEC",
                                                        "NPTS=     5, DT= nan SEC",
                                                        "NPTS=     5, DT= 1e300 SEC",
                                                        "NPTS=     5, DT= -.01 SEC",
                                                        "NPTS=     5, DT= .01 SEC",
                                                        "5 0.01 NPTS, DT",
                                                        "NPTS DT",
                                                        "NPTS=     5"};
    static const std::vector<std::string> values =
      {"nan", "1e999", "inf", "--1", "1e-320", ".1E-02-.2E-02", "x", "1.0D+00", "+", "1e308 1e308"};
    std::vector<std::string> lines = split_lines(text);
    const int                n     = 1 + static_cast<int>(index(rng, 3));
    for (int m = 0; m < n && !lines.empty(); ++m)
    {
      switch (index(rng, 7))
      {
        case 0:
          if (lines.size() > 2)
            lines[2] = pick(rng, headers);
          break;
        case 1:
          if (lines.size() > 3)
            lines[3] = pick(rng, npts_lines);
          break;
        case 2:
          if (lines.size() > 4)
            lines[4 + index(rng, lines.size() - 4)] += " " + pick(rng, values);
          break;
        case 3:
          lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(index(rng, lines.size())));
          break;
        case 4:
          lines = cut_at_random(lines, rng);
          break;
        case 5:
          lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(index(rng, lines.size())),
                       pick(rng, values));
          break;
        default:
        {
          std::string &line = lines[index(rng, lines.size())];
          if (!line.empty())
            line[index(rng, line.size())] = static_cast<char>(index(rng, 256));
        }
      }
    }
    return join_lines(lines);
  }

  /// The shipped lumped scenes (every data/scenes file that reads as a LumpedScene).
  std::vector<fs::path> lumped_scenes()
  {
    std::vector<fs::path> scenes;
    for (const auto &entry : fs::directory_iterator(kimp::testing::source_dir() / "data/scenes"))
    {
      if (entry.path().extension() != ".yaml")
        continue;
      try
      {
        kimp::io::read_scene<LumpedScene>(entry.path());
        scenes.push_back(entry.path());
      }
      catch (const kimp::io::SceneError &)
      {
        // A scene of another command (fem, study).
      }
    }
    std::sort(scenes.begin(), scenes.end());
    return scenes;
  }

  /// AT2 texts to mutate: the shared records when found (the first 200 lines: enough for every
  /// header and value mutation), plus a small built-in record.
  std::vector<std::string> at2_texts()
  {
    std::vector<std::string> texts = {
      "PEER NGA STRONG MOTION DATABASE RECORD\nKobe Japan, 1/16/1995, KJMA, 0\n"
      "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=    12, DT=   .0200 SEC,\n"
      "  -.1416764E-03  -.1418977E-03  -.1421037E-03  -.1423125E-03  -.1425214E-03\n"
      "   .1735176E-04   .1754978E-04   .1774780E-04  -.1E-02-.2E-02 .3E-02 .4E-02\n"};
    const char *env = std::getenv("KIMP_RECORDS_DIR");
    fs::path    dir = env ? fs::path(env) : kimp::testing::source_dir() / "../shared/data/records";
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
      return texts;
    std::vector<fs::path> files;
    for (const auto &entry : fs::directory_iterator(dir, ec))
      if (entry.path().extension() == ".AT2")
        files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const fs::path &file : files)
    {
      const std::vector<std::string> lines = split_lines(kimp::testing::read_text(file));
      std::vector<std::string>       head(lines.begin(),
                                    lines.begin() + static_cast<std::ptrdiff_t>(
                                                      std::min<std::size_t>(200, lines.size())));
      // Keep NPTS consistent with the values kept, so that most mutants start from a valid file.
      std::size_t n_values = 0;
      for (std::size_t i = 4; i < head.size(); ++i)
      {
        std::istringstream in(head[i]);
        std::string        token;
        while (in >> token)
          ++n_values;
      }
      if (head.size() > 4)
      {
        head[3] = "NPTS= " + std::to_string(n_values) + ", DT= .0100 SEC";
        texts.push_back(join_lines(head));
      }
    }
    return texts;
  }

  TEST(FuzzSmoke, MutatedScenesAreReadOrRefusedNamingTheFile)
  {
    const std::vector<fs::path> scenes = lumped_scenes();
    ASSERT_GE(scenes.size(), 3u) << "shipped lumped scenes not found";
    std::mt19937 rng(20261125);
    int          refused = 0, read = 0;
    for (const fs::path &scene : scenes)
    {
      const std::string text = kimp::testing::read_text(scene);
      for (int m = 0; m < scene_mutations_per_file; ++m)
      {
        const std::string mutant = mutate_scene(text, rng);
        try
        {
          const auto loaded = kimp::io::read_scene_text<LumpedScene>(mutant, "fuzz.yaml");
          // A scene that validates must also resolve its cases.
          try
          {
            kimp::app::resolve_cases(loaded.scene);
          }
          catch (const std::invalid_argument &)
          {
          }
          ++read;
        }
        catch (const kimp::io::SceneError &error)
        {
          ++refused;
          EXPECT_EQ(std::string(error.what()).rfind("fuzz.yaml", 0), 0u)
            << error.what() << "\n--- mutant of " << scene << ":\n"
            << mutant;
        }
        catch (const std::exception &error)
        {
          ADD_FAILURE() << "not a SceneError: " << error.what() << "\n--- mutant of " << scene
                        << ":\n"
                        << mutant;
        }
      }
    }
    // The mutations must exercise both outcomes.
    EXPECT_GT(refused, 50);
    EXPECT_GT(read, 5);
  }

  TEST(FuzzSmoke, MutatedAt2FilesAreReadOrRefusedNamingTheFile)
  {
    std::mt19937 rng(4000);
    int          refused = 0, read = 0;
    for (const std::string &text : at2_texts())
      for (int m = 0; m < at2_mutations_per_file; ++m)
      {
        const std::string mutant = mutate_at2(text, rng);
        try
        {
          const kimp::io::AccelerationRecord r = kimp::io::parse_at2(mutant, "fuzz.AT2");
          ++read;
          EXPECT_TRUE(std::isnormal(r.dt)) << r.dt;
          EXPECT_FALSE(r.acceleration.empty());
          for (const double a : r.acceleration)
            ASSERT_TRUE(std::isfinite(a)) << mutant;
        }
        catch (const kimp::io::GroundMotionFileError &error)
        {
          ++refused;
          EXPECT_EQ(std::string(error.what()).rfind("fuzz.AT2:", 0), 0u) << error.what();
        }
        catch (const std::exception &error)
        {
          ADD_FAILURE() << "not a GroundMotionFileError: " << error.what() << "\n" << mutant;
        }
      }
    EXPECT_GT(refused, 30);
    EXPECT_GT(read, 5);
  }

  TEST(FuzzSmoke, WholeRunsExitCleanlyOnMutatedInputs)
  {
    const std::vector<fs::path> scenes = lumped_scenes();
    ASSERT_FALSE(scenes.empty());
    const std::vector<std::string> records = at2_texts();
    const kimp::testing::TempDir   dir("fuzz");
    std::mt19937                   rng(77);
    int                            runs = 0, attempts = 0;
    while (runs < process_runs && attempts < 100 * process_runs)
    {
      ++attempts;
      // Every other run: a valid 1 s analysis of a mutated AT2 file; else a mutated scene
      // that the reader refuses (a valid mutant could run for minutes).
      const bool        record_run = runs % 2 == 1;
      const std::string name       = "run" + std::to_string(runs);
      std::string       scene_text;
      if (record_run)
      {
        const fs::path at2 =
          dir.write(name + ".AT2", mutate_at2(records[index(rng, records.size())], rng));
        scene_text = "ground_motion:\n  record: " + at2.string() +
                     "\nintegration:\n  duration: 1 s\n  output_interval: 0\n";
      }
      else
      {
        scene_text = mutate_scene(kimp::testing::read_text(scenes[index(rng, scenes.size())]), rng);
        try
        {
          kimp::io::read_scene_text<LumpedScene>(scene_text, "check.yaml");
          continue; // valid: not run
        }
        catch (const std::exception &)
        {
        }
      }
      const fs::path scene = dir.write(name + ".yaml", scene_text);
      const int      code =
        kimp::testing::run_command("cd '" + dir.path().string() + "' && timeout -s KILL " +
                                     std::to_string(process_timeout_s) + " " +
                                     kimp::testing::kimp_executable() + " -q lumped '" +
                                     scene.string() + "' -o '" +
                                     (dir.path() / (name + "_out")).string() + "'",
                                   dir.file(name + ".log"));
      const std::string log = kimp::testing::read_text(dir.file(name + ".log"));
      ++runs;
      SCOPED_TRACE(name + ": exit " + std::to_string(code) + ", log:\n" + log + "\n--- scene:\n" +
                   scene_text);
      // 137: killed by the timeout (a hang); 128 + n: a signal; anything else but 0 or 1: a crash.
      ASSERT_TRUE(code == 0 || code == 1);
      if (code == 1)
      {
        EXPECT_NE(log.find("error: "), std::string::npos);
        // A refused input names the scene; a case that failed (e.g. an implausible response to
        // a mutated record) is reported as such, with the output directory.
        EXPECT_TRUE(log.find(scene.string()) != std::string::npos ||
                    (record_run && log.find("cases failed") != std::string::npos))
          << "the message names the scene";
        EXPECT_EQ(log.find("terminate called"), std::string::npos);
        EXPECT_EQ(log.find("what():"), std::string::npos);
      }
      else
        EXPECT_TRUE(record_run) << "a refused scene ran";
    }
    EXPECT_EQ(runs, process_runs);
  }
} // namespace
