// The linear study's wall capacity estimate (app/study/wall_capacity.h) against its closed form,
// written out here: the base hinge of a reinforced section plus the Rankine passive moment, over
// the height of the slab's mid-thickness; the default study's capacity worked by hand, which the
// linear study's estimate element runs on.
#include <cmath>
#include <gtest/gtest.h>

#include "app/study/study_scene.h"
#include "app/study/wall_capacity.h"
#include "app/study/yielding_wall_element.h"

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

TEST(WallCapacity, DefaultStudyByHandIsTheEstimateElementsCapacity)
{
  // The default study (a plain 0.25 m wall, f_cm 38 MPa; an elastic backfill of 1900 kg/m^3 read
  // with phi = 30 deg and c = 0; slab top at the wall top, 0.20 m slab) at H = 1.25 m, by hand:
  //   f_ctm = 0.3 (38 - 8)^(2/3) MPa = 2.896 MPa; M_p = f_ctm t^2/6 = 30.17 kN m/m;
  //   K_p = 3; gamma = 1900 x 9.80665 = 18.63 kN/m^3; P_p = K_p gamma H_b^2/2 = 43.67 kN/m,
  //   its moment P_p H_b/3 = 18.20 kN m/m; h_c = 1.25 - 0.10 = 1.15 m;
  //   (M_p + P_p H_b/3)/h_c = 48.37/1.15 = 42.06 kN/m; over W = 27.78 m: 1168 kN.
  const kimp::app::StudyScene s;
  const auto                  e = kimp::app::wall_capacity_estimate(s.fem, 1.25);
  EXPECT_NEAR(e.plastic_moment, 30.17e3, 0.01e3);
  EXPECT_NEAR(e.passive_force, 43.67e3, 0.01e3);
  EXPECT_NEAR(e.passive_moment, 18.20e3, 0.01e3);
  EXPECT_NEAR(e.contact_height, 1.15, exact);
  EXPECT_NEAR(e.per_metre, 42.06e3, 0.01e3);
  EXPECT_NEAR(e.per_metre * s.fit.width, 1168e3, 1e3);
  // The linear study's estimate element runs on this capacity (its report's "capacity (kN/m)").
  const kimp::app::YieldingWallInputs in =
    kimp::app::yielding_wall_inputs(s.fem, 1.25, s.building.isolation_mass / s.fit.width);
  EXPECT_EQ(in.capacity, e.per_metre);
  const kimp::app::YieldingWallElement element = kimp::app::derive_yielding_wall(in, s.fit.width);
  EXPECT_NEAR(element.backfill.capacity_per_metre(), e.per_metre, exact * e.per_metre);
}
