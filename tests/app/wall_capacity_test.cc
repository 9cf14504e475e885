// The linear study's wall capacity estimate (app/study/wall_capacity.h) against its closed form,
// written out here: the base hinge of a reinforced section plus the Rankine passive moment, over
// the height of the slab's mid-thickness.
#include <cmath>
#include <gtest/gtest.h>

#include "app/study/study_scene.h"
#include "app/study/wall_capacity.h"

namespace
{
  constexpr double exact = 1e-12; // relative: the same closed form evaluated two ways

  kimp::app::FemScene scene_with(const double ratio_y)
  {
    kimp::app::StudyFemScene scene;
    scene.materials.soil.preset                              = "none";
    scene.materials.soil.density                             = 1800.0;
    scene.materials.soil.friction_angle                      = 30.0;
    scene.materials.soil.cohesion                            = 0.0;
    scene.materials.concrete.f_cm                            = 38e6;
    scene.materials.concrete.wall_reinforcement.ratio_y      = ratio_y;
    scene.materials.concrete.wall_reinforcement.yield_stress = 500e6;
    scene.geometry.wall_thickness                            = 0.25;
    scene.geometry.slab_thickness                            = 0.20;
    scene.geometry.slab_top.reset();
    scene.geometry.backfill_height.reset();
    return scene;
  }
} // namespace

TEST(WallCapacity, ReinforcedHingePlusRankinePassiveOverTheContactHeight)
{
  const auto e = kimp::app::wall_capacity_estimate(scene_with(0.01), 1.25);
  // Tension half of 1 % of a 0.25 m section at d = 0.225 m, a = A_s·f_y/(0.85·f_cm).
  const double a_s = 0.5 * 0.01 * 0.25;
  const double a   = a_s * 500e6 / (0.85 * 38e6);
  const double m_p = a_s * 500e6 * (0.225 - 0.5 * a);
  EXPECT_NEAR(e.plastic_moment, m_p, exact * m_p);
  EXPECT_NEAR(m_p, 134.6e3, 0.1e3); // kN·m/m, by hand
  // φ = 30°: K_p = 3; γ = 1800·g; H_b = H = 1.25 m; resultant at H_b/3.
  const double gamma = 1800.0 * 9.80665;
  const double p_p   = 0.5 * 3.0 * gamma * 1.25 * 1.25;
  EXPECT_NEAR(e.passive_force, p_p, 1e-9 * p_p);
  EXPECT_NEAR(e.passive_moment, p_p * 1.25 / 3.0, 1e-9 * p_p);
  // Slab top at the wall top: h_c = 1.25 − 0.10 m.
  EXPECT_NEAR(e.contact_height, 1.15, exact);
  EXPECT_NEAR(e.per_metre, (m_p + p_p * 1.25 / 3.0) / 1.15, 1e-9 * e.per_metre);
}

TEST(WallCapacity, PlainSectionTakesItsCrackingMoment)
{
  const auto e = kimp::app::wall_capacity_estimate(scene_with(0.0), 2.0);
  // f_ctm of fib MC2010 for f_cm = 38 MPa (f_ck = 30 MPa): 0.3·30^(2/3) = 2.896 MPa.
  const double f_ctm = 0.3 * std::pow(30.0, 2.0 / 3.0) * 1e6;
  EXPECT_NEAR(e.plastic_moment, f_ctm * 0.25 * 0.25 / 6.0, 1e-3 * e.plastic_moment);
  EXPECT_NEAR(e.contact_height, 1.9, exact);
  EXPECT_GT(e.per_metre, 0.0);
}
