// Validation of the lumped solver through the shipped scenes against the thesis (docs/physics.md
// §5): fixed-base T1 = 0.398 s; Kobe KJMA without walls 16.74 / 18.85 cm; Table 4.3 for six laws.
// The Kobe file available is the NGA-West2 processing (PGA 0.834 g) of the thesis' record
// (0.821 g), so the tolerances are those the comparison supports (docs/validation.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <string>
#include <vector>

#include "app/lumped/ground_motion_scene.h"
#include "app/lumped/lumped_run.h"
#include "app/lumped/lumped_scene.h"
#include "tests/support/files.h"

namespace
{
  using namespace kimp::io;
  using namespace kimp::app;

  /// Peaks of the thesis' Kobe runs: isolation and top displacement 16.74 / 18.85 cm.
  constexpr double thesis_base_no_walls = 0.1674;
  constexpr double thesis_top_no_walls  = 0.1885;
  /// Record processing differs (PGA +1.6 %, different filtering). Measured: unscaled +7.9 % (base)
  /// and +6.5 % (top); scaled by 0.939: -0.1 % and -1.1 % (docs/validation.md).
  constexpr double no_walls_unscaled_tolerance    = 0.10;
  constexpr double no_walls_scaled_base_tolerance = 0.01;
  constexpr double no_walls_scaled_top_tolerance  = 0.03;
  /// Table 4.3 with the record scaled by 0.939, relative to the thesis. Measured ranges over the
  /// six laws: base -0.3...+0.7 %, top -4.1...-0.4 %, drift -24...+6 %, top acceleration -10...-4
  /// %, base acceleration +7...+18 % (docs/validation.md for the reasons).
  constexpr double table_base_tolerance     = 0.02;
  constexpr double table_top_tolerance      = 0.06;
  constexpr double table_drift_tolerance    = 0.30;
  constexpr double table_top_acc_tolerance  = 0.15;
  constexpr double table_base_acc_tolerance = 0.25;
  /// Unscaled record: only the base displacement, held by the walls, stays close (+0.6 %).
  constexpr double table_unscaled_base_tolerance = 0.02;
  /// First impacts "about 8.4 s on one side, then the other side at about 8.8 s".
  constexpr double impact_time_tolerance = 0.1; // s
  /// Permanent indentation of the modified Kelvin-Voigt law: the thesis' 0.687 read as mm, i.e.
  /// 0.0687 cm per wall (measured 0.065 / 0.078 cm); accept a factor of 2 either way.
  constexpr double thesis_indentation_in_m = 0.687e-3;

  std::filesystem::path scene_path(const std::string &name)
  {
    return kimp::testing::source_dir() / "data" / "scenes" / name;
  }

  /// The shipped scene, or nullopt (with the reason) when its record is not available.
  std::optional<LumpedScene> scene_with_record(const std::string &name, std::string &why)
  {
    const LumpedScene scene = load_scene<LumpedScene>(scene_path(name));
    const auto        dir   = scene_records_directory(scene.ground_motion);
    if (!dir)
    {
      why = "no records directory (set KIMP_RECORDS_DIR or provide ../shared/data/records)";
      return std::nullopt;
    }
    if (!std::filesystem::exists(*dir / (scene.ground_motion.record + ".AT2")))
    {
      why = "record " + scene.ground_motion.record + ".AT2 not in " + dir->string();
      return std::nullopt;
    }
    return scene;
  }

  /// Runs every case of the shipped scene `name` on its record (companion runs off unless
  /// `companion`) and hands each case's name and result to `check`; the reason when the record
  /// is not available (nothing run), else "".
  template <class Check>
  std::string run_cases_on_record(const std::string &name, bool companion, Check &&check)
  {
    std::string why;
    const auto  scene = scene_with_record(name, why);
    if (!scene)
      return why;
    const kimp::lumped::GroundMotion motion = load_ground_motion(scene->ground_motion);
    for (const auto &[case_name, resolved_scene] : resolve_cases(*scene))
    {
      LumpedScene resolved           = resolved_scene;
      resolved.integration.companion = resolved.integration.companion && companion;
      check(case_name,
            resolved,
            run_lumped_case(case_name, resolved, motion, scene->ground_motion.scale));
    }
    return "";
  }

  struct Thesis43
  {
    double base, top, drift, top_acc, base_acc;
  };

  const std::map<std::string, Thesis43> &table_4_3()
  {
    static const std::map<std::string, Thesis43> table = {
      {"linear", {0.15615, 0.19368, 0.02631, 25.736, 39.169}},
      {"kelvin_voigt", {0.15462, 0.18832, 0.01899, 21.258, 36.297}},
      {"modified_kelvin_voigt", {0.15555, 0.19424, 0.02519, 22.972, 36.297}},
      {"jankowski", {0.15614, 0.19309, 0.02361, 21.421, 30.321}},
      {"hertzdamp", {0.15688, 0.19225, 0.02358, 22.418, 35.457}},
      {"hysteretic", {0.15750, 0.19201, 0.02291, 21.665, 36.287}}};
    return table;
  }
} // namespace

TEST(LumpedValidation, FixedBaseFourStoreyPeriod)
{
  const LumpedScene scene = load_scene<LumpedScene>(scene_path("fixed_base_4storey.yaml"));
  const auto        result =
    run_lumped_case("modal", scene, kimp::lumped::GroundMotion{0.01, {0.0, 0.0}, "zero"});
  ASSERT_TRUE(result.ok()) << result.status;
  ASSERT_FALSE(result.buildings.empty());
  const double     t1        = result.buildings[0].periods[0];
  constexpr double tolerance = 1.5e-3; // 0.398 s is quoted to 3 digits
  std::printf("fixed-base 4-storey T1 = %.5f s (thesis 0.398 s)\n", t1);
  EXPECT_NEAR(t1, 0.398, 0.398 * tolerance);
}

TEST(LumpedValidation, KobeWithoutWalls)
{
  const auto check =
    [](const std::string &name, const LumpedScene &resolved, const LumpedCaseResult &r)
  {
    ASSERT_TRUE(r.ok()) << r.status;
    const double base = r.response.peak_displacement.front();
    const double top  = r.response.peak_displacement.back();
    std::printf("Kobe no walls, %s (PGA %.4f g): base %.3f cm (thesis 16.74), top %.3f cm "
                "(thesis 18.85); factor to match the base: %.4f\n",
                name.c_str(),
                r.pga / 9.80665,
                100 * base,
                100 * top,
                thesis_base_no_walls / base * resolved.ground_motion.scale);
    const bool   scaled   = name == "scaled";
    const double base_tol = scaled ? no_walls_scaled_base_tolerance : no_walls_unscaled_tolerance;
    const double top_tol  = scaled ? no_walls_scaled_top_tolerance : no_walls_unscaled_tolerance;
    EXPECT_NEAR(base, thesis_base_no_walls, base_tol * thesis_base_no_walls) << name;
    EXPECT_NEAR(top, thesis_top_no_walls, top_tol * thesis_top_no_walls) << name;
    EXPECT_EQ(r.response.n_impacts(), 0u);
  };
  const std::string why = run_cases_on_record("isolated_4storey_no_walls.yaml", true, check);
  if (!why.empty())
    GTEST_SKIP() << why;
}

TEST(LumpedValidation, Table43SixLaws)
{
  std::size_t n_scaled = 0;
  const auto  check =
    [&n_scaled](const std::string &name, const LumpedScene &, const LumpedCaseResult &r)
  {
    ASSERT_TRUE(r.ok()) << r.status;
    const bool        scaled = name.size() > 7 && name.substr(name.size() - 7) == "_scaled";
    const std::string law    = scaled ? name.substr(0, name.size() - 7) : name;
    const Thesis43   &t      = table_4_3().at(law);
    const kimp::lumped::Response &resp = r.response;
    ASSERT_EQ(resp.contacts.size(), 2u);
    const double base = resp.peak_displacement.front(), top = resp.peak_displacement.back();
    const double base_acc = resp.peak_absolute_acceleration.front();
    const double top_acc  = resp.peak_absolute_acceleration.back();
    const double drift    = resp.max_interstorey_drift();
    std::printf("Table 4.3 %-28s base %.3f (%.3f) top %.3f (%.3f) drift %.3f (%.3f) cm; "
                "a_top %.2f (%.2f) a_base %.2f (%.2f) m/s2; impacts %zu; energy error %.1e\n",
                name.c_str(),
                100 * base,
                100 * t.base,
                100 * top,
                100 * t.top,
                100 * drift,
                100 * t.drift,
                top_acc,
                t.top_acc,
                base_acc,
                t.base_acc,
                resp.n_impacts(),
                resp.energy.relative_error);
    for (const auto &c : resp.contacts)
      std::printf("    %-10s first impact %.3f s at %.3f m/s, peak force %.2f MN, permanent "
                  "indentation %.4f cm\n",
                  c.name.c_str(),
                  c.impacts.empty() ? -1.0 : c.impacts.front().time,
                  c.impacts.empty() ? 0.0 : c.impacts.front().velocity,
                  c.peak_force / 1e6,
                  100 * c.permanent_indentation);
    EXPECT_GT(resp.n_impacts(), 0u) << name;
    if (!scaled)
    {
      EXPECT_NEAR(base, t.base, table_unscaled_base_tolerance * t.base) << name;
      return;
    }
    ++n_scaled;
    EXPECT_NEAR(base, t.base, table_base_tolerance * t.base) << name;
    EXPECT_NEAR(top, t.top, table_top_tolerance * t.top) << name;
    EXPECT_NEAR(drift, t.drift, table_drift_tolerance * t.drift) << name;
    EXPECT_NEAR(top_acc, t.top_acc, table_top_acc_tolerance * t.top_acc) << name;
    EXPECT_NEAR(base_acc, t.base_acc, table_base_acc_tolerance * t.base_acc) << name;
    // Both walls are hit, first near 8.4 s, then the other one near 8.8 s.
    std::vector<double> first_impacts;
    for (const auto &c : resp.contacts)
    {
      ASSERT_FALSE(c.impacts.empty()) << name << " " << c.name;
      first_impacts.push_back(c.impacts.front().time);
    }
    std::sort(first_impacts.begin(), first_impacts.end());
    const double first = first_impacts[0], second = first_impacts[1];
    EXPECT_NEAR(first, 8.4, impact_time_tolerance) << name;
    EXPECT_NEAR(second, 8.8, impact_time_tolerance) << name;
    for (const auto &c : resp.contacts)
    {
      if (law == "modified_kelvin_voigt")
      {
        EXPECT_GT(c.permanent_indentation, 0.5 * thesis_indentation_in_m) << c.name;
        EXPECT_LT(c.permanent_indentation, 2.0 * thesis_indentation_in_m) << c.name;
      }
      else
      {
        EXPECT_EQ(c.permanent_indentation, 0.0) << name << ": only law 3 indents";
      }
    }
  };
  const std::string why = run_cases_on_record("table_4_3_kobe_gap15.yaml", false, check);
  if (!why.empty())
    GTEST_SKIP() << why;
  EXPECT_EQ(n_scaled, 6u);
}

TEST(LumpedValidation, NewmarkAgreesWithCentralDifferenceUnderPounding)
{
  // Synthetic motion (no records needed), walls at 4 cm: several impacts. The explicit method at
  // 1e-4 s and the implicit one at 1e-3 s must give the same peak displacements.
  const LumpedScene                scene          = load_scene_text<LumpedScene>("walls:\n"
                                                                                 "  left:\n"
                                                                                 "    gap: \"4 cm\"\n"
                                                                                 "  right:\n"
                                                                                 "    gap: \"4 cm\"\n"
                                                                                 "ground_motion:\n"
                                                                                 "  duration: \"6 s\"\n"
                                                                                 "integration:\n"
                                                                                 "  dt: \"1e-4 s\"\n",
                                                         "pounding.yaml");
  const kimp::lumped::GroundMotion motion         = load_ground_motion(scene.ground_motion);
  LumpedScene                      implicit_scene = scene;
  implicit_scene.integration.method               = IntegrationMethod::newmark;
  implicit_scene.integration.dt                   = "1e-3 s";
  const LumpedCaseResult cdm                      = run_lumped_case("cdm", scene, motion);
  const LumpedCaseResult newmark = run_lumped_case("newmark", implicit_scene, motion);
  ASSERT_TRUE(cdm.ok()) << cdm.status;
  ASSERT_TRUE(newmark.ok()) << newmark.status;
  ASSERT_GT(cdm.response.n_impacts(), 0u);
  constexpr double peak_tolerance = 0.02; // measured: 0.2 % at the base
  for (std::size_t i = 0; i < cdm.response.peak_displacement.size(); ++i)
  {
    const double a = cdm.response.peak_displacement[i];
    const double b = newmark.response.peak_displacement[i];
    std::printf("dof %zu: peak displacement cdm %.4f cm, newmark %.4f cm\n", i, 100 * a, 100 * b);
    EXPECT_NEAR(b, a, peak_tolerance * a) << "dof " << i;
  }
}
