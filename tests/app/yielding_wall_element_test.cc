// The yielding wall element of an inelastic study (app/study/yielding_wall_element.h): each
// formula of the derivation against its closed form written out here, the inputs of a scene,
// and a building run against the derived walls closing its energy balance with the walls'
// plastic and radiated work; a slab striking the element against the rigid-plastic closed forms
// (energy and impulse-momentum), and the dashpot fitted back to a slab travel.
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <stdexcept>

#include "app/lumped/lumped_run.h"
#include "app/study/study_scene.h"
#include "app/study/wall_capacity.h"
#include "app/study/yielding_wall_element.h"
#include "app/study/yielding_wall_impact.h"

namespace kimp::app
{
  namespace
  {
    constexpr double exact = 1e-12; // relative: the same closed form evaluated two ways

    YieldingWallInputs inputs()
    {
      YieldingWallInputs in;
      in.capacity            = 120e3;
      in.stiffness           = 20e6;
      in.unloading_stiffness = 30e6;
      in.hardening_ratio     = 0.02;
      in.soil_density        = 1900.0;
      in.soil_wave_speed     = 190.0;
      in.loaded_height       = 1.25;
      in.slab_impedance      = 1.6e6;
      in.wall_impedance      = 2.4e6;
      in.wall_mass           = 750.0;
      in.striker_mass        = 11.5e3;
      in.wall_height         = 1.25;
      return in;
    }

    StudyScene study_scene()
    {
      StudyScene s;
      s.fem.materials.soil.preset                              = "none";
      s.fem.materials.soil.youngs_modulus                      = 50e6;
      s.fem.materials.soil.poisson_ratio                       = 0.3;
      s.fem.materials.soil.density                             = 1900.0;
      s.fem.materials.soil.friction_angle                      = 35.0;
      s.fem.materials.concrete.youngs_modulus                  = 30e9;
      s.fem.materials.concrete.poisson_ratio                   = 0.2;
      s.fem.materials.concrete.density                         = 2400.0;
      s.fem.materials.concrete.wall_reinforcement.ratio_y      = 0.005;
      s.fem.materials.concrete.wall_reinforcement.yield_stress = 500e6;
      s.fem.geometry.wall_thickness                            = 0.25;
      s.fem.geometry.slab_thickness                            = 0.20;
      s.fem.geometry.slab_top.reset();
      s.fem.geometry.backfill_height.reset();
      return s;
    }
  } // namespace

  TEST(YieldingWallElement, DashpotIsTheBackfillImpedanceOverTheLoadedHeight)
  {
    const YieldingWallElement e = derive_yielding_wall(inputs(), 27.78);
    EXPECT_NEAR(e.radiation_damping, 1900.0 * 190.0 * 1.25, exact * e.radiation_damping);
    ASSERT_TRUE(e.backfill.radiation_damping.has_value());
    EXPECT_EQ(*e.backfill.radiation_damping, e.radiation_damping);
    // × W in the engine's parameters.
    EXPECT_NEAR(e.backfill.resolved().radiation_damping,
                27.78 * 1900.0 * 190.0 * 1.25,
                1e-9 * 27.78 * e.radiation_damping);
  }

  TEST(YieldingWallElement, ContactSpringGivesTheSeriesImpedanceAsItsFirstPeak)
  {
    const YieldingWallElement e = derive_yielding_wall(inputs(), 27.78);
    const double              z = 1.0 / (1.0 / 1.6e6 + 1.0 / 2.4e6); // 0.96 MN·s/m per m
    EXPECT_NEAR(e.contact_impedance, 0.96e6, 1e-9 * z);
    const double m_red = 750.0 * 11.5e3 / (750.0 + 11.5e3);
    EXPECT_NEAR(e.reduced_mass, m_red, exact * m_red);
    EXPECT_NEAR(e.contact_stiffness, z * z / m_red, exact * e.contact_stiffness);
    // The closed form the spring is chosen for: a spring k between two masses closing at v has
    // the peak force v·√(k·m_red), here Z_c·v.
    EXPECT_NEAR(std::sqrt(e.contact_stiffness * e.reduced_mass), z, 1e-9 * z);
  }

  TEST(YieldingWallElement, WallAndBackfillPartIsTheCappedCrackedWall)
  {
    const YieldingWallElement        e = derive_yielding_wall(inputs(), 10.0);
    const lumped::WallBackfillParams p = e.backfill.resolved();
    EXPECT_EQ(p.envelope, lumped::WallEnvelope::bilinear);
    EXPECT_NEAR(p.capacity, 10.0 * 120e3, exact * p.capacity);
    EXPECT_NEAR(p.stiffness, 10.0 * 20e6, exact * p.stiffness);
    EXPECT_NEAR(p.unloading_stiffness, 10.0 * 30e6, exact * p.unloading_stiffness);
    EXPECT_EQ(p.hardening_ratio, 0.02);
    EXPECT_NEAR(p.tension_capacity, p.capacity, exact * p.capacity); // the spring-back
    EXPECT_NEAR(p.failure_displacement, 0.125, exact);               // 10 % of H
  }

  TEST(YieldingWallElement, PushoverHullBecomesTheCurveEnvelope)
  {
    // With an envelope curve (a pushover's concave hull) the part's envelope is that curve × W,
    // its capacity the last force, its k the first slope; the pull-back stays the capacity F_y
    // of the inputs, k_ur the inputs'.
    YieldingWallInputs in        = inputs();
    in.envelope_displacements    = {0.0, 2e-3, 10e-3};
    in.envelope_forces           = {0.0, 100e3, 140e3};
    const YieldingWallElement  e = derive_yielding_wall(in, 10.0);
    lumped::WallBackfillParams p = e.backfill.resolved();
    p.mass                       = e.wall_mass * 10.0; // the model's
    EXPECT_EQ(p.envelope, lumped::WallEnvelope::curve);
    ASSERT_EQ(p.curve_forces.size(), 3u);
    EXPECT_NEAR(p.curve_forces[2], 10.0 * 140e3, exact * 1.4e6);
    EXPECT_EQ(p.curve_displacements[1], 2e-3);
    EXPECT_NEAR(e.backfill.capacity_per_metre(), 140e3, exact * 140e3);
    EXPECT_NEAR(p.tension_capacity, 10.0 * 120e3, exact * 1.2e6);
    EXPECT_NEAR(p.unloading_stiffness, 10.0 * 30e6, exact * 3e8);
    const lumped::WallBackfillLaw law(p); // a valid curve for the law: k = 50 kN/mm/m × W
    EXPECT_NEAR(law.parameters().stiffness, 10.0 * 50e6, exact * 5e8);
    EXPECT_NEAR(law.parameters().capacity, 1.4e6, exact * 1.4e6);
  }

  TEST(YieldingWallElement, RefusesAnInputThatIsNotPositiveAndNamesIt)
  {
    YieldingWallInputs in = inputs();
    in.soil_wave_speed    = 0.0;
    try
    {
      derive_yielding_wall(in, 27.78);
      FAIL() << "accepted a zero wave speed";
    }
    catch (const std::invalid_argument &error)
    {
      EXPECT_NE(std::string(error.what()).find("soil_wave_speed"), std::string::npos);
    }
    in                     = inputs();
    in.unloading_stiffness = 0.0;
    EXPECT_THROW(derive_yielding_wall(in, 27.78), std::invalid_argument);
    // Softer than the loading (a cracked wall springing back) is the element's k_ur as given.
    in.unloading_stiffness = 0.5 * in.stiffness;
    EXPECT_EQ(derive_yielding_wall(in, 27.78).backfill.unloading_stiffness, 0.5 * in.stiffness);
  }

  TEST(YieldingWallElement, SceneInputsAreTheCapacityEstimateCrackedCantileverAndImpedances)
  {
    const StudyScene         s  = study_scene();
    const YieldingWallInputs in = yielding_wall_inputs(s.fem, 1.25, 20e3);
    // Capacity: the linear study's estimate (its own test checks the closed form).
    EXPECT_EQ(in.capacity, wall_capacity_estimate(s.fem, 1.25).per_metre);
    // Cracked cantilever at h_c = 1.25 − 0.10 m: 3·(E/2)·t³/12/h_c³.
    const double k = 3.0 * 15e9 * (0.25 * 0.25 * 0.25 / 12.0) / (1.15 * 1.15 * 1.15);
    EXPECT_NEAR(in.stiffness, k, exact * k);
    EXPECT_NEAR(k, 38.53e6, 0.01e6); // N/m per m, by hand
    EXPECT_EQ(in.unloading_stiffness, in.stiffness);
    // P-wave speed of E = 50 MPa, ν = 0.3, ρ = 1900: M = 67.31 MPa, c = 188.2 m/s.
    const double m = 50e6 * 0.7 / (1.3 * 0.4);
    EXPECT_NEAR(in.soil_wave_speed, std::sqrt(m / 1900.0), exact * 200.0);
    EXPECT_NEAR(in.soil_wave_speed, 188.2, 0.1);
    EXPECT_EQ(in.soil_density, 1900.0);
    EXPECT_NEAR(in.loaded_height, 1.25, exact); // backfill height = H
    // Plane-strain bar speed √(E/(ρ(1 − ν²))) = 3608 m/s; Z = ρ·c·t_slab = 1.732 MN·s/m per m.
    const double z = 2400.0 * std::sqrt(30e9 / (2400.0 * 0.96)) * 0.20;
    EXPECT_NEAR(in.slab_impedance, z, exact * z);
    EXPECT_NEAR(z, 1.732e6, 0.001e6);
    // The wall: the P-wave speed √(E(1 − ν)/((1 + ν)(1 − 2ν))/ρ) = 3727 m/s (1D strain: the wall
    // continues above and below the band) over the wall's thickness: Z = 2.236 MN·s/m per m.
    const double zw = 2400.0 * std::sqrt(30e9 * 0.8 / (1.2 * 0.6 * 2400.0)) * 0.25;
    EXPECT_NEAR(in.wall_impedance, zw, exact * zw);
    EXPECT_NEAR(zw, 2.236e6, 0.001e6);
    EXPECT_NEAR(in.wall_mass, 2400.0 * 0.25 * 1.25, exact * 750.0);
    EXPECT_EQ(in.striker_mass, 20e3);
  }

  // A heavy slab against an elastic-perfectly plastic wall without a dashpot (α = 0: the cap is
  // F_y): the slab's energy goes into the plateau, ½mv² = F_y·(w_max − w_y/2) + F_y²/(2k_c)
  // (the wall's and the contact's springs at F_y; the light wall's kinetic energy neglected),
  // and its momentum, with the wall's that moves with it, into the plateau's impulse:
  // (m + m_w)·v = F_y·(t_stop − w_y/(2v)), the rise to F_y taking w_y/v at half the force.
  TEST(YieldingWallElement, HeavySlabStopsByTheRigidPlasticEnergyAndImpulse)
  {
    YieldingWallInputs in       = inputs();
    in.hardening_ratio          = 0.0;
    in.ultimate_capacity        = in.capacity;
    in.striker_mass             = 55e3;
    const YieldingWallElement e = with_radiation_damping(derive_yielding_wall(in, 1.0), 0.0);
    const double              m = 55e3, v = 1.0, f_y = in.capacity;
    const SlabImpactResult    r   = slab_impact(e, m, v, 1.0, 1e-5);
    const double              w_y = f_y / in.stiffness;
    const double w_max  = 0.5 * m * v * v / f_y + 0.5 * w_y - f_y / (2.0 * e.contact_stiffness);
    const double travel = w_max + f_y / e.contact_stiffness;
    std::cout << "slab travel " << r.slab_peak_displacement * 1e3 << " mm (closed form "
              << travel * 1e3 << "), time to stop " << r.time_to_stop * 1e3 << " ms (closed form "
              << ((m + in.wall_mass) * v / f_y + w_y / (2.0 * v)) * 1e3 << "), wall set "
              << r.wall_residual * 1e3 << " mm\n";
    EXPECT_NEAR(r.slab_peak_displacement, travel, 0.01 * travel);
    const double t_stop = (m + in.wall_mass) * v / f_y + w_y / (2.0 * v);
    EXPECT_NEAR(r.time_to_stop, t_stop, 0.02 * t_stop);
    // On the plateau slab and wall decelerate together at F_y/(m + m_w): the last 5 % of the
    // travel takes √(2 · 0.05 · travel · (m + m_w)/F_y), and 95 % of it is reached that much
    // earlier (the FEM's time_to_95_travel, the same definition).
    const double t_95 = t_stop - std::sqrt(0.1 * travel * (m + in.wall_mass) / f_y);
    std::cout << "time to 95 % of the travel " << r.time_to_95_travel * 1e3 << " ms (closed form "
              << t_95 * 1e3 << ")\n";
    EXPECT_NEAR(r.time_to_95_travel, t_95, 0.02 * t_95);
    // The set: w_max less the spring-back F_y/k_ur.
    EXPECT_NEAR(r.wall_residual, w_max - f_y / in.unloading_stiffness, 0.01 * w_max);
    EXPECT_LT(r.peak_contact_force, in.slab_impedance * v); // below the rigid-slab impact
  }

  // The dashpot fitted to the slab travel of an element with a known dashpot gives that dashpot
  // back; a target beyond the travels of c_r = 0 or of the largest c_r is returned with a note.
  TEST(YieldingWallElement, DashpotFittedToASlabTravelIsRecovered)
  {
    YieldingWallInputs in       = inputs();
    in.striker_mass             = 3840.0;
    in.ultimate_capacity        = 150e3;
    const YieldingWallElement e = derive_yielding_wall(in, 1.0);
    const double              c = 60e3;
    const double              travel =
      slab_impact(with_radiation_damping(e, c), 3840.0, 1.0, 0.2, 1e-6).slab_peak_displacement;
    const DashpotFit fit = fit_radiation_damping(e, 3840.0, 1.0, travel, 400e3, 0.2, 1e-6);
    std::cout << "dashpot " << c / 1e3 << " kN*s/m^2 (travel " << travel * 1e3
              << " mm) fitted back: " << fit.damping / 1e3 << " kN*s/m^2\n";
    EXPECT_TRUE(fit.note.empty()) << fit.note;
    EXPECT_NEAR(fit.damping, c, 0.01 * c);
    EXPECT_NEAR(fit.travel, travel, 1e-4 * travel);
    const DashpotFit far = fit_radiation_damping(e, 3840.0, 1.0, 10.0 * travel, 400e3, 0.2, 1e-6);
    EXPECT_EQ(far.damping, 0.0);
    EXPECT_FALSE(far.note.empty());
    const DashpotFit near = fit_radiation_damping(e, 3840.0, 1.0, 0.01 * travel, 400e3, 0.2, 1e-6);
    EXPECT_EQ(near.damping, 400e3);
    EXPECT_FALSE(near.note.empty());
    EXPECT_THROW(fit_radiation_damping(e, 3840.0, 1.0, 0.0, 400e3, 0.2, 1e-6),
                 std::invalid_argument);
  }

  TEST(YieldingWallElement, BuildingRunClosesTheEnergyBalanceWithPlasticAndRadiatedWork)
  {
    // The default study's building on the synthetic record (8 s) between the derived walls of
    // H = 1.25 m, 10 % inside the no-wall peak isolation displacement.
    StudyScene        s = study_scene();
    GroundMotionScene record;
    record.duration                   = 8.0;
    const lumped::GroundMotion motion = load_ground_motion(record);
    const LumpedScene          bare   = study_lumped_scene(s, record);
    const LumpedCaseResult     none   = run_lumped_case("no_walls", bare, motion);
    ASSERT_TRUE(none.ok()) << none.status;
    const YieldingWallElement e = derive_yielding_wall(
      yielding_wall_inputs(s.fem, 1.25, s.building.isolation_mass / s.fit.width),
      s.fit.width);
    LumpedScene walled =
      yielding_walled_scene(bare, 0.9 * none.response.peak_displacement.at(0), e);
    walled.integration.dt       = "5e-5 s";
    const LumpedCaseResult done = run_lumped_case("yielding", walled, motion);
    ASSERT_TRUE(done.ok()) << done.status;
    ASSERT_EQ(done.yielding_walls.size(), 2u);
    double plastic = 0.0, radiated = 0.0;
    for (const YieldingWallLimits &w : done.yielding_walls)
    {
      plastic += done.response.contacts.at(w.contact).plastic_work;
      radiated += done.response.contacts.at(w.contact).radiated_work;
    }
    const lumped::EnergyBalance &b = done.response.energy;
    std::cout << "input " << b.input << " J, wall plastic " << plastic << " J, radiated "
              << radiated << " J, largest residual " << b.max_relative_error << "\n";
    EXPECT_GT(plastic, 1e-3 * b.input); // the walls yielded
    EXPECT_GT(radiated, 1e-3 * b.input);
    EXPECT_LT(b.max_relative_error, 1e-4);
  }
} // namespace kimp::app
