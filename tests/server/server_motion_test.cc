// The ground-motion preview of `kimp gui` (POST /api/motion) through real HTTP requests: the
// synthetic motion of a scene and a PEER record of the records directory as the run would read,
// scale and trim them, and the errors of bad scenes and of commands without a ground motion.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/server/server_test_support.h"
#include "tests/support/files.h"
#include "tests/support/kimp_run.h"

namespace
{
  using namespace kimp;
  using kimp::testing::ServerFixture;

  constexpr double standard_gravity = 9.80665;

  /// The largest |a| of a motion's acceleration samples, m/s².
  double peak_of(const nlohmann::json &motion)
  {
    double peak = 0.0;
    for (const auto &a : motion["acceleration"])
      peak = std::max(peak, std::abs(a.get<double>()));
    return peak;
  }

  /// A server whose records directory holds one PEER record: RSN1_TEST_X000.AT2, a 4 s sine of
  /// 0.3 g amplitude and 1 Hz (400 samples at 0.01 s, written to 5 decimals, in g), the
  /// AT2 fixture of the gui process test with a waveform whose samples all differ.
  class RecordsServer : public ServerFixture
  {
  protected:
    void configure(server::GuiOptions &options) override
    {
      std::string at2 = "PEER TEST\nStation, 1/2/2003, 90\nACCELERATION TIME SERIES IN UNITS OF G\n"
                        "NPTS= 400, DT= .0100 SEC\n";
      for (int i = 0; i < 400; ++i)
      {
        char line[32];
        std::snprintf(line, sizeof(line), " %.5f\n", 0.3 * std::sin(2.0 * M_PI * 0.01 * i));
        at2 += line;
      }
      std::filesystem::create_directories(dir_.path() / "records");
      kimp::testing::write_text(dir_.path() / "records" / "RSN1_TEST_X000.AT2", at2);
      options.records_dir = dir_.path() / "records";
    }
    /// POST /api/motion of `scene` for `command`.
    httplib::Result motion(const std::string &scene, const std::string &command = "lumped")
    {
      return post("/api/motion", {{"command", command}, {"scene", scene}});
    }
  };

  TEST_F(RecordsServer, InfoOffersTheMotionPreview)
  {
    const auto info = client_->Get("/api/info");
    ASSERT_TRUE(info);
    EXPECT_EQ(json_of(info)["motion_preview"], true) << info->body;
  }

  TEST_F(RecordsServer, SyntheticMotionHasTheScenesPgaSamplesAndScaling)
  {
    // The default scene: the generator's 20 s at 5 ms, its PGA (0.8 g) met exactly.
    const auto plain = motion("");
    ASSERT_TRUE(plain);
    ASSERT_EQ(plain->status, 200) << plain->body;
    const nlohmann::json m = json_of(plain);
    EXPECT_EQ(m["name"], "synthetic_near_fault");
    EXPECT_EQ(m["dt"].get<double>(), 0.005);
    EXPECT_EQ(m["acceleration"].size(), 4000u);
    EXPECT_NEAR(peak_of(m), 0.8 * standard_gravity, 1e-12 * 0.8 * standard_gravity);
    EXPECT_EQ(m["pga"].get<double>(), peak_of(m));
    EXPECT_NEAR(m["duration"].get<double>(), 20.0, 1e-12);

    // scale_to_pga "0.3 g": the peak is 0.3 g to 1e-12 (relative); the samples are the
    // unscaled ones times 0.3 g / 0.8 g (scaled_to_pga pins the peak, the rest to rounding).
    const auto to_pga = motion("ground_motion:\n  scale_to_pga: \"0.3 g\"\n");
    ASSERT_TRUE(to_pga);
    ASSERT_EQ(to_pga->status, 200) << to_pga->body;
    const nlohmann::json s = json_of(to_pga);
    ASSERT_EQ(s["acceleration"].size(), 4000u);
    EXPECT_NEAR(peak_of(s), 0.3 * standard_gravity, 1e-12 * 0.3 * standard_gravity);
    for (std::size_t i = 0; i < 4000; i += 97)
      EXPECT_NEAR(s["acceleration"][i].get<double>(),
                  m["acceleration"][i].get<double>() * 0.375,
                  1e-12 * standard_gravity)
        << i;

    // The scene's own synthetic section, then scale (after scale_to_pga) and duration: 0.25 g
    // x -2 = 0.5 g; 6 s at 4 ms = 1500 samples (round(duration / dt), within one).
    const auto own = motion("ground_motion:\n  scale: -2\n  duration: \"6 s\"\n  synthetic:\n"
                            "    pga: \"0.25 g\"\n    dt: \"4 ms\"\n    pulse_time: \"3 s\"\n");
    ASSERT_TRUE(own);
    ASSERT_EQ(own->status, 200) << own->body;
    const nlohmann::json o = json_of(own);
    EXPECT_EQ(o["dt"].get<double>(), 0.004);
    EXPECT_NEAR(static_cast<double>(o["acceleration"].size()), 6.0 / 0.004, 1.0);
    EXPECT_NEAR(peak_of(o), 0.5 * standard_gravity, 1e-12 * 0.5 * standard_gravity);
  }

  TEST_F(RecordsServer, ScaledRecordIsTheRecordTimesTheScale)
  {
    const auto raw = client_->Get("/api/records/RSN1_TEST_X000");
    ASSERT_TRUE(raw);
    ASSERT_EQ(raw->status, 200) << raw->body;
    const nlohmann::json r = json_of(raw);
    ASSERT_EQ(r["acceleration"].size(), 400u);
    // Its peak, sample 25 (sin = 1, written 0.30000), in m/s².
    EXPECT_NEAR(r["pga"].get<double>(), 0.3 * standard_gravity, 1e-12 * 0.3 * standard_gravity);

    // A bare record name found in kimp gui's records directory, scaled by 2.5 and trimmed to
    // 3 s: the first 300 samples of GET /api/records, each times 2.5 (one rounding).
    const auto scaled =
      motion("ground_motion:\n  record: RSN1_TEST_X000\n  scale: 2.5\n  duration: \"3 s\"\n");
    ASSERT_TRUE(scaled);
    ASSERT_EQ(scaled->status, 200) << scaled->body;
    const nlohmann::json s = json_of(scaled);
    EXPECT_EQ(s["name"], r["name"]);
    EXPECT_EQ(s["dt"].get<double>(), r["dt"].get<double>());
    ASSERT_EQ(s["acceleration"].size(), 300u);
    for (std::size_t i = 0; i < 300; ++i)
    {
      const double expected = 2.5 * r["acceleration"][i].get<double>();
      EXPECT_NEAR(s["acceleration"][i].get<double>(), expected, 1e-15 * std::abs(expected)) << i;
    }

    // scale_to_pga "0.45 g" of the record: its peak 0.45 g to 1e-12 (relative).
    const auto to_pga = motion("ground_motion:\n  record: RSN1_TEST_X000\n"
                               "  scale_to_pga: \"0.45 g\"\n");
    ASSERT_TRUE(to_pga);
    ASSERT_EQ(to_pga->status, 200) << to_pga->body;
    EXPECT_EQ(json_of(to_pga)["acceleration"].size(), 400u);
    EXPECT_NEAR(peak_of(json_of(to_pga)), 0.45 * standard_gravity, 1e-12 * 0.45 * standard_gravity);

    // A scene naming its own records_dir: found there, as the run finds it (kimp gui's
    // directory is the run's KIMP_RECORDS_DIR, which the scene's key overrides). There the
    // record is 0.1 g throughout.
    std::string constant = "PEER TEST\nStation, 1/2/2003, 90\nACCELERATION TIME SERIES IN UNITS "
                           "OF G\nNPTS= 50, DT= .0200 SEC\n";
    for (int i = 0; i < 50; ++i)
      constant += " 0.10000\n";
    std::filesystem::create_directories(dir_.path() / "own_records");
    kimp::testing::write_text(dir_.path() / "own_records" / "RSN1_TEST_X000.AT2", constant);
    const auto own = motion("ground_motion:\n  record: RSN1_TEST_X000\n  records_dir: '" +
                            (dir_.path() / "own_records").string() + "'\n");
    ASSERT_TRUE(own);
    ASSERT_EQ(own->status, 200) << own->body;
    EXPECT_EQ(json_of(own)["dt"].get<double>(), 0.02);
    EXPECT_EQ(json_of(own)["acceleration"].size(), 50u);
    EXPECT_NEAR(peak_of(json_of(own)), 0.1 * standard_gravity, 1e-12 * standard_gravity);

    // A misspelt name: refused at its key as the run refuses it, with the directory's name.
    const auto missing = motion("building:\n  n_storeys: 3\nground_motion:\n"
                                "  record: RSN1_TEST_X00\n");
    ASSERT_TRUE(missing);
    EXPECT_EQ(missing->status, 400) << missing->body;
    const std::string error = json_of(missing).value("error", "");
    EXPECT_EQ(error.rfind("scene.yaml:4: ground_motion.record = 'RSN1_TEST_X00': ", 0), 0u)
      << error;
    EXPECT_NE(error.find("did you mean 'RSN1_TEST_X000'?"), std::string::npos) << error;
  }

  TEST_F(RecordsServer, BadScenesGetTheMessageOfKimpLumpedCheck)
  {
    const kimp::testing::TempDir check_dir{"motion_check"};
    for (const std::string scene :
         {"building:\n  n_storeys: 3\nground_motion:\n  scale_to_pgaa: \"0.3 g\"\n",
          "ground_motion:\n  synthetic:\n    dt: \"-5 ms\"\n",
          "ground_motion:\n  duration: \"30 s\"\n"})
    {
      const auto r = motion(scene);
      ASSERT_TRUE(r);
      EXPECT_EQ(r->status, 400) << r->body;
      const std::string error = json_of(r).value("error", "");
      // `kimp lumped scene.yaml --check` on the same text: "error: <message>" on stderr.
      kimp::testing::write_text(check_dir.path() / "scene.yaml", scene);
      const kimp::testing::KimpRun check =
        kimp::testing::run_kimp("-q lumped scene.yaml --check", check_dir.path());
      EXPECT_NE(check.exit_code, 0) << check.out;
      std::string printed = check.err;
      if (printed.rfind("error: ", 0) == 0)
        printed.erase(0, 7);
      while (!printed.empty() && printed.back() == '\n')
        printed.pop_back();
      EXPECT_EQ(error, printed) << scene;
      EXPECT_EQ(error.rfind("scene.yaml:", 0), 0u) << error;
    }
  }

  TEST_F(RecordsServer, CommandsWithoutAGroundMotionAreRefusedByName)
  {
    for (const std::string command : {"fem", "collide", "study", "sweep", "rm"})
    {
      const auto r = motion("", command);
      ASSERT_TRUE(r) << command;
      EXPECT_EQ(r->status, 400) << command << ": " << r->body;
      EXPECT_NE(json_of(r).value("error", "").find(command), std::string::npos) << r->body;
    }
    // Without the X-Kimp-Request header, as any other POST: refused.
    const auto plain =
      client_->Post("/api/motion", R"({"command": "lumped", "scene": ""})", "application/json");
    ASSERT_TRUE(plain);
    EXPECT_EQ(plain->status, 403);
  }
} // namespace
