// Reduction of a lumped run (docs/physics.md §2 responses) to the scalar metrics of a sweep row.
#include "app/sweep/sweep_lumped.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "app/lumped_scene.h"
#include "io/scene_io.h"

namespace kimp::app
{
  using namespace kimp::io;
  void
  append_lumped_metrics(const LumpedCaseResult &result, const std::string &prefix, CaseRow &row)
  {
    const lumped::Response &r   = result.response;
    const auto              add = [&](const std::string &name, double value)
    { row.metrics.emplace_back(prefix + name, value); };
    add("dt [s]", r.dt);
    add("n_steps", static_cast<double>(r.n_steps));
    for (std::size_t i = 0; i < r.peak_displacement.size(); ++i)
      add(fmt::format("peak_displacement_dof{} [m]", i), r.peak_displacement[i]);
    for (std::size_t i = 0; i < r.peak_absolute_acceleration.size(); ++i)
      add(fmt::format("peak_abs_acceleration_dof{} [m/s^2]", i), r.peak_absolute_acceleration[i]);
    for (std::size_t s = 0; s < r.peak_interstorey_drift.size(); ++s)
      add(fmt::format("peak_drift_storey{} [m]", s), r.peak_interstorey_drift[s]);
    add("max_interstorey_drift [m]", r.max_interstorey_drift());
    add("n_impacts", static_cast<double>(r.n_impacts()));
    for (const lumped::ContactResult &c : r.contacts)
    {
      double max_velocity = 0.0;
      for (const lumped::ImpactEvent &impact : c.impacts)
        max_velocity = std::max(max_velocity, std::abs(impact.velocity));
      add(c.name + ".n_impacts", static_cast<double>(c.impacts.size()));
      add(c.name + ".max_impact_velocity [m/s]", max_velocity);
      add(c.name + ".peak_force [N]", c.peak_force);
      add(c.name + ".indentation [m]", c.permanent_indentation);
    }
    add("energy_error", r.energy.max_relative_error);
    for (const BuildingModes &b : result.buildings)
      if (!b.periods.empty())
        add(b.name + ".T1 [s]", b.periods.front());
    if (result.companion)
    {
      const lumped::Response &free = *result.companion;
      for (std::size_t i = 0; i < free.peak_displacement.size(); ++i)
        add(fmt::format("free_peak_displacement_dof{} [m]", i), free.peak_displacement[i]);
      const lumped::Amplification amplification = lumped::amplification_factors(r, free);
      for (std::size_t i = 0; i < amplification.absolute_acceleration.size(); ++i)
        add(fmt::format("amp_abs_acceleration_dof{}", i), amplification.absolute_acceleration[i]);
      for (std::size_t s = 0; s < amplification.interstorey_drift.size(); ++s)
        add(fmt::format("amp_drift_storey{}", s), amplification.interstorey_drift[s]);
    }
  }

  void append_model_metrics(const lumped::PoundingModel &model,
                            const LumpedCaseResult      &result,
                            const std::string           &prefix,
                            CaseRow                     &row)
  {
    for (const lumped::BuildingBlock &block : model.buildings())
    {
      const auto n_storeys =
        std::count_if(model.storeys().begin(),
                      model.storeys().end(),
                      [&](const lumped::Storey &s) { return s.building == block.name; });
      row.metrics.emplace_back(prefix + block.name + ".first_dof", block.first_dof);
      row.metrics.emplace_back(prefix + block.name + ".n_dofs", block.n_dofs);
      row.metrics.emplace_back(prefix + block.name + ".n_storeys", static_cast<double>(n_storeys));
    }
    const std::vector<lumped::ContactPair> &contacts = model.contacts();
    for (const lumped::ContactPair &c : contacts)
      row.metrics.emplace_back(prefix + c.name + ".clearance [m]", c.gap);
    if (!result.companion)
      return;
    const std::vector<double> &free_peak = result.companion->peak_displacement;
    // A DOF index of -1 is the ground (a moat wall moves with it: no relative displacement).
    const auto peak_of = [&](int dof)
    { return dof < 0 ? 0.0 : free_peak.at(static_cast<std::size_t>(dof)); };
    for (const lumped::ContactPair &c : contacts)
      row.metrics.emplace_back(prefix + c.name + ".srss_gap [m]",
                               std::hypot(peak_of(c.left_dof), peak_of(c.right_dof)));
  }

  CaseRunner make_lumped_case_runner(std::optional<std::filesystem::path> records_dir_override)
  {
    return [records_dir_override](const std::string &text, const std::string &name)
    {
      const LumpedScene          scene  = load_scene_text<LumpedScene>(text, name);
      const lumped::GroundMotion motion = load_ground_motion_at(scene.ground_motion,
                                                                records_dir_override,
                                                                name,
                                                                text,
                                                                "ground_motion");
      const auto                 cases  = resolve_cases(scene);
      CaseRow                    row;
      for (const auto &[case_name, case_scene] : cases)
      {
        const LumpedCaseResult result =
          run_lumped_case(case_name, case_scene, motion, scene.ground_motion.scale);
        if (!result.ok())
          return CaseRow{{}, result.status};
        const std::string prefix = cases.size() > 1 ? case_name + "." : std::string();
        append_lumped_metrics(result, prefix, row);
        const lumped::PoundingModel model(make_pounding_scene(case_scene));
        append_model_metrics(model, result, prefix, row);
      }
      return row;
    };
  }
} // namespace kimp::app
