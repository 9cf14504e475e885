// The wall-and-backfill part of a yielding moat wall (lumped/laws/wall_backfill_law.h) against
// closed forms: yield, hardening, unloading, permanent set, tension cap, failure, plastic and
// radiated work, the trial/commit contract; and its cap-and-hyperbola variants against OpenSees'
// ElasticPPGap ("damage") and HyperbolicGapMaterial, written out below from their documented
// equations, on their documented parameters.
#include <cmath>
#include <gtest/gtest.h>
#include <initializer_list>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "lumped/laws/wall_backfill_law.h"
#include "tests/support/lumped_scenes.h"

namespace kimp::lumped
{
  namespace
  {
    constexpr double tight_tol    = 1e-12; // closed forms evaluated the same way: round-off
    constexpr double opensees_tol = 1e-3;  // the issue's 0.1 % on forces

    /// Bilinear wall: k = 100 MN/m, F_y = 1 MN (w_y = 1 cm), α = 5 %, k_ur = 200 MN/m.
    WallBackfillParams bilinear_params()
    {
      WallBackfillParams p = kimp::testing::bilinear_wall_part(100e6, 1e6, 0.05, 200e6);
      p.mass               = 50e3;
      return p;
    }

    /// Trial and commit at w (quasi-static: ẇ = 0); returns the force.
    double step(WallBackfillLaw &law, double w, double rate = 0.0)
    {
      const double f = law.set_trial(w, rate).force;
      law.commit();
      return f;
    }

    void expect_rel(double actual, double expected, double tol, const char *what)
    {
      EXPECT_NEAR(actual, expected, tol * std::max(std::abs(expected), 1.0)) << what;
    }

    /// Walks `law` from w = 0 through `targets` in 1 µm quasi-static steps; returns the work put
    /// in (trapezoid rule), J.
    double work_along(WallBackfillLaw &law, std::initializer_list<double> targets)
    {
      double work = 0.0, w = 0.0, f = 0.0;
      for (const double target : targets)
      {
        const double dw = target > w ? 1e-6 : -1e-6;
        while (std::abs(target - w) > 0.5e-6)
        {
          const double f_next = step(law, w + dw);
          work += 0.5 * (f + f_next) * dw;
          f = f_next;
          w += dw;
        }
      }
      return work;
    }
  } // namespace

  TEST(WallBackfillLaw, ElasticUpToTheCapThenHardens)
  {
    WallBackfillLaw law(bilinear_params());
    expect_rel(step(law, 0.005), 0.5e6, tight_tol, "elastic: k·w");
    EXPECT_EQ(law.permanent_indentation(), 0.005 - 0.5e6 / 200e6); // k_ur > k: a small set
    expect_rel(step(law, 0.01), 1e6, tight_tol, "at the cap");
    // Hardening: F_y + α·k·(w − w_y).
    expect_rel(step(law, 0.03), 1e6 + 0.05 * 100e6 * 0.02, tight_tol, "hardening");
    EXPECT_DOUBLE_EQ(law.set_trial(0.031, 0.0).stiffness, 0.05 * 100e6);
    law.revert_to_last_commit();
    EXPECT_DOUBLE_EQ(law.peak_deformation(), 0.03);
  }

  TEST(WallBackfillLaw, UnloadsAtKurToAPermanentSetAndReloadsToTheEnvelope)
  {
    WallBackfillLaw law(bilinear_params());
    step(law, 0.03);
    const double f_max = 1.1e6;
    const double w_p   = 0.03 - f_max / 200e6; // the permanent set
    expect_rel(step(law, 0.028), f_max - 200e6 * 0.002, tight_tol, "unloading at k_ur");
    EXPECT_DOUBLE_EQ(law.permanent_indentation(), w_p);
    // Past the set the part carries nothing (F_t = 0) and keeps the set: pushed back stays back.
    EXPECT_EQ(step(law, 0.0), 0.0);
    EXPECT_EQ(step(law, -0.01), 0.0);
    EXPECT_DOUBLE_EQ(law.permanent_indentation(), w_p);
    // Reloading: nothing until w_p, then the line, then the envelope beyond w_max.
    EXPECT_EQ(step(law, w_p - 1e-6), 0.0);
    expect_rel(step(law, 0.029), 200e6 * (0.029 - w_p), tight_tol, "reloading line");
    expect_rel(step(law, 0.04), 1e6 + 0.05 * 100e6 * 0.03, tight_tol, "back on the envelope");
  }

  TEST(WallBackfillLaw, UnloadingSofterThanTheLoadingNeverLeavesANegativeSet)
  {
    // A cracked wall that springs back softer than it was loaded: k_ur = 20 MN/m < k = 100 MN/m.
    // The line unloads at k̃ = max(k_ur, E(w_max)/w_max): elastic back to 0 while the envelope's
    // secant is the steeper, the set w_max − E/k_ur once it is not.
    WallBackfillParams p  = bilinear_params();
    p.unloading_stiffness = 20e6;
    WallBackfillLaw law(p);
    step(law, 0.005); // elastic: the secant is k
    expect_rel(step(law, 0.0025), 100e6 * 0.0025, tight_tol, "back along k");
    EXPECT_EQ(law.permanent_indentation(), 0.0);
    // 30 mm: E = 1.1 MN, secant 36.67 MN/m > k_ur: the line through the origin, no set.
    step(law, 0.03);
    expect_rel(step(law, 0.015), 1.1e6 / 0.03 * 0.015, tight_tol, "along the secant");
    EXPECT_NEAR(law.permanent_indentation(), 0.0, tight_tol);
    EXPECT_DOUBLE_EQ(law.set_trial(0.015, 0.0).stiffness, 1.1e6 / 0.03);
    law.revert_to_last_commit();
    // 100 mm: E = 1.45 MN, secant 14.5 MN/m < k_ur: set 0.1 − 1.45/20 = 27.5 mm.
    step(law, 0.1);
    const double w_p = 0.1 - 1.45e6 / 20e6;
    expect_rel(step(law, 0.09), 1.45e6 - 20e6 * 0.01, tight_tol, "unloading at k_ur");
    expect_rel(law.permanent_indentation(), w_p, tight_tol, "set");
    EXPECT_EQ(step(law, 0.02), 0.0);
    // Reloading along the line rejoins the envelope at w_max.
    expect_rel(step(law, 0.1), 1.45e6, tight_tol, "reloaded to w_max");
    expect_rel(step(law, 0.11), 1.5e6, tight_tol, "on the envelope");
  }

  TEST(WallBackfillLaw, SoftUnloadingKeepsTheWorkBalance)
  {
    // The work put in along a cyclic path (trapezoid over 1 µm steps) equals the plastic work
    // W_p = ∫E − E²/(2k̃) plus the stored energy, with k_ur < k (k̃ changes with w_max).
    WallBackfillParams p  = bilinear_params();
    p.unloading_stiffness = 20e6;
    WallBackfillLaw law(p);
    const double    work = work_along(law, {0.03, 0.0, 0.1, 0.05, 0.12, 0.1});
    expect_rel(law.plastic_work() + law.stored_energy(), work, 1e-6, "work balance");
    const double e = 1.5e6 + 0.05 * 100e6 * 0.01; // E(0.12)
    EXPECT_GT(law.plastic_work(), 0.0);
    expect_rel(law.plastic_work(), law.envelope_work(0.12) - 0.5 * e * e / 20e6, 1e-10, "W_p");
  }

  TEST(WallBackfillLaw, PlasticWorkIsTheEnvelopeWorkLessTheRecoverableEnergy)
  {
    WallBackfillLaw law(bilinear_params());
    const double    k = 100e6, fy = 1e6, a = 0.05, kur = 200e6;
    for (const double w : {0.004, 0.01, 0.02, 0.03, 0.025, 0.0, 0.03, 0.035})
      step(law, w);
    const double w_max = 0.035, f = fy + a * k * (w_max - 0.01);
    // ∫E dw: elastic triangle, then the trapezoid of the hardening branch.
    const double work = 0.5 * fy * 0.01 + 0.5 * (fy + f) * (w_max - 0.01);
    expect_rel(law.plastic_work(), work - 0.5 * f * f / kur, tight_tol, "W_p");
    expect_rel(law.stored_energy(), 0.5 * f * f / kur, tight_tol, "stored on the envelope");
    step(law, 0.0);
    EXPECT_EQ(law.stored_energy(), 0.0); // past the set: nothing stored
    expect_rel(law.dissipated_energy(), work - 0.5 * f * f / kur, tight_tol, "no dashpot");
  }

  TEST(WallBackfillLaw, TensionCapLimitsThePullBackWithoutMovingTheSet)
  {
    WallBackfillParams p = bilinear_params();
    p.tension_capacity   = 0.2e6;
    WallBackfillLaw law(p);
    step(law, 0.03);
    const double w_p = law.permanent_indentation();
    expect_rel(step(law, w_p - 0.0005), -200e6 * 0.0005, tight_tol, "elastic pull-back");
    EXPECT_EQ(step(law, w_p - 0.01), -0.2e6);
    EXPECT_EQ(law.set_trial(w_p - 0.011, 0.0).stiffness, 0.0);
    law.revert_to_last_commit();
    // Stored: the line to the cap, then F_t times the further travel.
    const double d_t = 0.2e6 / 200e6;
    expect_rel(law.stored_energy(), 0.5 * 200e6 * d_t * d_t + 0.2e6 * (0.01 - d_t), tight_tol, "U");
    EXPECT_DOUBLE_EQ(law.permanent_indentation(), w_p); // no reverse yielding
    expect_rel(step(law, w_p + 0.001), 200e6 * 0.001, tight_tol, "back on the same line");
  }

  TEST(WallBackfillLaw, RadiatedWorkAtConstantRateIsCTimesVTimesTravel)
  {
    WallBackfillParams p = bilinear_params();
    p.radiation_damping  = 3e6;
    WallBackfillLaw law(p);
    const double    v = 0.5;
    const double    f = law.set_trial(0.001, v).force;
    EXPECT_DOUBLE_EQ(f, 100e6 * 0.001 + 3e6 * v);
    EXPECT_EQ(law.set_trial(0.001, v).damping, 3e6);
    law.revert_to_last_commit();
    step(law, 0.0, v); // the rate at the start of the travel
    for (int i = 1; i <= 20; ++i)
      step(law, 0.001 * i, v);
    expect_rel(law.radiated_work(), 3e6 * v * 0.02, tight_tol, "c·v·travel");
    // The peak resistance leaves the dashpot out: E(0.02 m) of the envelope.
    expect_rel(law.peak_resistance(), 1e6 + 0.05 * 100e6 * 0.01, tight_tol, "peak R");
    EXPECT_NEAR(law.dissipated_energy(), law.plastic_work() + law.radiated_work(), 1e-9);
  }

  TEST(WallBackfillLaw, FailsPastTheStatedDisplacement)
  {
    WallBackfillParams p   = bilinear_params();
    p.failure_displacement = 0.05;
    WallBackfillLaw law(p);
    step(law, 0.049);
    EXPECT_FALSE(law.failed());
    step(law, 0.0);
    EXPECT_FALSE(law.failed());
    step(law, 0.051);
    EXPECT_TRUE(law.failed());
    step(law, 0.0);
    EXPECT_TRUE(law.failed()); // a failed wall stays failed
  }

  TEST(WallBackfillLaw, RepeatedImpactsAccumulateTheSet)
  {
    // Three pushes, each 1 cm past the set left by the last: w_max grows by 1 cm + its set
    // shift, the set after push i is w_max,i − E(w_max,i)/k_ur.
    WallBackfillLaw law(bilinear_params());
    double          w_p = 0.0;
    for (int i = 0; i < 3; ++i)
    {
      const double w_max = std::max(law.peak_deformation(), w_p + 0.02);
      step(law, w_max);
      step(law, w_p - 0.01); // rebound past the set: the wall comes to rest there
      const double f = 1e6 + 0.05 * 100e6 * (w_max - 0.01);
      w_p            = w_max - f / 200e6;
      EXPECT_DOUBLE_EQ(law.permanent_indentation(), w_p) << "push " << i;
    }
    EXPECT_GT(w_p, 0.03);
  }

  TEST(WallBackfillLaw, KeepsTheTrialCommitContract)
  {
    WallBackfillParams p = bilinear_params();
    p.radiation_damping  = 1e6;
    p.tension_capacity   = 0.1e6;
    for (const WallEnvelope env : {WallEnvelope::bilinear, WallEnvelope::hyperbolic})
    {
      p.envelope      = env;
      p.failure_ratio = 0.7;
      WallBackfillLaw           law(p);
      const std::vector<double> path = {0.002, 0.012, 0.03, 0.02, -0.01, 0.025, 0.045};
      double                    w_c  = 0.0;
      for (const double w : path)
      {
        const double        v = (w - w_c) / 0.1; // a rate consistent with the path
        const ForceResponse a = law.set_trial(w, v);
        const ForceResponse b = law.set_trial(w, v);
        EXPECT_EQ(a.force, b.force) << "idempotent at " << w;
        std::unique_ptr<ForceLaw> copy = law.clone();
        EXPECT_EQ(copy->set_trial(w, v).force, a.force) << "clone at " << w;
        // Tangent against a central difference (no kink within ±h of the path's points).
        const double h  = 1e-8;
        const double fp = law.set_trial(w + h, v).force;
        const double fm = law.set_trial(w - h, v).force;
        EXPECT_NEAR(a.stiffness, (fp - fm) / (2 * h), 1e-4 * std::abs(a.stiffness) + 1.0)
          << "tangent at " << w;
        const double before  = law.dissipated_energy();
        const double plastic = law.plastic_work();
        law.set_trial(w, v);
        law.revert_to_last_commit();
        EXPECT_EQ(law.dissipated_energy(), before) << "a trial leaves the committed state";
        step(law, w, v);
        // The plastic work never decreases; the radiated work's trapezoid rule may dip at a
        // turning point between two samples (as the contact laws' dissipation).
        EXPECT_GE(law.plastic_work(), plastic) << "at " << w;
        EXPECT_GE(law.dissipated_energy(), 0.0) << "at " << w;
        w_c = w;
      }
      EXPECT_TRUE(law.in_contact());
      law.revert_to_start();
      EXPECT_EQ(law.peak_deformation(), 0.0);
      EXPECT_EQ(law.dissipated_energy(), 0.0);
    }
  }

  // The cap F_u = 1.1 MN of the bilinear wall: reached at w_u = w_y + (F_u − F_y)/(α·k) =
  // 0.01 + 0.1e6/5e6 = 3 cm, flat beyond (tangent 0); unloading from w_max = 5 cm at k_ur leaves
  // the set w_max − F_u/k_ur; the plastic work is the envelope's area less F_u²/(2k_ur).
  TEST(WallBackfillLaw, HardeningStopsAtTheCapAndUnloadsToItsSet)
  {
    WallBackfillParams p = bilinear_params();
    p.ultimate_capacity  = 1.1e6;
    WallBackfillLaw law(p);
    EXPECT_DOUBLE_EQ(law.cap_displacement(), 0.03);
    expect_rel(step(law, 0.005), 0.5e6, tight_tol, "elastic below the yield force");
    expect_rel(step(law, 0.02), 1e6 + 0.05 * 100e6 * 0.01, tight_tol, "hardening below the cap");
    EXPECT_DOUBLE_EQ(law.set_trial(0.025, 0.0).stiffness, 0.05 * 100e6);
    law.revert_to_last_commit();
    expect_rel(step(law, 0.03), 1.1e6, tight_tol, "at the cap");
    expect_rel(step(law, 0.05), 1.1e6, tight_tol, "flat past the cap");
    EXPECT_EQ(law.set_trial(0.06, 0.0).stiffness, 0.0);
    law.revert_to_last_commit();
    EXPECT_DOUBLE_EQ(law.peak_resistance(), 1.1e6);
    const double w_p = 0.05 - 1.1e6 / 200e6; // 4.45 cm
    expect_rel(step(law, 0.049), 1.1e6 - 200e6 * 0.001, tight_tol, "unloading at k_ur");
    EXPECT_DOUBLE_EQ(law.permanent_indentation(), w_p);
    EXPECT_EQ(step(law, 0.0), 0.0); // F_t = 0: the wall keeps its set
    EXPECT_DOUBLE_EQ(law.permanent_indentation(), w_p);
    // Reloading meets the cap at w_max, then the flat envelope again.
    expect_rel(step(law, 0.0495), 200e6 * (0.0495 - w_p), tight_tol, "reloading line");
    expect_rel(step(law, 0.07), 1.1e6, tight_tol, "the cap after reloading");
    EXPECT_DOUBLE_EQ(law.permanent_indentation(), 0.07 - 1.1e6 / 200e6);
    // ∫E dw to 7 cm: the elastic triangle, the hardening trapezoid to 3 cm, the cap's rectangle.
    const double work = 0.5 * 1e6 * 0.01 + 0.5 * (1e6 + 1.1e6) * 0.02 + 1.1e6 * 0.04;
    expect_rel(law.envelope_work(0.07), work, tight_tol, "envelope work");
    expect_rel(law.plastic_work(), work - 0.5 * 1.1e6 * 1.1e6 / 200e6, tight_tol, "W_p");
  }

  // A cap at the yield force, or one that the hardening never reaches (α = 0), is the
  // elastic-perfectly plastic wall: flat at F_y.
  TEST(WallBackfillLaw, CapAtTheYieldForceIsElasticPerfectlyPlastic)
  {
    for (const double alpha : {0.05, 0.0})
    {
      WallBackfillParams p = bilinear_params();
      p.hardening_ratio    = alpha;
      p.ultimate_capacity  = alpha > 0.0 ? 1e6 : 2e6;
      WallBackfillLaw law(p);
      expect_rel(step(law, 0.04), 1e6, tight_tol, "flat at F_y");
      EXPECT_EQ(law.set_trial(0.05, 0.0).stiffness, 0.0);
      law.revert_to_last_commit();
      expect_rel(law.plastic_work(),
                 0.5 * 1e6 * 0.01 + 1e6 * 0.03 - 0.5 * 1e6 * 1e6 / 200e6,
                 tight_tol,
                 "W_p");
    }
  }

  TEST(WallBackfillLaw, RefusesBadParameters)
  {
    {
      WallBackfillParams q = bilinear_params();
      q.ultimate_capacity  = 0.9e6; // below F_y
      EXPECT_THROW(WallBackfillLaw{q}, std::invalid_argument);
      q.envelope          = WallEnvelope::hyperbolic;
      q.ultimate_capacity = 2e6; // the hyperbolic envelope has no cap
      EXPECT_THROW(WallBackfillLaw{q}, std::invalid_argument);
    }
    WallBackfillParams p  = bilinear_params();
    p.unloading_stiffness = 0.0;
    EXPECT_THROW(WallBackfillLaw{p}, std::invalid_argument);
    p                 = bilinear_params();
    p.hardening_ratio = 1.0;
    EXPECT_THROW(WallBackfillLaw{p}, std::invalid_argument);
    p      = bilinear_params();
    p.mass = 0.0;
    EXPECT_THROW(WallBackfillLaw{p}, std::invalid_argument);
  }

  // ---- OpenSees' materials, written out from their documentation (sign convention there:
  // ---- deformation u and force negative in compression, gap < 0; kimp's w = −u − |gap|).
  namespace
  {
    /**
     * ElasticPPGap, tag E Fy gap eta "damage" (compression form, Fy < 0, gap < 0): zero force
     * while u > u_min (initially the gap); elastic E·(u − u_min) for u_max <= u <= u_min;
     * beyond u_max (initially gap + Fy/E) the hardening line Fy + η·E·(u − gap − Fy/E). At a
     * committed state beyond u_max: u_max := u, u_min := u − F/E. With "damage" u_min is not
     * moved back when the element re-opens, so the gap grows.
     */
    class OpenSeesElasticPPGapDamage
    {
    public:
      OpenSeesElasticPPGapDamage(double e, double fy, double gap, double eta)
        : e_(e)
        , fy_(fy)
        , gap_(gap)
        , eta_(eta)
        , u_max_(gap + fy / e)
        , u_min_(gap)
      {
      }
      double commit(double u)
      {
        double f = 0.0;
        if (u < u_max_)
          f = fy_ + (u - gap_ - fy_ / e_) * eta_ * e_;
        else if (u > u_min_)
          f = 0.0;
        else
          f = e_ * (u - u_min_);
        if (u < u_max_)
        {
          u_max_ = u;
          u_min_ = u - f / e_;
        }
        return f;
      }

    private:
      double e_, fy_, gap_, eta_, u_max_, u_min_;
    };

    /**
     * HyperbolicGapMaterial, tag Kmax Kur Rf Fult gap (Fult < 0, gap < 0): on the envelope
     * (u <= the most negative u so far) F = (u − gap)/(1/Kmax + Rf·(u − gap)/Fult), 0 for
     * u >= gap; unloading (du > 0) F = F_c + Kur·du, not above 0; reloading (du < 0) the line
     * F = Kur·(u − u_r) through the reloading onset u_r = u_min − F(u_min)/Kur, 0 above u_r.
     */
    class OpenSeesHyperbolicGap
    {
    public:
      OpenSeesHyperbolicGap(double kmax, double kur, double rf, double fult, double gap)
        : kmax_(kmax)
        , kur_(kur)
        , rf_(rf)
        , fult_(fult)
        , gap_(gap)
      {
      }
      double commit(double u)
      {
        const double du = u - u_c_;
        double       f  = f_c_;
        if (u <= u_min_)
        {
          u_min_ = u;
          f      = u >= gap_ ? 0.0 : (u - gap_) / (1.0 / kmax_ + rf_ * (u - gap_) / fult_);
          u_r_   = u_min_ - f / kur_;
        }
        else if (du > 0.0)
          f = std::min(f_c_ + kur_ * du, 0.0);
        else if (du < 0.0)
          f = u > u_r_ ? 0.0 : kur_ * (u - u_r_);
        u_c_ = u;
        f_c_ = f;
        return f;
      }

    private:
      double kmax_, kur_, rf_, fult_, gap_;
      double u_c_ = 0.0, f_c_ = 0.0, u_min_ = 0.0, u_r_ = 0.0;
    };

    /// A cyclic closing path u(t) of OpenSees (negative = closing), beyond the gap three times.
    std::vector<double> cyclic_path(double gap, double amplitude)
    {
      std::vector<double> u;
      const double        pi = 3.14159265358979323846;
      for (int i = 0; i <= 3000; ++i)
      {
        const double s = static_cast<double>(i) / 3000.0;
        // Growing pushes with partial and full rebounds.
        u.push_back(-(gap + amplitude * s) * std::abs(std::sin(3.0 * pi * s)) +
                    0.1 * gap * std::sin(7.0 * pi * s));
      }
      return u;
    }

    /// Drives `law` and the OpenSees `reference` along cyclic_path(gap, 0.08) and expects the
    /// same force at every step (within opensees_tol of `capacity`, N). Returns the peak force of
    /// the reference, N.
    template <class Reference>
    double
    follow_cyclic_path(Reference &reference, WallBackfillLaw &law, double gap, double capacity)
    {
      double peak = 0.0;
      for (const double u : cyclic_path(gap, 0.08))
      {
        const double f_os = -reference.commit(u);
        const double f    = step(law, -u - gap);
        peak              = std::max(peak, f_os);
        EXPECT_NEAR(f, f_os, opensees_tol * capacity) << "u " << u;
      }
      return peak;
    }
  } // namespace

  TEST(WallBackfillLaw, BilinearReproducesOpenSeesElasticPPGapWithDamage)
  {
    // Caltrans-style backfill spring of a 1.68 m (5.5 ft) backwall per metre (5 ksf over the
    // height, 50 kip/in/ft: E = 28.9 kN/mm, Fy = 407 kN), gap 1 in, hardening η = 0 and 0.1.
    const double gap = 0.0254;
    for (const double eta : {0.0, 0.1})
    {
      OpenSeesElasticPPGapDamage reference(28.9e6, -407e3, -gap, eta);
      WallBackfillParams         p = kimp::testing::bilinear_wall_part(28.9e6, 407e3, eta, 28.9e6);
      p.mass                       = 1e3;
      WallBackfillLaw law(p);
      SCOPED_TRACE("eta " + std::to_string(eta));
      const double peak = follow_cyclic_path(reference, law, gap, 407e3);
      EXPECT_GE(peak, 407e3); // the path yields the material
      EXPECT_GT(law.plastic_work(), 0.0);
    }
  }

  TEST(WallBackfillLaw, HyperbolicReproducesOpenSeesHyperbolicGapMaterial)
  {
    // The documented parameters: Kmax = 20300 kN/m, Kur = Kmax, Rf = 0.7, Fult = 326 kN,
    // gap = 2.54 cm (a 1.68 m backwall, 1 m wide).
    const double          gap = 0.0254;
    OpenSeesHyperbolicGap reference(20300e3, 20300e3, 0.7, -326e3, -gap);
    WallBackfillParams    p;
    p.envelope            = WallEnvelope::hyperbolic;
    p.stiffness           = 20300e3;
    p.capacity            = 326e3;
    p.failure_ratio       = 0.7;
    p.unloading_stiffness = 20300e3;
    p.mass                = 1e3;
    WallBackfillLaw law(p);
    const double    peak = follow_cyclic_path(reference, law, gap, 326e3);
    EXPECT_GT(peak, 326e3); // past Fult: the hyperbola tends to Fult/Rf
    // The envelope's closed form at 7.64 cm beyond the gap (the documented range of the fit).
    expect_rel(law.envelope(0.0764),
               0.0764 / (1.0 / 20300e3 + 0.7 * 0.0764 / 326e3),
               tight_tol,
               "hyperbola");
  }

  // The curve envelope (a pushover's concave hull). Three segments: (0, 0), (1 cm, 1 MN),
  // (3 cm, 1.5 MN), (5 cm, 1.6 MN), flat at 1.6 MN past 5 cm; k = 100 MN/m, k_ur = 200 MN/m.
  namespace
  {
    WallBackfillParams curve_params()
    {
      WallBackfillParams p  = bilinear_params();
      p.envelope            = WallEnvelope::curve;
      p.hardening_ratio     = 0.0;
      p.curve_displacements = {0.0, 0.01, 0.03, 0.05};
      p.curve_forces        = {0.0, 1e6, 1.5e6, 1.6e6};
      return p;
    }
  } // namespace

  TEST(WallBackfillLaw, CurveOfTwoSegmentsIsTheBilinearWithItsCap)
  {
    // The bilinear wall with the cap F_u = 1.1 MN at w_u = 3 cm as the points (0, 0), (w_y, F_y),
    // (w_u, F_u): the same forces, tangents, sets and works along a cyclic path, to round-off.
    WallBackfillParams b  = bilinear_params();
    b.ultimate_capacity   = 1.1e6;
    b.tension_capacity    = 0.2e6;
    b.unloading_stiffness = 40e6; // below k: the secant and the set branches both occur
    WallBackfillParams c  = b;
    c.envelope            = WallEnvelope::curve;
    c.ultimate_capacity   = std::numeric_limits<double>::infinity();
    c.hardening_ratio     = 0.0;
    c.stiffness           = 0.0; // set by the curve
    c.capacity            = 0.0;
    c.curve_displacements = {0.0, 0.01, 0.03};
    c.curve_forces        = {0.0, 1e6, 1.1e6};
    WallBackfillLaw lb(b), lc(c);
    expect_rel(lc.parameters().stiffness, 100e6, tight_tol, "k: the first slope");
    EXPECT_EQ(lc.parameters().capacity, 1.1e6);
    expect_rel(lc.cap_displacement(), lb.cap_displacement(), tight_tol, "w_u");
    for (const double w : {0.004, 0.0, 0.0101, 0.015, 0.012, -0.01, 0.02, 0.031, 0.045, 0.01, 0.06})
    {
      const ForceResponse rb = lb.set_trial(w, 0.0), rc = lc.set_trial(w, 0.0);
      expect_rel(rc.force, rb.force, tight_tol, "force");
      expect_rel(rc.stiffness, rb.stiffness, tight_tol, "tangent");
      lb.commit();
      lc.commit();
      expect_rel(lc.permanent_indentation(), lb.permanent_indentation(), tight_tol, "set");
      expect_rel(lc.plastic_work(), lb.plastic_work(), tight_tol, "plastic work");
      expect_rel(lc.stored_energy(), lb.stored_energy(), tight_tol, "stored energy");
      expect_rel(lc.envelope_work(w > 0 ? w : 0.0),
                 lb.envelope_work(w > 0 ? w : 0.0),
                 tight_tol,
                 "envelope work");
    }
  }

  TEST(WallBackfillLaw, CurveYieldsAlongItsSegmentsAndIsFlatPastTheLastPoint)
  {
    WallBackfillLaw law(curve_params());
    expect_rel(step(law, 0.005), 0.5e6, tight_tol, "first segment: k·w");
    expect_rel(step(law, 0.02), 1e6 + 0.25e8 * 0.01, tight_tol, "second segment");
    EXPECT_DOUBLE_EQ(law.set_trial(0.025, 0.0).stiffness, 0.25e8);
    law.revert_to_last_commit();
    expect_rel(step(law, 0.04), 1.5e6 + 0.05e8 * 0.01, tight_tol, "third segment");
    expect_rel(step(law, 0.08), 1.6e6, tight_tol, "flat past the last point");
    EXPECT_EQ(law.set_trial(0.09, 0.0).stiffness, 0.0);
    law.revert_to_last_commit();
    EXPECT_DOUBLE_EQ(law.peak_resistance(), 1.6e6);
    EXPECT_EQ(law.cap_displacement(), 0.05);
  }

  TEST(WallBackfillLaw, CurveUnloadsToItsSetAndRemembersItAcrossImpacts)
  {
    // Push to 2 cm (E = 1.25 MN), unload at k_ur = 200 MN/m to w_p = 2 cm − 1.25/200 m; reload
    // along the line to the envelope at w_max; push to 4 cm; the set moves to 4 cm − 1.55/200.
    WallBackfillLaw law(curve_params());
    step(law, 0.02);
    const double w_p = 0.02 - 1.25e6 / 200e6;
    expect_rel(step(law, 0.019), 1.25e6 - 200e6 * 0.001, tight_tol, "unloading at k_ur");
    EXPECT_DOUBLE_EQ(law.permanent_indentation(), w_p);
    EXPECT_EQ(step(law, 0.0), 0.0); // F_t = 0: rests at its set
    expect_rel(step(law, 0.0195), 200e6 * (0.0195 - w_p), tight_tol, "reloading line");
    expect_rel(step(law, 0.04), 1.55e6, tight_tol, "back on the envelope");
    EXPECT_DOUBLE_EQ(law.permanent_indentation(), 0.04 - 1.55e6 / 200e6);
    // A cracked wall's k_ur = 20 MN/m < k: the secant 62.5 MN/m at 2 cm is steeper (elastic
    // back to 0, no set); at 5 cm the secant 32 MN/m still is; past 8 cm (20 MN/m) a set.
    WallBackfillParams p  = curve_params();
    p.unloading_stiffness = 20e6;
    WallBackfillLaw soft(p);
    step(soft, 0.02);
    EXPECT_NEAR(soft.permanent_indentation(), 0.0, 1e-15);
    step(soft, 0.1);
    expect_rel(soft.permanent_indentation(), 0.1 - 1.6e6 / 20e6, tight_tol, "set past 8 cm");
  }

  TEST(WallBackfillLaw, CurveWorkIsTheAreaUnderItsPoints)
  {
    WallBackfillLaw law(curve_params());
    for (const double w : {0.01, 0.0, 0.045, 0.03, 0.07})
      step(law, w);
    // ∫E dw to 7 cm: the triangle, two trapezoids, the flat rectangle.
    const double work =
      0.5 * 1e6 * 0.01 + 0.5 * (1e6 + 1.5e6) * 0.02 + 0.5 * (1.5e6 + 1.6e6) * 0.02 + 1.6e6 * 0.02;
    expect_rel(law.envelope_work(0.07), work, tight_tol, "envelope work");
    expect_rel(law.plastic_work(), work - 0.5 * 1.6e6 * 1.6e6 / 200e6, tight_tol, "W_p");
    // The work put in along a cyclic path (1 µm steps) is W_p plus the stored energy.
    WallBackfillParams p  = curve_params();
    p.unloading_stiffness = 20e6;
    p.tension_capacity    = 0.3e6;
    WallBackfillLaw cyc(p);
    const double    in = work_along(cyc, {0.02, -0.01, 0.045, 0.03, 0.09, 0.06});
    expect_rel(cyc.plastic_work() + cyc.stored_energy(), in, 1e-6, "work balance");
  }

  TEST(WallBackfillLaw, CurveRefusesPointsThatAreNotAConcaveMonotoneCurveFromTheOrigin)
  {
    const auto problem = [](std::vector<double> w, std::vector<double> f)
    { return wall_curve_problem(w, f); };
    EXPECT_EQ(problem({0, 0.01, 0.03}, {0, 1e6, 1.5e6}), "");
    EXPECT_EQ(problem({0, 0.01, 0.03}, {0, 1e6, 1e6}), ""); // flat last segment
    EXPECT_NE(problem({0}, {0}).find("at least two"), std::string::npos);
    EXPECT_NE(problem({0, 0.01}, {0, 1e6, 2e6}).find("count"), std::string::npos);
    EXPECT_NE(problem({0.001, 0.01}, {0, 1e6}).find("point 0"), std::string::npos);
    EXPECT_NE(problem({0, 0.01, 0.01}, {0, 1e6, 1.1e6}).find("point 2: displacement"),
              std::string::npos);
    EXPECT_NE(problem({0, 0.01, 0.02}, {0, 1e6, 0.9e6}).find("point 2: force"), std::string::npos);
    EXPECT_NE(problem({0, 0.01, 0.02, 0.03}, {0, 1e6, 1.2e6, 1.5e6}).find("point 3: the slope"),
              std::string::npos);
    EXPECT_NE(problem({0, 0.01}, {0, 0}).find("point 1"), std::string::npos);
    WallBackfillParams p = curve_params();
    p.curve_forces[2]    = 2.5e6; // a convex kink at point 2
    EXPECT_THROW(WallBackfillLaw{p}, std::invalid_argument);
    p                 = curve_params();
    p.hardening_ratio = 0.05; // the curve's slopes are its own
    EXPECT_THROW(WallBackfillLaw{p}, std::invalid_argument);
    p              = bilinear_params();
    p.curve_forces = {0.0, 1e6}; // points without the curve envelope
    EXPECT_THROW(WallBackfillLaw{p}, std::invalid_argument);
  }
} // namespace kimp::lumped
