// FreeRunPrefix: runs with contacts restarted from a shared contact-free run are bitwise equal to
// full runs (fused, any-size and reference kernels; gaps that pound early, late or never), and the
// free run is the companion run without contacts.
#include <gtest/gtest.h>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>

#include "lumped/excitation/ground_motion.h"
#include "lumped/integrators/free_run_prefix.h"
#include "lumped/laws/force_law_factory.h"
#include "tests/support/lumped_scenes.h"
#include "tests/support/response_compare.h"

namespace kimp::lumped
{
  namespace
  {
    using kimp::testing::expect_identical;

    /// What expect_identical leaves out: energies at the end, impact velocities, isolator peak.
    void expect_identical_all(const Response &a, const Response &b, const std::string &what)
    {
      expect_identical(a, b, what);
      EXPECT_EQ(a.energy.kinetic, b.energy.kinetic) << what;
      EXPECT_EQ(a.energy.strain, b.energy.strain) << what;
      EXPECT_EQ(a.energy.initial, b.energy.initial) << what;
      EXPECT_EQ(a.energy.relative_error, b.energy.relative_error) << what;
      EXPECT_EQ(a.energy.impact_dissipated, b.energy.impact_dissipated) << what;
      EXPECT_EQ(a.peak_isolator_force, b.peak_isolator_force) << what;
      ASSERT_EQ(a.contacts.size(), b.contacts.size()) << what;
      for (std::size_t c = 0; c < a.contacts.size(); ++c)
      {
        EXPECT_EQ(a.contacts[c].name, b.contacts[c].name) << what;
        EXPECT_EQ(a.contacts[c].dissipated_energy, b.contacts[c].dissipated_energy) << what;
        EXPECT_EQ(a.contacts[c].pulse_force, b.contacts[c].pulse_force) << what;
        EXPECT_EQ(a.contacts[c].pulse_deformation, b.contacts[c].pulse_deformation) << what;
        for (std::size_t i = 0; i < a.contacts[c].impacts.size(); ++i)
          EXPECT_EQ(a.contacts[c].impacts[i].velocity, b.contacts[c].impacts[i].velocity) << what;
      }
    }

    ForceLawSpec mkv()
    {
      return kimp::testing::contact_law("modified_kelvin_voigt", 2.5e9);
    }

    /// The thesis building between walls at `gap`, neighbours of `left`/`right` storeys (0: none)
    /// at `gap` + `extra`.
    PoundingScene scene(const double gap, const int left, const int right, const double extra)
    {
      PoundingScene s = kimp::testing::walled_scene("modified_kelvin_voigt", 2.5e9, gap);
      for (const auto &[storeys, side] :
           {std::pair{left, &s.left_neighbour}, std::pair{right, &s.right_neighbour}})
        if (storeys > 0)
        {
          AdjacentBuilding nb;
          nb.building   = reference_fixed_base_building(static_cast<unsigned int>(storeys));
          nb.separation = gap + extra;
          nb.law        = force_law_factory(mkv());
          *side         = nb;
        }
      return s;
    }

    /// Every gap of `gaps` through one shared prefix against full runs; returns the share of
    /// the steps the prefix saved.
    double check_gap_sweep(const int                  left,
                           const int                  right,
                           CentralDifferenceOptions   opt,
                           const std::vector<double> &gaps,
                           const GroundMotion        &g,
                           const std::string         &what)
    {
      const PoundingModel      first(scene(gaps.front(), left, right, 0.05));
      const CentralDifference  first_cdm(first, opt);
      CentralDifferenceOptions free_opt = opt;
      free_opt.dt                       = first_cdm.time_step(g.dt);
      const FreeRunPrefix prefix(CentralDifference(first.without_contacts(), free_opt), g);
      expect_identical_all(prefix.response(),
                           CentralDifference(first.without_contacts(), free_opt).run(g),
                           what + ": companion");
      long skipped = 0, total = 0, impacts = 0;
      for (const double gap : gaps)
      {
        const std::string       w = what + ", gap " + std::to_string(gap);
        const CentralDifference cdm(PoundingModel(scene(gap, left, right, 0.05)), opt);
        const Response          full = cdm.run(g);
        expect_identical_all(prefix.run(cdm, g), full, w);
        skipped += prefix.steps_skipped(cdm);
        total += full.n_steps + 1;
        impacts += static_cast<long>(full.n_impacts());
      }
      const double saved = static_cast<double>(skipped) / static_cast<double>(total);
      std::cout << "  " << what << " (" << first.n_dofs() << " DOFs): " << impacts
                << " impacts over " << gaps.size() << " gaps, " << 100.0 * saved
                << " % of the steps skipped\n";
      EXPECT_GT(impacts, 0) << what; // some gaps pound
      EXPECT_GT(saved, 0.0) << what; // and some start late or never
      return saved;
    }

    /// Δt = 0.2 ms and no histories: what a free-run prefix can share.
    CentralDifferenceOptions prefix_options()
    {
      CentralDifferenceOptions opt;
      opt.dt              = 2e-4;
      opt.output_interval = 0.0;
      return opt;
    }

    const std::vector<double> gaps{0.03, 0.06, 0.09, 0.12, 0.16, 0.25, 0.6};
  } // namespace

  TEST(FreeRunPrefix, FusedKernelRunsAreBitwiseEqualToFullRuns)
  {
    const GroundMotion       g   = kimp::testing::near_fault_motion(12.0);
    CentralDifferenceOptions opt = prefix_options();
    check_gap_sweep(0, 0, opt, gaps, g, "walls, fused kernel");
    opt.law_velocity = LawVelocity::backward_second_order;
    check_gap_sweep(0, 0, opt, gaps, g, "walls, second-order law velocity");
    opt.law_velocity = LawVelocity::backward;
    opt.dt           = 0.0; // auto: the step of the model with contacts
    check_gap_sweep(0, 3, opt, gaps, g, "wall and a 3-storey neighbour, dt auto");
  }

  TEST(FreeRunPrefix, AnySizeAndReferenceKernelRunsAreBitwiseEqualToFullRuns)
  {
    const GroundMotion       g   = kimp::testing::near_fault_motion(12.0);
    CentralDifferenceOptions opt = prefix_options();
    check_gap_sweep(4, 4, opt, gaps, g, "both neighbours 4 + 4, any-size kernel");
    check_gap_sweep(6, 2, opt, gaps, g, "both neighbours 6 + 2, any-size kernel");
    opt.kernel = CdmKernel::reference;
    check_gap_sweep(4, 4, opt, gaps, g, "both neighbours 4 + 4, reference kernel");
    check_gap_sweep(0, 0, opt, gaps, g, "walls, reference kernel");
  }

  TEST(FreeRunPrefix, RefusesOtherModelsAndHistories)
  {
    CentralDifferenceOptions opt = prefix_options();
    const GroundMotion       g   = kimp::testing::near_fault_motion(12.0);
    const PoundingModel      walls(scene(0.1, 0, 0, 0.0));
    const FreeRunPrefix      prefix(CentralDifference(walls.without_contacts(), opt), g);
    // Another building (5 storeys), another step, another record: refused.
    PoundingScene taller = scene(0.1, 0, 0, 0.0);
    taller.building      = reference_isolated_building(5);
    EXPECT_THROW(prefix.run(CentralDifference(PoundingModel(taller), opt), g),
                 std::invalid_argument);
    CentralDifferenceOptions finer = opt;
    finer.dt                       = 1e-4;
    EXPECT_THROW(prefix.run(CentralDifference(walls, finer), g), std::invalid_argument);
    GroundMotion scaled = g;
    scaled.acceleration[100] *= 1.0 + 1e-15;
    EXPECT_THROW(prefix.run(CentralDifference(walls, opt), scaled), std::invalid_argument);
    CentralDifferenceOptions with_histories = opt;
    with_histories.output_interval          = 0.01;
    EXPECT_THROW(FreeRunPrefix(CentralDifference(walls.without_contacts(), with_histories), g),
                 std::invalid_argument);
  }

  TEST(FreeRunPrefix, RepeatedContactsShareARunOtherLawsDoNot)
  {
    CentralDifferenceOptions opt = prefix_options();
    const GroundMotion       g   = kimp::testing::near_fault_motion(12.0);
    const PoundingModel      walls(scene(0.05, 0, 0, 0.0));
    const FreeRunPrefix      prefix(CentralDifference(walls.without_contacts(), opt), g);
    const CentralDifference  cdm(walls, opt);
    const Response           full = cdm.run(g);
    expect_identical_all(prefix.run(cdm, g), full, "first run");
    expect_identical_all(prefix.run(CentralDifference(PoundingModel(scene(0.05, 0, 0, 0.0)), opt),
                                    g),
                         full,
                         "the same contacts again (from the memo)");
    ASSERT_GT(full.n_impacts(), 0U);
    // Another COR or stiffness at the same gap is another run.
    for (const auto &[k, cor] : {std::pair{2.5e9, 0.5}, std::pair{1.0e9, 0.7}})
    {
      const PoundingScene other =
        kimp::testing::walled_scene("modified_kelvin_voigt", k, 0.05, cor);
      const CentralDifference other_cdm(PoundingModel(other), opt);
      const Response          other_full = other_cdm.run(g);
      EXPECT_NE(other_full.contacts[0].peak_force, full.contacts[0].peak_force);
      expect_identical_all(prefix.run(other_cdm, g), other_full, "another law");
    }
  }
} // namespace kimp::lumped
