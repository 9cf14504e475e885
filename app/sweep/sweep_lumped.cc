// Reduction of a lumped run (docs/physics.md §2 responses) to the scalar metrics of a sweep row.
#include "app/sweep/sweep_lumped.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <future>
#include <list>
#include <map>
#include <mutex>
#include <string>
#include <utility>

#include "app/lumped/lumped_scene.h"
#include "app/lumped/plan_run.h"
#include "app/lumped/plan_scene.h"
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

  void append_plan_metrics(const PlanRun &run, const std::string &prefix, CaseRow &row)
  {
    const lumped::plan::PlanResponse &r   = run.response;
    const auto                        add = [&](const std::string &name, double value)
    { row.metrics.emplace_back(prefix + name, value); };
    const PlanPeaks peaks = plan_peaks(r);
    add("dt [s]", r.dt);
    add("n_steps", static_cast<double>(r.n_steps));
    // The peaks of the directionality chart first (summary.json's names of `kimp lumped`).
    add("base_corner_displacement [m]", r.peak_corner_displacement.front());
    add("corner_impact_force [N]", peaks.corner_force);
    add("friction_force [N]", peaks.friction_force);
    add("top_acceleration [m/s^2]", r.peak_horizontal_acceleration.back());
    add("corner_drift [m]", peaks.corner_drift);
    add("rotation [rad]", peaks.rotation);
    add("isolator_force [N]", r.peak_isolator_force);
    add("n_impacts", static_cast<double>(r.n_impacts()));
    static const char *const direction[3] = {"x", "y", "theta"};
    for (std::size_t i = 0; i < r.peak_displacement.size(); ++i)
    {
      const std::size_t level = i / 3, d = i % 3;
      add(
        fmt::format("peak_displacement_level{}_{} [{}]", level, direction[d], d == 2 ? "rad" : "m"),
        r.peak_displacement[i]);
      add(fmt::format("peak_abs_acceleration_level{}_{} [{}]",
                      level,
                      direction[d],
                      d == 2 ? "rad/s^2" : "m/s^2"),
          r.peak_absolute_acceleration[i]);
    }
    for (std::size_t l = 0; l < r.peak_corner_displacement.size(); ++l)
    {
      add(fmt::format("peak_corner_displacement_level{} [m]", l), r.peak_corner_displacement[l]);
      add(fmt::format("peak_horizontal_acceleration_level{} [m/s^2]", l),
          r.peak_horizontal_acceleration[l]);
    }
    for (std::size_t s = 0; s < r.peak_corner_drift.size(); ++s)
    {
      add(fmt::format("peak_drift_x_storey{} [m]", s), r.peak_drift_x[s]);
      add(fmt::format("peak_drift_y_storey{} [m]", s), r.peak_drift_y[s]);
      add(fmt::format("peak_corner_drift_storey{} [m]", s), r.peak_corner_drift[s]);
    }
    for (std::size_t j = 0; j < r.peak_wall_force.size(); ++j)
      add(fmt::format("peak_wall_force_face{} [N]", j), r.peak_wall_force[j]);
    add("friction_work [J]", r.energy.friction);
    add("energy_error", r.energy.max_relative_error);
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

  struct FreeRunCache::Impl
  {
    using Entry =
      std::pair<std::string, std::shared_future<std::shared_ptr<const lumped::FreeRunPrefix>>>;
    std::mutex       mutex;
    std::list<Entry> entries; ///< most recently used first
    std::size_t      capacity = 12;
    std::size_t      computed = 0;
    std::size_t      served   = 0;
  };

  FreeRunCache::FreeRunCache(const std::size_t capacity)
    : impl_(std::make_unique<Impl>())
  {
    impl_->capacity = std::max<std::size_t>(capacity, 1);
  }

  FreeRunCache::~FreeRunCache() = default;

  std::shared_ptr<const lumped::FreeRunPrefix>
  FreeRunCache::get(const lumped::CentralDifference &free,
                    const double                     dt,
                    const lumped::GroundMotion      &motion)
  {
    std::string key = lumped::FreeRunPrefix::key(free, dt, motion);
    std::promise<std::shared_ptr<const lumped::FreeRunPrefix>> promise;
    std::unique_lock<std::mutex>                               lock(impl_->mutex);
    const auto found = std::find_if(impl_->entries.begin(),
                                    impl_->entries.end(),
                                    [&](const Impl::Entry &e) { return e.first == key; });
    if (found != impl_->entries.end())
    {
      impl_->entries.splice(impl_->entries.begin(), impl_->entries, found);
      ++impl_->served;
      const auto future = found->second;
      lock.unlock(); // another thread may still be computing it
      return future.get();
    }
    impl_->entries.emplace_front(std::move(key), promise.get_future().share());
    if (impl_->entries.size() > impl_->capacity)
      impl_->entries.pop_back();
    ++impl_->computed;
    lock.unlock();
    std::shared_ptr<const lumped::FreeRunPrefix> prefix;
    try
    {
      prefix = std::make_shared<const lumped::FreeRunPrefix>(free, motion);
    }
    catch (const std::exception &)
    {
      prefix = nullptr; // the cases run alone and report their own errors
    }
    promise.set_value(prefix);
    return prefix;
  }

  std::size_t FreeRunCache::computed() const
  {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->computed;
  }

  std::size_t FreeRunCache::served() const
  {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    return impl_->served;
  }

  namespace
  {
    /// Recorded ground motions by what selects them (loading and filtering an AT2 file costs more
    /// than a short run); synthetic motions are generated per case.
    class MotionCache
    {
    public:
      std::shared_ptr<const lumped::GroundMotion>
      get(const GroundMotionScene                    &gm,
          const std::optional<std::filesystem::path> &records_dir,
          const std::string                          &name,
          const std::string                          &text,
          const std::string                          &key_path = "ground_motion")
      {
        if (!gm.is_record())
          return std::make_shared<const lumped::GroundMotion>(
            load_ground_motion_at(gm, records_dir, name, text, key_path));
        // The scene name only enters error messages (failed loads are not cached).
        const std::string key =
          fmt::format("{}\n{}\n{}\n{}\n{}\n{}\n{}",
                      records_dir ? records_dir->string() : std::string(),
                      gm.record,
                      gm.records_dir,
                      gm.record_unit,
                      gm.scale_to_pga ? fmt::format("{:a}", *gm.scale_to_pga) : "-",
                      fmt::format("{:a}", gm.scale),
                      gm.duration ? fmt::format("{:a}", *gm.duration) : "-");
        {
          const std::lock_guard<std::mutex> lock(mutex_);
          const auto                        found = motions_.find(key);
          if (found != motions_.end())
            return found->second;
        }
        auto motion = std::make_shared<const lumped::GroundMotion>(
          load_ground_motion_at(gm, records_dir, name, text, key_path));
        const std::lock_guard<std::mutex> lock(mutex_);
        if (motions_.size() >= 64)
          motions_.clear();
        return motions_.emplace(key, motion).first->second;
      }

    private:
      std::mutex                                                         mutex_;
      std::map<std::string, std::shared_ptr<const lumped::GroundMotion>> motions_;
    };
  } // namespace

  CaseRunner make_lumped_case_runner(std::optional<std::filesystem::path> records_dir_override,
                                     const bool                           share_free_runs,
                                     std::filesystem::path                scene_directory)
  {
    const auto    motions   = std::make_shared<MotionCache>();
    const auto    free_runs = share_free_runs ? std::make_shared<FreeRunCache>() : nullptr;
    FreeRunSource source;
    if (free_runs)
      source = [free_runs](const lumped::CentralDifference &free,
                           const double                     dt,
                           const lumped::GroundMotion      &motion)
      { return free_runs->get(free, dt, motion); };
    return [records_dir_override, motions, source, scene_directory](const std::string &text,
                                                                    const std::string &name)
    {
      const PlanLumpedScene read = load_scene_text<PlanLumpedScene>(text, name, scene_directory);
      if (read.plan)
      {
        // A scene in plan: one run of the plan engine (its motion, both components, loaded
        // per case: an angle of incidence turns them).
        CaseRow row;
        append_plan_metrics(run_plan(read, name, text, records_dir_override), "", row);
        return row;
      }
      const LumpedScene                                &scene = read.base;
      const std::shared_ptr<const lumped::GroundMotion> motion =
        motions->get(scene.ground_motion, records_dir_override, name, text);
      const auto cases = resolve_cases(scene);
      CaseRow    row;
      for (std::size_t i = 0; i < cases.size(); ++i)
      {
        const auto &[case_name, case_scene] = cases[i];
        // A case with its own record (cases[i].record) runs with it, not with the scene's.
        const GroundMotionScene &case_motion = case_scene.ground_motion;
        const bool               own         = case_motion.record != scene.ground_motion.record;
        const std::shared_ptr<const lumped::GroundMotion> used =
          own ? motions->get(case_motion,
                             records_dir_override,
                             name,
                             text,
                             "cases[" + std::to_string(i) + "]") :
                motion;
        const LumpedCaseResult result =
          run_lumped_case(case_name,
                          case_scene,
                          *used,
                          own ? case_motion.scale : scene.ground_motion.scale,
                          source);
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
