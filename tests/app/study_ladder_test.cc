// The fidelity ladder of `kimp study` (fidelity: auto) on fake FEM levels with a known
// convergence k(h) = k_∞·(1 + a·h^p): stops at the tolerance, reports the level and
// |k − k_previous| as the error, handles non-monotone and failing levels; k_total error.
#ifdef KIMP_WITH_FEM

#  include <cmath>
#  include <gtest/gtest.h>
#  include <map>
#  include <stdexcept>
#  include <string>
#  include <vector>

#  include "app/study/study_ladder.h"

namespace
{
  using kimp::app::FidelityLevel;
  using kimp::app::LevelOutcome;

  constexpr double exact = 1e-12; ///< arithmetic on the fake values only, relative

  /// A fake FEM whose k converges as k_∞·(1 + a·h^p) in h and k_∞·(1 − b/penalty) in the penalty.
  struct FakeFem
  {
    double k_kv = 1.0e11, k_j = 3.0e13, a = 0.0, p = 2.0, b = 0.0;
    int    calls = 0;

    LevelOutcome operator()(const FidelityLevel &level)
    {
      ++calls;
      const double factor =
        (1.0 + a * std::pow(level.h_contact, p)) * (1.0 - b / level.penalty_factor);
      LevelOutcome o;
      o.ok = true;
      // Kelvin-Voigt, then Jankowski's: the Hertz law reacts more (as observed).
      o.k = {k_kv * factor, k_j * factor * factor};
      return o;
    }
  };
} // namespace

TEST(FidelityLadder, StopsAtTheFirstLevelWithinTheToleranceAndReportsTheChange)
{
  // a·h² with a = 4 m⁻²: relative k excess 1 %, 0.25 %, 0.0625 % at h = 5, 2.5, 1.25 cm; the
  // Jankowski k (squared factor) changes by 2·(1 % − 0.25 %) ≈ 1.5 % from 5 to 2.5 cm, so a 1 %
  // tolerance needs the third level; 2 % stops at the second.
  FakeFem fem;
  fem.a                        = 4.0;
  const std::vector<double> hs = {0.05, 0.025, 0.0125};
  const auto loose             = kimp::app::climb_fidelity_ladder(hs, {1.0}, 0.02, std::ref(fem));
  ASSERT_TRUE(loose.has_usable_level());
  EXPECT_EQ(loose.used, 1u) << loose.reason;
  EXPECT_TRUE(loose.converged) << loose.reason;
  EXPECT_EQ(fem.calls, 2);
  const double kv0 = 1e11 * 1.01, kv1 = 1e11 * 1.0025;
  EXPECT_NEAR(loose.mesh_error[0], kv0 - kv1, exact * kv1);
  EXPECT_NEAR(loose.error[0], kv0 - kv1, exact * kv1);
  EXPECT_TRUE(std::isnan(loose.penalty_error[0]));
  EXPECT_NEAR(loose.used_outcome().k[0], kv1, exact * kv1);

  fem.calls        = 0;
  const auto tight = kimp::app::climb_fidelity_ladder(hs, {1.0}, 0.01, std::ref(fem));
  EXPECT_EQ(tight.used, 2u) << tight.reason;
  EXPECT_TRUE(tight.converged) << tight.reason;
  EXPECT_EQ(fem.calls, 3);
  EXPECT_NEAR(tight.used_level().h_contact, 0.0125, exact);
  // The error is the change to the previous level, larger than the true error of the finest.
  const double kj_true_error = tight.used_outcome().k[1] - 3e13;
  EXPECT_GT(tight.error[1], kj_true_error) << "error " << tight.error[1];
}

TEST(FidelityLadder, ExhaustedLadderReportsTheFinestLevelAsNotConverged)
{
  FakeFem fem;
  fem.a = 40.0; // 10 %, 2.5 %, 0.6 %: changes 7.3 % and 1.9 %
  const auto r =
    kimp::app::climb_fidelity_ladder({0.05, 0.025, 0.0125}, {1.0}, 0.01, std::ref(fem));
  EXPECT_EQ(r.used, 2u);
  EXPECT_FALSE(r.converged) << r.reason;
  EXPECT_NE(r.reason.find("exhausted"), std::string::npos) << r.reason;
  const double k1 = 1e11 * (1 + 40 * 0.025 * 0.025), k2 = 1e11 * (1 + 40 * 0.0125 * 0.0125);
  EXPECT_NEAR(r.error[0], k1 - k2, exact * k2);
}

TEST(FidelityLadder, NonMonotoneLevelsUseTheLastDifferenceNotAnExtrapolation)
{
  // k oscillates around the limit: +3 %, −2 %, +0.5 %, −0.4 %. Changes 4.9 %, 2.6 %, 0.9 %.
  const std::vector<double> excess = {0.03, -0.02, 0.005, -0.004};
  const std::vector<double> hs     = {0.08, 0.04, 0.02, 0.01};
  std::map<double, double>  by_h;
  for (std::size_t i = 0; i < hs.size(); ++i)
    by_h[hs[i]] = excess[i];
  int        calls = 0;
  const auto fem   = [&](const FidelityLevel &level)
  {
    ++calls;
    LevelOutcome o;
    o.ok = true;
    o.k  = {2e11 * (1 + by_h.at(level.h_contact)), 5e13 * (1 + by_h.at(level.h_contact))};
    return o;
  };
  const auto r = kimp::app::climb_fidelity_ladder(hs, {1.0}, 0.01, fem);
  EXPECT_EQ(r.used, 3u) << r.reason;
  EXPECT_TRUE(r.converged) << r.reason;
  EXPECT_EQ(calls, 4);
  EXPECT_NEAR(r.error[0], 2e11 * 0.009, exact * 2e11);
  EXPECT_NEAR(r.error[1], 5e13 * 0.009, exact * 5e13);
}

TEST(FidelityLadder, FailingLevelStopsTheClimbAtThePreviousUsableLevel)
{
  FakeFem fem;
  fem.a                     = 40.0;
  const auto failing_finest = [&](const FidelityLevel &level)
  {
    if (level.h_contact < 0.02)
    {
      LevelOutcome o;
      o.status = "failed: implicit Newton did not converge";
      return o;
    }
    return fem(level);
  };
  const auto r =
    kimp::app::climb_fidelity_ladder({0.05, 0.025, 0.0125}, {1.0, 10.0}, 0.01, failing_finest);
  ASSERT_TRUE(r.has_usable_level());
  EXPECT_EQ(r.used, 1u);
  EXPECT_EQ(r.outcomes.size(), 3u) << "the penalty phase must not run after a failed level";
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.reason.find("unusable"), std::string::npos) << r.reason;
  EXPECT_TRUE(std::isfinite(r.error[0]));

  const auto none =
    kimp::app::climb_fidelity_ladder({0.01},
                                     {1.0},
                                     0.01,
                                     [](const FidelityLevel &) { return LevelOutcome{}; });
  EXPECT_FALSE(none.has_usable_level());
}

TEST(FidelityLadder, PenaltyPhaseRunsAtTheConvergedMeshAndAddsItsErrorInQuadrature)
{
  // Mesh converged at the second level (a = 4, tolerance 2 %); penalty 1 -> 10 changes k by
  // 0.3 % · (1 − 1/10) = 0.27 % (KV).
  FakeFem fem;
  fem.a = 4.0;
  fem.b = 0.003;
  const auto r =
    kimp::app::climb_fidelity_ladder({0.05, 0.025, 0.0125}, {1.0, 10.0}, 0.02, std::ref(fem));
  ASSERT_EQ(r.outcomes.size(), 3u) << r.reason;
  EXPECT_EQ(r.used, 2u);
  EXPECT_NEAR(r.used_level().h_contact, 0.025, exact);
  EXPECT_NEAR(r.used_level().penalty_factor, 10.0, exact);
  EXPECT_TRUE(r.converged) << r.reason;
  const double mesh = 1e11 * (1.01 - 1.0025) * (1 - 0.003);
  const double pen  = 1e11 * 1.0025 * (0.003 - 0.0003);
  EXPECT_NEAR(r.mesh_error[0], mesh, 1e-9 * mesh);
  EXPECT_NEAR(r.penalty_error[0], pen, 1e-9 * pen);
  EXPECT_NEAR(r.error[0], std::hypot(mesh, pen), 1e-9 * mesh);
}

TEST(FidelityLadder, SingleLevelIsNotAnErrorEstimate)
{
  FakeFem    fem;
  const auto r = kimp::app::climb_fidelity_ladder({0.025}, {1.0}, 0.01, std::ref(fem));
  EXPECT_EQ(r.used, 0u);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(std::isnan(r.error_of(0)));
  EXPECT_NE(r.reason.find("not estimated"), std::string::npos) << r.reason;
}

TEST(FidelityLadder, RejectsBadLaddersNamingTheKey)
{
  FakeFem fem;
  try
  {
    kimp::app::climb_fidelity_ladder({0.025, 0.05}, {1.0}, 0.01, std::ref(fem));
    FAIL() << "increasing h accepted";
  }
  catch (const std::invalid_argument &e)
  {
    EXPECT_NE(std::string(e.what()).find("fidelity_h_contact[1]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(kimp::app::climb_fidelity_ladder({0.05}, {10.0, 1.0}, 0.01, std::ref(fem)),
               std::invalid_argument);
  EXPECT_THROW(kimp::app::climb_fidelity_ladder({0.05}, {1.0}, 0.0, std::ref(fem)),
               std::invalid_argument);
  EXPECT_THROW(kimp::app::climb_fidelity_ladder({}, {1.0}, 0.01, std::ref(fem)),
               std::invalid_argument);
  EXPECT_EQ(fem.calls, 0);
}

TEST(FidelityLadder, QuantitiesBetweenTheTwoFinestLevelsPassOrFailAgainstFivePercent)
{
  // Quantities converging as q_inf (1 + c h): at h = 2.5 / 1.25 cm with c = 1 /m the change is
  // 0.0125 / 1.0125 = 1.23 % (pass); with c = 4 /m, 4.76 % (pass); c = 5 /m: 5.88 % (fail).
  const auto run = [](const FidelityLevel &level)
  {
    LevelOutcome o;
    o.ok = true;
    o.k  = {1e11 * (1 + level.h_contact), 3e13 * (1 + level.h_contact)}; // tolerance 1 %
    o.quantities["first_peak_force"]             = 1.0e6 * (1 + 1 * level.h_contact);
    o.quantities["energy_equivalent_resistance"] = 1.0e5 * (1 + 4 * level.h_contact);
    o.quantities["max_wall_displacement"]        = 0.01 * (1 + 5 * level.h_contact);
    // Near zero: 3 µm apart, below the 0.01 mm floor.
    o.quantities["wall_residual_displacement"] = 1e-6 + 1.2e-4 * level.h_contact;
    if (level.h_contact < 0.03)
      o.quantities["max_bar_strain_ratio"] = 0.5; // only the finer levels show it
    return o;
  };
  const kimp::app::LadderResult r =
    kimp::app::climb_fidelity_ladder({0.05, 0.025, 0.0125}, {1.0}, 1e-3, run);
  ASSERT_EQ(r.outcomes.size(), 3u);
  std::map<std::string, kimp::app::QuantityError> by_key;
  for (const auto &e : r.quantity_errors)
    by_key[e.key] = e;
  EXPECT_NEAR(by_key.at("first_peak_force").relative, 0.0125 / 1.0125, exact);
  EXPECT_EQ(by_key.at("first_peak_force").verdict, "pass");
  EXPECT_NEAR(by_key.at("energy_equivalent_resistance").relative, 0.05 / 1.05, exact);
  EXPECT_EQ(by_key.at("energy_equivalent_resistance").verdict, "pass");
  EXPECT_NEAR(by_key.at("max_wall_displacement").relative, 0.0625 / 1.0625, exact);
  EXPECT_EQ(by_key.at("max_wall_displacement").verdict, "fail");
  EXPECT_GT(by_key.at("wall_residual_displacement").relative, 0.5);
  EXPECT_EQ(by_key.at("wall_residual_displacement").verdict, "pass") << "below its floor";
  EXPECT_EQ(by_key.at("max_bar_strain_ratio").verdict, "pass") << "both finest levels show it";
  EXPECT_EQ(by_key.count("time_to_stop"), 0u) << "shown by no level: not listed";
  EXPECT_FALSE(r.quantities_converged);
  // The coarse and fine values are those of the two finest levels.
  EXPECT_NEAR(by_key.at("first_peak_force").fine, 1.0e6 * 1.0125, 1e-6);
  EXPECT_NEAR(by_key.at("first_peak_force").coarse, 1.0e6 * 1.025, 1e-6);

  // A quantity one of the two levels lacks is "not shown" and fails.
  LevelOutcome coarse, fine;
  coarse.quantities["time_to_stop"] = 0.02;
  const auto errors                 = kimp::app::quantity_errors(coarse, fine);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].verdict, "not shown");
  EXPECT_FALSE(errors[0].pass);
}

TEST(FidelityLadder, TotalStiffnessErrorPropagatesLinearlyInKAndWidth)
{
  // k_total = k·W: σ = sqrt((W σ_k)² + (k σ_W)²); 3-4-5 triangle.
  EXPECT_NEAR(kimp::app::total_stiffness_error(2.0, 0.3, 10.0, 2.0), 5.0, exact * 5);
  EXPECT_NEAR(kimp::app::total_stiffness_error(90.0, 1.5, 27.78), 1.5 * 27.78, exact * 42);
  EXPECT_NEAR(kimp::app::relative_change(101.0, 100.0), 0.01, exact);
  EXPECT_TRUE(std::isinf(kimp::app::relative_change(1.0, 0.0)));
}

#endif
