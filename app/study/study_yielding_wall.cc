// The yielding moat wall of an inelastic `kimp study` (docs/physics.md §2 "Yielding moat wall",
// "Element of a study"): each height's element, the building runs against it, and their files:
// yielding_wall_element.csv, yielding_wall.csv, study.h5 /yielding_wall and the report section.
#include <algorithm>
#include <cmath>
#include <exception>
#include <fmt/format.h>
#include <limits>
#include <thread>

#include "app/study/pushover_fit.h"
#include "app/study/study_internal.h"
#include "app/study/yielding_wall_element.h"
#include "app/study/yielding_wall_impact.h"
#include "base/errors.h"
#include "base/format.h"
#include "base/thread_pool.h"
#include "io/results_file.h"
#include "io/table.h"

namespace kimp::app::study_internal
{
  namespace
  {
    const StudyYieldingWall *element_of(const std::vector<StudyYieldingWall> &walls, double h)
    {
      for (const StudyYieldingWall &w : walls)
        if (w.wall_height == h)
          return &w;
      return nullptr;
    }

    /// The walls' values of a done run into `run`: the larger wall's peaks, both walls' work.
    void fill_wall_values(StudyBuildingRun &run, const LumpedCaseResult &done)
    {
      const lumped::Response &r = done.response;
      run.peak_impact_force     = 0.0; // the contact parts only (not the permanent pairs)
      run.permanent_indentation = 0.0;
      for (const lumped::ContactResult &c : r.contacts)
        if (!c.permanent)
          run.peak_impact_force = std::max(run.peak_impact_force, c.peak_force);
      for (const YieldingWallLimits &w : done.yielding_walls)
      {
        const lumped::ContactResult &c = r.contacts.at(w.contact);
        run.wall_peak_resistance       = std::max(run.wall_peak_resistance, c.peak_resistance);
        run.peak_wall_displacement     = std::max(run.peak_wall_displacement, c.peak_deformation);
        run.wall_residual_displacement =
          std::max(run.wall_residual_displacement, c.permanent_indentation);
        run.wall_plastic_work += c.plastic_work;
        run.wall_radiated_work += c.radiated_work;
        if (c.failure_time && (!run.wall_failed || *c.failure_time < run.wall_failure_time))
        {
          run.wall_failed       = true;
          run.wall_failure_time = *c.failure_time;
        }
      }
      run.energy_error = r.energy.max_relative_error;
      run.energy_input = r.energy.input;
    }

    /// w's wall-and-backfill terms from the height's pushover and its fit; on failure w keeps
    /// the estimate and says why (source, source_reason, one warning).
    void apply_pushover(const StudyScene &scene, StudyYieldingWall &w)
    {
      const PushoverResistance r = pushover_resistance(scene.fem, w.wall_height, w.inputs);
      w.source                   = r.source;
      w.source_reason            = r.reason;
      w.fit                      = r.fit;
      w.pushover_curve           = r.curve;
      w.pushover_seconds         = r.seconds;
      w.pushover_cells           = r.cells;
      if (r.source != "pushover")
      {
        logger().warn("{}: yielding wall element from the capacity estimate ({} kN/m, cracked "
                      "cantilever): {}",
                      w.name,
                      base::sig(w.estimate_capacity / 1e3),
                      w.source_reason);
        return;
      }
      logger().info("{}: pushover ({} cells, {} s): largest force {} kN/m at {} mm; equal-energy "
                    "bilinear F_y {} kN/m (estimate {}), k {} kN/mm/m, alpha {}, k_ur {} kN/mm/m{}",
                    w.name,
                    w.pushover_cells,
                    base::sig(w.pushover_seconds),
                    base::sig(w.fit.target_force / 1e3),
                    base::sig(w.fit.target_displacement * 1e3),
                    base::sig(w.fit.capacity / 1e3),
                    base::sig(w.estimate_capacity / 1e3),
                    base::sig(w.fit.stiffness / 1e6),
                    base::sig(w.fit.hardening_ratio),
                    base::sig(w.fit.unloading_stiffness / 1e6),
                    w.fit.note.empty() ? std::string() : " (" + w.fit.note + ")");
    }

    /// w's radiation dashpot fitted to the slab travel of the height's FEM record at the
    /// reference velocity (fit_radiation_damping(): the one parameter of the element fitted to
    /// the dynamic FEM, docs/validation.md "Yielding wall element against the dynamic FEM"), for
    /// an element of the FEM's own slab (mass, impedance); without a record's travel w keeps
    /// rho c_p H_b, and says so. The reason joins source_reason.
    void fit_dashpot(const StudyScene &scene, const StudyHeight &h, StudyYieldingWall &w)
    {
      const io::FemCase &fem    = h.fem_case;
      const auto         travel = fem.summary.max_slab_displacement;
      if (!travel || !(*travel > 0.0) || !(fem.slab_mass > 0.0) || !(fem.impact_velocity > 0.0) ||
          fem.time.empty())
      {
        const std::string reason = "radiation dashpot not fitted (the height's FEM record has no "
                                   "slab travel): rho c_p H_b kept, about ten times the fitted "
                                   "dashpots of docs/validation.md";
        w.source_reason += (w.source_reason.empty() ? "" : "; ") + reason;
        logger().warn("{}: {}", w.name, reason);
        return;
      }
      YieldingWallInputs in = w.inputs;
      in.striker_mass       = fem.slab_mass;
      if (scene.fem.solver.rigid_slab)
        in.slab_impedance = std::numeric_limits<double>::infinity();
      const YieldingWallElement e   = derive_yielding_wall(in, 1.0);
      const double              end = std::max(0.05, 2.0 * fem.time.back());
      const DashpotFit          fit = fit_radiation_damping(e,
                                                   fem.slab_mass,
                                                   fem.impact_velocity,
                                                   *travel,
                                                   e.radiation_damping,
                                                   end,
                                                   1e-6);
      w.element                     = with_radiation_damping(w.element, fit.damping);
      const std::string reason =
        fmt::format("radiation dashpot {} kN*s/m^2 fitted to the FEM slab's travel {} mm at {} "
                    "m/s (rho c_p H_b = {}){}",
                    base::sig(fit.damping / 1e3),
                    base::sig(*travel * 1e3),
                    base::sig(fem.impact_velocity),
                    base::sig(e.radiation_damping / 1e3),
                    fit.note.empty() ? std::string() : ": " + fit.note);
      w.source_reason += (w.source_reason.empty() ? "" : "; ") + reason;
      if (fit.damping >= e.radiation_damping) // the bound, not a fit
        logger().warn("{}: {}", w.name, reason);
      else
        logger().info("{}: {}", w.name, reason);
    }

    /// Why a linear study's element is the estimate: it has no inelastic FE model to push.
    constexpr const char *linear_study_reason =
      "linear study: the estimate element beside the linear springs (capacity (M_p + P_p H/3)/h_c "
      "from the section and Rankine's passive resistance, cracked cantilever 3(EI/2)/h_c^3, "
      "radiation dashpot rho c_p H_b; no FEM pushover, no dashpot fitted)";
  } // namespace

  std::vector<StudyYieldingWall>
  derive_study_yielding_walls(const StudyScene &scene, const std::vector<StudyHeight> &heights)
  {
    std::vector<StudyYieldingWall> walls;
    const double                   striker   = scene.building.isolation_mass / scene.fit.width;
    const bool                     inelastic = has_inelastic_materials(scene.fem);
    for (const StudyHeight &h : heights)
    {
      StudyYieldingWall w;
      w.wall_height = h.wall_height;
      w.name        = h.name;
      try
      {
        w.inputs            = yielding_wall_inputs(scene.fem, h.wall_height, striker);
        w.estimate_capacity = w.inputs.capacity;
        if (inelastic)
          apply_pushover(scene, w);
        else
          w.source_reason = linear_study_reason;
        w.element = derive_yielding_wall(w.inputs, scene.fit.width);
        if (h.inelastic)
          fit_dashpot(scene, h, w);
        logger().info(
          "{}: yielding wall element per metre: capacity {} kN/m, cracked stiffness "
          "{} kN/mm/m, radiation dashpot {} kN*s/m^2 (rho c = {} kg/m^3 x {} m/s "
          "over {} m: {} kN*s/m^2), contact k_c = Z_c^2/m_red = {} kN/mm/m (Z_c {} kN*s/m^2), "
          "wall mass {} t/m",
          h.name,
          base::sig(w.inputs.capacity / 1e3),
          base::sig(w.inputs.stiffness / 1e6),
          base::sig(w.element.radiation_damping / 1e3),
          base::sig(w.inputs.soil_density),
          base::sig(w.inputs.soil_wave_speed),
          base::sig(w.inputs.loaded_height),
          base::sig(w.inputs.soil_density * w.inputs.soil_wave_speed * w.inputs.loaded_height /
                    1e3),
          base::sig(w.element.contact_stiffness / 1e6),
          base::sig(w.element.contact_impedance / 1e3),
          base::sig(w.element.wall_mass / 1e3));
      }
      catch (const std::exception &error)
      {
        w.status = "failed: " + base::error_text(error);
        logger().warn("{}: yielding wall element {}", h.name, w.status);
      }
      walls.push_back(w);
    }
    return walls;
  }

  YieldingWallCase run_yielding_wall_case(const StudyScene                     &scene,
                                          const RecordRun                      &record,
                                          const StudyHeight                    &h,
                                          const std::vector<StudyYieldingWall> &yielding)
  {
    YieldingWallCase  out;
    StudyBuildingRun &run      = out.run;
    run.record                 = record.label;
    run.wall_height            = h.wall_height;
    run.law                    = "yielding_wall";
    run.gap                    = record.gap;
    run.yielding_wall          = true;
    const StudyYieldingWall *w = element_of(yielding, h.wall_height);
    if (!w || !w->ok())
    {
      run.status = "skipped: no yielding wall element for " + h.name;
      return out;
    }
    run.k_total                 = w->element.contact_stiffness * scene.fit.width;
    run.exponent                = 1.0;
    run.wall_source             = w->source;
    run.wall_capacity_per_metre = w->element.backfill.capacity_per_metre();
    run.wall_capacity           = run.wall_capacity_per_metre * scene.fit.width;
    const LumpedCaseResult done =
      run_lumped_case(h.name + "_yielding_wall",
                      yielding_walled_scene(record.base, record.gap, w->element),
                      record.motion,
                      record.scale);
    out.ran      = true;
    out.adaptive = done.adaptive;
    fill_building_peaks(run, done, scene.building.n_storeys, nullptr);
    if (!done.ok())
    {
      logger().warn("record {} {} yielding wall: {}", record.label, h.name, done.status);
      return out;
    }
    fill_wall_values(run, done);
    // Amplification against the run without walls (two more DOFs: the walls').
    const lumped::Response &none  = record.without_walls;
    const auto              ratio = [](double a, double b) { return a / std::max(b, 1e-300); };
    const unsigned int      top   = scene.building.n_storeys;
    run.amplification_base_acc =
      ratio(run.base_acceleration, none.peak_absolute_acceleration.at(0));
    run.amplification_top_acc =
      ratio(run.top_acceleration, none.peak_absolute_acceleration.at(top));
    run.amplification_drift = ratio(run.max_interstorey_drift, none.max_interstorey_drift());
    return out;
  }

  std::vector<YieldingWallCase>
  run_yielding_wall_cases(const StudyScene                     &scene,
                          const std::vector<RecordContext>     &records,
                          const std::vector<StudyHeight>       &heights,
                          const std::vector<StudyYieldingWall> &yielding,
                          const std::function<void()>          &beside)
  {
    const std::size_t             n = records.size() * heights.size();
    std::vector<YieldingWallCase> cases(n);
    const auto                    work = [&](std::size_t i)
    {
      const RecordContext &record = records[i / heights.size()];
      const StudyHeight   &h      = heights[i % heights.size()];
      try
      {
        cases[i] = run_yielding_wall_case(scene, record.record(), h, yielding);
      }
      catch (const std::exception &error)
      {
        cases[i].run.record        = record.label;
        cases[i].run.wall_height   = h.wall_height;
        cases[i].run.law           = "yielding_wall";
        cases[i].run.gap           = record.gap;
        cases[i].run.yielding_wall = true;
        cases[i].run.status        = "failed: " + base::error_text(error);
        logger().warn("record {} {} yielding wall: {}", record.label, h.name, cases[i].run.status);
      }
      return true;
    };
    const std::size_t cores = std::max(1U, std::thread::hardware_concurrency());
    base::for_each_index(n, std::min(cores, n), work, beside);
    return cases;
  }

  void log_yielding_walls(const std::vector<StudyBuildingRun> &runs, const std::string &what)
  {
    std::size_t             n = 0, n_failed = 0;
    const StudyBuildingRun *worst = nullptr;
    for (const StudyBuildingRun &r : runs)
    {
      if (!r.yielding_wall || r.status != "ok")
        continue;
      ++n;
      n_failed += r.wall_failed ? 1 : 0;
      if (!worst || r.peak_wall_displacement > worst->peak_wall_displacement)
        worst = &r;
    }
    if (!worst)
      return;
    const std::string text = fmt::format(
      "{}: {} of {} building runs fail a wall (pushed past 10 % of H); largest wall "
      "displacement {} cm (residual {} cm, peak resistance {} of the capacity {} MN), record {}, "
      "H = {} m (yielding_wall.csv)",
      what,
      n_failed,
      n,
      base::sig(100.0 * worst->peak_wall_displacement),
      base::sig(100.0 * worst->wall_residual_displacement),
      base::sig(worst->wall_peak_resistance / worst->wall_capacity),
      base::sig(worst->wall_capacity / 1e6),
      worst->record,
      base::sig(worst->wall_height));
    if (n_failed > 0)
      logger().warn("{}", text);
    else
      logger().info("{}", text);
  }
} // namespace kimp::app::study_internal
