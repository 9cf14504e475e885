// `kimp study` with inelastic materials, end to end on a quick scene (coarse rigid-slab FEM, one
// short synthetic record): every height's walled building run hits its yielding wall element
// (no equivalent-k run), and the capacity, peak and residual wall displacement and failure of
// each run are in yielding_wall.csv (with units), study.h5 /yielding_wall (SI) and at the top of
// the report; each element's resistance comes from its height's static pushover where it runs
// (source pushover: the same curve as `kimp fem --pushover`) and from the capacity estimate where
// it fails (source estimate, with the reason; the reinforced wall's pushover falls back from the
// implicit damage update to IMPL-EX and says so); a linear study keeps the equivalent-k runs and
// runs the same building beside them against each height's estimate element (capacity by hand,
// residual displacement, failure, energy balance; labelled as the estimate in every file).
#ifdef KIMP_WITH_FEM

#  include <algorithm>
#  include <cmath>
#  include <filesystem>
#  include <gtest/gtest.h>
#  include <nlohmann/json.hpp>
#  include <string>
#  include <vector>

#  include "base/format.h"
#  include "tests/e2e/fem_scenes.h"
#  include "tests/support/csv.h"
#  include "tests/support/files.h"
#  include "tests/support/hdf5_reader.h"
#  include "tests/support/kimp_run.h"
#  include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::testing;

  /// Reinforced damaged concrete and a Mohr-Coulomb backfill; no velocity axis.
  constexpr const char *inelastic = R"(  velocities: []
  materials:
    concrete:
      model: damage_plasticity
      f_cm: "38 MPa"
      wall_reinforcement: {ratio_y: "0.8 %", ratio_x: "0.2 %"}
    soil:
      model: mohr_coulomb
      preset: medium_dense_sand
      c: "5 kPa"
)";

  constexpr const char *linear = R"(  velocities: []
  materials:
    concrete:
      model: elastic
    soil:
      model: elastic
)";
} // namespace

TEST(StudyYieldingWallCli, InelasticStudyRunsEveryHeightAgainstItsYieldingWall)
{
  const TempDir dir("study_yielding_wall");
  const KimpRun run = run_study(reduced_study(R"(["1.25 m", "2.0 m"])", inelastic), dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.output();
  const std::filesystem::path out = dir.path() / "out";

  // The building runs: one without walls, one yielding-wall run per height, no k law.
  const auto building = read_csv_records(out / "building_response.csv");
  ASSERT_EQ(building.size(), 3u) << read_text(out / "building_response.csv");
  for (const auto &row : building)
    EXPECT_TRUE(row.at("law") == "none" || row.at("law") == "yielding_wall") << row.at("law");

  const auto elements = read_csv_records(out / "yielding_wall_element.csv");
  ASSERT_EQ(elements.size(), 2u);
  // The reinforced wall against its backfill: the implicit damage update stalls at the first
  // cracks, the IMPL-EX one runs to 5 % drift (docs/physics.md §6 "Static pushover"), so each
  // element is its height's pushover: its concave hull, and beside it the equal-energy bilinear
  // ending at the curve's largest force, a capacity other than the estimate's, and the reason
  // names the fallback.
  for (const auto &e : elements)
  {
    EXPECT_EQ(e.at("source"), "pushover") << e.at("source_reason");
    EXPECT_EQ(e.at("source_reason")
                .rfind("IMPL-EX damage update at 0.25 mm steps (the implicit "
                       "update stalled: ",
                       0),
              0u)
      << e.at("source_reason");
    const double cap   = 1e3 * std::stod(e.at("bilinear_capacity_kN_per_m"));
    const double k     = 1e6 * std::stod(e.at("bilinear_stiffness_kN_per_mm_per_m"));
    const double alpha = std::stod(e.at("bilinear_hardening_ratio"));
    const double w_d   = 1e-3 * std::stod(e.at("pushover_displacement_mm"));
    const double f_d   = 1e3 * std::stod(e.at("pushover_force_kN_per_m"));
    EXPECT_GT(alpha, 0.0);
    EXPECT_LT(cap, f_d);
    EXPECT_NEAR((cap + alpha * k * (w_d - cap / k)) / f_d, 1.0, 1e-9);
    EXPECT_NE(e.at("bilinear_capacity_kN_per_m"), e.at("estimate_capacity_kN_per_m"));
    // The element runs on the hull, which ends at the pushover's largest force.
    EXPECT_EQ(e.at("envelope"), "hull");
    EXPECT_NEAR(1e3 * std::stod(e.at("envelope_force_kN_per_m")) / f_d, 1.0, 1e-9);
    // The dashpot is fitted to the height's FEM record (its slab travel), below its bound, the
    // backfill's plane-wave rho c_p H_b.
    EXPECT_NE(e.at("source_reason").find("kN*s/m^2 fitted to the FEM slab's travel"),
              std::string::npos)
      << e.at("source_reason");
    const double c_r   = std::stod(e.at("radiation_damping_kN_s_per_m2"));
    const double bound = 1e-3 * std::stod(e.at("soil_density_kg_per_m3")) *
                         std::stod(e.at("soil_wave_speed_m_per_s")) *
                         std::stod(e.at("loaded_height_m"));
    EXPECT_GE(c_r, 0.0);
    EXPECT_LE(c_r, bound * (1.0 + 1e-6));
  }
  const auto runs = read_csv_records(out / "yielding_wall.csv");
  ASSERT_EQ(runs.size(), 2u) << read_text(out / "yielding_wall.csv");
  for (const auto &r : runs)
  {
    const auto e =
      std::find_if(elements.begin(),
                   elements.end(),
                   [&](const auto &x) { return x.at("wall_height_m") == r.at("wall_height_m"); });
    ASSERT_NE(e, elements.end()) << r.at("wall_height_m");
    EXPECT_EQ(r.at("status"), "ok");
    const double resistance = 1e3 * std::stod(r.at("peak_wall_resistance_kN"));
    const double capacity   = 1e3 * std::stod(r.at("wall_capacity_kN"));
    const double peak       = 1e-2 * std::stod(r.at("peak_wall_displacement_cm"));
    const double residual   = 1e-2 * std::stod(r.at("residual_wall_displacement_cm"));
    // The run's envelope is the pushover curve's concave hull: its capacity the curve's largest
    // force over the wall's width, which the resistance never exceeds.
    const double f_d   = 1e3 * std::stod(e->at("pushover_force_kN_per_m"));
    const double width = std::stod(e->at("width_m"));
    EXPECT_NEAR(capacity / (f_d * width), 1.0, 1e-9);
    EXPECT_LE(resistance, capacity * (1.0 + 1e-9));
    EXPECT_GT(resistance, 0.0);
    EXPECT_GE(residual, 0.0);
    EXPECT_LE(residual, peak);
    EXPECT_TRUE(r.at("failed") == "0" || r.at("failed") == "1");
    EXPECT_LT(std::stod(r.at("energy_error")), 1e-4);
  }

  // study.h5 in SI, a units attribute per column.
  Hdf5Reader h5(out / "study.h5");
  EXPECT_EQ(h5.units("/yielding_wall/runs/residual_wall_displacement"), "m");
  EXPECT_EQ(h5.units("/yielding_wall/runs/wall_capacity"), "N");
  EXPECT_EQ(h5.units("/yielding_wall/element/bilinear_capacity"), "N/m");
  EXPECT_EQ(h5.units("/yielding_wall/element/bilinear_stiffness"), "N/m/m");
  EXPECT_NEAR(h5.doubles("/yielding_wall/element/bilinear_capacity").at(0),
              1e3 * std::stod(elements.at(0).at("bilinear_capacity_kN_per_m")),
              1e-6);
  EXPECT_EQ(h5.dims("/yielding_wall/runs/peak_wall_resistance").at(0), 2u);

  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  ASSERT_TRUE(summary.contains("yielding_wall"));
  EXPECT_EQ(summary["yielding_wall"]["n_runs"], 2);
  EXPECT_EQ(summary["yielding_wall"]["runs"].size(), 2u);
  EXPECT_TRUE(summary["yielding_wall"]["runs"][0]["failed"].is_boolean());
  ASSERT_EQ(summary["yielding_wall"]["elements"].size(), 2u);
  EXPECT_EQ(summary["yielding_wall"]["elements"][0]["source"], "pushover");

  // The answer comes first in the report: the yielding walls before the k table.
  const std::string report = read_text(out / "report.md");
  const auto        walls  = report.find("## Yielding moat walls");
  ASSERT_NE(walls, std::string::npos);
  EXPECT_LT(walls, report.find("## Impact stiffness per wall height"));
  EXPECT_NE(report.find("building runs push a wall past its failure limit"), std::string::npos);
  EXPECT_NE(report.find("| pushover |"), std::string::npos);
  EXPECT_NE(report.find("the implicit update stalled"), std::string::npos);
}

TEST(StudyYieldingWallCli, ElementTakesItsResistanceFromTheHeightsPushover)
{
  // An elastic wall against Mohr-Coulomb sand with the contact interface: the pushover runs, the
  // element runs on its concave hull (the equal-energy bilinear beside it), and its curve is the
  // one `kimp fem --pushover` gives for the same scene on the study's pushover mesh (5 cm, at most
  // 25 cm).
  constexpr const char *materials = R"(  velocities: []
  interface: {model: contact}
  materials:
    concrete: {model: elastic}
    soil: {model: mohr_coulomb, preset: medium_dense_sand}
)";
  const TempDir         dir("study_yielding_wall_pushover");
  const KimpRun         run = run_study(reduced_study(R"(["1.25 m"])", materials), dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.output();
  const std::filesystem::path out      = dir.path() / "out";
  const auto                  elements = read_csv_records(out / "yielding_wall_element.csv");
  ASSERT_EQ(elements.size(), 1u);
  const auto &e = elements.at(0);
  EXPECT_EQ(e.at("source"), "pushover") << e.at("source_reason");
  const double cap   = 1e3 * std::stod(e.at("bilinear_capacity_kN_per_m"));
  const double k     = 1e6 * std::stod(e.at("bilinear_stiffness_kN_per_mm_per_m"));
  const double alpha = std::stod(e.at("bilinear_hardening_ratio"));
  const double w_d   = 1e-3 * std::stod(e.at("pushover_displacement_mm"));
  const double f_d   = 1e3 * std::stod(e.at("pushover_force_kN_per_m"));
  // The equal-energy bilinear (the comparison) ends at the pushover's largest force.
  EXPECT_LE(cap, f_d * (1 + 1e-12));
  EXPECT_NEAR((cap + alpha * k * (w_d - cap / k)) / f_d, 1.0, 1e-9);
  EXPECT_NE(std::stod(e.at("estimate_capacity_kN_per_m")) * 1e3, cap);

  // The element runs on the curve's concave hull: its points are in yielding_wall_envelope.csv,
  // from (0, 0) to the largest force (Δ_d, V_d), concave, and the element's columns are the
  // hull's first slope, last force and where it turns flat.
  EXPECT_EQ(e.at("envelope"), "hull");
  const auto hull = read_csv_records(out / "yielding_wall_envelope.csv");
  ASSERT_GE(hull.size(), 2u);
  EXPECT_EQ(std::to_string(hull.size()), e.at("envelope_points"));
  std::vector<double> hw, hf;
  for (const auto &row : hull)
  {
    EXPECT_EQ(row.at("wall_height_m"), e.at("wall_height_m"));
    EXPECT_EQ(row.at("point"), std::to_string(hw.size()));
    hw.push_back(1e-3 * std::stod(row.at("displacement_mm")));
    hf.push_back(1e3 * std::stod(row.at("force_kN_per_m")));
  }
  EXPECT_EQ(hw.front(), 0.0);
  EXPECT_EQ(hf.front(), 0.0);
  EXPECT_NEAR(hw.back() / w_d, 1.0, 1e-9);
  EXPECT_NEAR(hf.back() / f_d, 1.0, 1e-9);
  for (std::size_t i = 2; i < hw.size(); ++i)
    EXPECT_LE((hf[i] - hf[i - 1]) / (hw[i] - hw[i - 1]),
              (hf[i - 1] - hf[i - 2]) / (hw[i - 1] - hw[i - 2]) * (1 + 1e-9))
      << "point " << i;
  EXPECT_NEAR(1e6 * std::stod(e.at("envelope_stiffness_kN_per_mm_per_m")) / (hf[1] / hw[1]),
              1.0,
              1e-9);
  EXPECT_NEAR(1e3 * std::stod(e.at("envelope_force_kN_per_m")) / f_d, 1.0, 1e-9);
  EXPECT_NEAR(1e-3 * std::stod(e.at("envelope_displacement_mm")) / w_d, 1.0, 1e-9);

  // The same pushover through `kimp fem --pushover`.
  write_text(dir.path() / "pushover.yaml",
             "wall_heights: [\"1.25 m\"]\n"
             "mesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5}\n"
             "slab: {rigid: true}\n"
             "interface: {model: contact}\n"
             "materials:\n"
             "  concrete: {model: elastic}\n"
             "  soil: {model: mohr_coulomb, preset: medium_dense_sand}\n");
  const KimpRun pushover = run_kimp("fem --pushover pushover.yaml -o po", dir.path());
  ASSERT_EQ(pushover.exit_code, 0) << pushover.output();
  const auto summary = read_csv_records(dir.path() / "po" / "pushover_summary.csv");
  ASSERT_EQ(summary.size(), 1u);
  EXPECT_NEAR(f_d / std::stod(summary.at(0).at("capacity_N_per_m")), 1.0, 1e-9);
  EXPECT_NEAR(w_d / std::stod(summary.at(0).at("displacement_at_capacity_m")), 1.0, 1e-9);

  // The pushover's far side is the rollered block whatever the impact's is: the same curve with
  // a viscous-spring far side, and a warning that says so.
  write_text(dir.path() / "pushover_springs.yaml",
             read_text(dir.path() / "pushover.yaml") + "boundary: {far: viscous_spring}\n");
  const KimpRun springs = run_kimp("fem --pushover pushover_springs.yaml -o pos", dir.path());
  ASSERT_EQ(springs.exit_code, 0) << springs.output();
  EXPECT_NE(springs.output().find("held as the rollered block (boundary.far: viscous_spring"),
            std::string::npos)
    << springs.output();
  const auto springs_summary = read_csv_records(dir.path() / "pos" / "pushover_summary.csv");
  ASSERT_EQ(springs_summary.size(), 1u);
  EXPECT_EQ(springs_summary.at(0).at("capacity_N_per_m"), summary.at(0).at("capacity_N_per_m"));

  // study.h5 keeps the curve the element was fitted to.
  Hdf5Reader h5(out / "study.h5");
  const auto force = h5.doubles("/yielding_wall/pushover/H1.25/force");
  EXPECT_EQ(h5.units("/yielding_wall/pushover/H1.25/force"), "N/m");
  EXPECT_EQ(h5.units("/yielding_wall/pushover/H1.25/displacement"), "m");
  ASSERT_FALSE(force.empty());
  EXPECT_NEAR(*std::max_element(force.begin(), force.end()) / f_d, 1.0, 1e-9);
  // ... and the hull the element runs on, in SI.
  EXPECT_EQ(h5.units("/yielding_wall/envelope/H1.25/force"), "N/m");
  EXPECT_EQ(h5.units("/yielding_wall/envelope/H1.25/displacement"), "m");
  const auto h5_hull = h5.doubles("/yielding_wall/envelope/H1.25/displacement");
  ASSERT_EQ(h5_hull.size(), hw.size());
  EXPECT_NEAR(h5_hull.back() / w_d, 1.0, 1e-12);

  // The report and summary.json name the source.
  const auto json = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(json["yielding_wall"]["elements"][0]["source"], "pushover");
  EXPECT_NEAR(json["yielding_wall"]["elements"][0]["capacity"].get<double>() / cap, 1.0, 1e-9);
  const std::string report = read_text(out / "report.md");
  EXPECT_NE(report.find("| pushover | hull of " + std::to_string(hw.size()) + " points: k "),
            std::string::npos)
    << report;
  EXPECT_NE(report.find("bilinear (comparison): F_y (kN/m)"), std::string::npos);
  EXPECT_NE(report.find("[yielding_wall_envelope.csv](yielding_wall_envelope.csv)"),
            std::string::npos);
}

TEST(StudyYieldingWallCli, LinearStudyRunsTheEstimateElementBesideItsSprings)
{
  const TempDir dir("study_yielding_wall_linear");
  const KimpRun run = run_study(reduced_study(R"(["1.25 m"])", linear), dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.output();
  const std::filesystem::path out = dir.path() / "out";
  // The linear route stays: the three laws' runs, read against the capacity estimate; beside
  // them the same building, record and gap against the height's estimate element.
  const auto building = read_csv_records(out / "building_response.csv");
  ASSERT_EQ(building.size(), 5u); // none + three laws + the estimate element
  EXPECT_EQ(building.at(4).at("law"), "yielding_wall");
  for (std::size_t i = 1; i < 4; ++i)
  {
    EXPECT_NE(building.at(i).at("law"), "yielding_wall");
    EXPECT_FALSE(building.at(i).at("peak_force_over_capacity").empty());
  }

  // The capacity by hand, from the default scene's values at H = 1.25 m (plain 0.25 m wall,
  // f_cm 38 MPa; elastic backfill of 1900 kg/m^3 read with phi = 30 deg, c = 0; slab top at the
  // wall top, 0.20 m slab):
  //   f_ctm = 0.3 (38 - 8)^(2/3) = 2.896 MPa, M_p = f_ctm t^2/6 = 30.17 kN m/m;
  //   K_p = (1 + sin 30)/(1 - sin 30) = 3, P_p = K_p gamma H_b^2/2 = 3 x 18.63 x 1.25^2/2
  //   = 43.67 kN/m at H_b/3; h_c = 1.25 - 0.10 = 1.15 m;
  //   (M_p + P_p H_b/3)/h_c = (30.17 + 18.20)/1.15 = 42.06 kN/m, x 27.78 m = 1168 kN.
  const double f_ctm   = 0.3 * std::pow(30.0, 2.0 / 3.0) * 1e6;
  const double m_p     = f_ctm * 0.25 * 0.25 / 6.0;
  const double p_p     = 0.5 * 3.0 * 1900.0 * 9.80665 * 1.25 * 1.25;
  const double by_hand = (m_p + p_p * 1.25 / 3.0) / 1.15;
  EXPECT_NEAR(by_hand, 42.06e3, 0.01e3);

  const auto runs = read_csv_records(out / "yielding_wall.csv");
  ASSERT_EQ(runs.size(), 1u) << read_text(out / "yielding_wall.csv");
  const auto &r = runs.at(0);
  EXPECT_EQ(r.at("record"), building.at(4).at("record"));
  EXPECT_EQ(r.at("source"), "estimate");
  EXPECT_EQ(r.at("status"), "ok");
  const double capacity = 1e3 * std::stod(r.at("wall_capacity_per_metre_kN_per_m"));
  EXPECT_NEAR(capacity / by_hand, 1.0, 1e-5);
  EXPECT_NEAR(1e3 * std::stod(r.at("wall_capacity_kN")) / (by_hand * 27.78), 1.0, 1e-5);
  // Physical: the residual is a permanent set in the push direction, at most the peak; failed
  // exactly when the wall was pushed past 10 % of H, with a time inside the record; the run
  // closes its energy balance with the walls' plastic and radiated work.
  const double peak     = 1e-2 * std::stod(r.at("peak_wall_displacement_cm"));
  const double residual = 1e-2 * std::stod(r.at("residual_wall_displacement_cm"));
  EXPECT_GT(peak, 0.0);
  EXPECT_GE(residual, 0.0);
  EXPECT_LE(residual, peak);
  const bool failed = r.at("failed") == "1";
  EXPECT_EQ(failed, peak > 0.1 * 1.25) << "peak " << peak << " m";
  EXPECT_EQ(r.at("failure_time_s").empty(), !failed);
  if (failed)
  {
    EXPECT_LE(std::stod(r.at("failure_time_s")), 8.0);
  }
  EXPECT_LE(1e3 * std::stod(r.at("peak_wall_resistance_kN")),
            1e3 * std::stod(r.at("wall_capacity_kN")) * (1.0 + 1e-9));
  EXPECT_GT(std::stod(r.at("wall_plastic_work_kJ")), 0.0); // the wall yields
  EXPECT_LE(std::stod(r.at("energy_error")), 1e-4);

  const auto elements = read_csv_records(out / "yielding_wall_element.csv");
  ASSERT_EQ(elements.size(), 1u);
  // The estimate is elastic-perfectly plastic, unloading at its loading stiffness: the wall
  // springs back by F_y/k from its largest push, so residual = max(0, peak - F_y/k).
  const double k_wall = 1e6 * std::stod(elements.at(0).at("bilinear_stiffness_kN_per_mm_per_m"));
  EXPECT_EQ(elements.at(0).at("unloading_stiffness_kN_per_mm_per_m"),
            elements.at(0).at("bilinear_stiffness_kN_per_mm_per_m"));
  EXPECT_NEAR(residual, std::max(0.0, peak - by_hand / k_wall), 1e-6 * peak);
  EXPECT_EQ(elements.at(0).at("source"), "estimate");
  EXPECT_EQ(elements.at(0).at("envelope"), "bilinear");
  EXPECT_EQ(elements.at(0).at("source_reason").rfind("linear study: the estimate element", 0), 0u)
    << elements.at(0).at("source_reason");
  EXPECT_NEAR(1e3 * std::stod(elements.at(0).at("bilinear_capacity_kN_per_m")) / by_hand,
              1.0,
              1e-5);

  // study.h5 in SI with units, the route named; summary.json the same.
  Hdf5Reader h5(out / "study.h5");
  EXPECT_EQ(h5.attribute("/yielding_wall", "route"), "linear");
  EXPECT_EQ(h5.units("/yielding_wall/runs/residual_wall_displacement"), "m");
  EXPECT_EQ(h5.units("/yielding_wall/runs/wall_capacity_per_metre"), "N/m");
  EXPECT_NEAR(h5.doubles("/yielding_wall/runs/wall_capacity_per_metre").at(0) / by_hand,
              1.0,
              1e-12);
  const auto summary = nlohmann::json::parse(read_text(out / "summary.json"));
  ASSERT_TRUE(summary.contains("yielding_wall"));
  EXPECT_EQ(summary["yielding_wall"]["route"], "linear");
  EXPECT_EQ(summary["yielding_wall"]["runs"].size(), 1u);
  EXPECT_EQ(summary["yielding_wall"]["runs"][0]["source"], "estimate");
  EXPECT_NEAR(summary["yielding_wall"]["runs"][0]["wall_capacity_per_metre"].get<double>() /
                by_hand,
              1.0,
              1e-12);
  EXPECT_NEAR(summary["yielding_wall"]["runs"][0]["residual_wall_displacement"].get<double>(),
              residual,
              1e-6 * peak);

  // The report: the estimate's section first, labelled as such, with the capacity by hand and
  // the residual of the CSV; the linear route below it.
  const std::string report = read_text(out / "report.md");
  const auto        walls =
    report.find("## Moat walls as yielding elements (estimate, beside the linear springs)");
  ASSERT_NE(walls, std::string::npos) << report;
  EXPECT_LT(walls, report.find("## Impact stiffness per wall height"));
  EXPECT_EQ(report.find("## Yielding moat walls"), std::string::npos);
  EXPECT_NE(report.find("| 42.06 | 1168 |"), std::string::npos) << report;
  EXPECT_NE(report.find(" | " + kimp::base::sig(residual * 100) + " | "), std::string::npos);
  EXPECT_NE(report.find("linear route"), std::string::npos);
}

#endif
