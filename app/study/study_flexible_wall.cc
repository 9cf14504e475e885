// Compute stage of `kimp study`'s flexible wall (docs/physics.md §4 "Wall SDOF"): each height's
// wall + backfill as a SDOF from its FE model (fem::wall_sdof), then the building against it.
#include "app/study/study_flexible_wall.h"

#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "app/fem/fem_common.h"
#include "app/fem/mesh_run.h"
#include "app/lumped/lumped_run.h"
#include "app/study/study_fem.h"
#include "app/study/study_internal.h"
#include "base/errors.h"
#include "base/format.h"
#include "base/logging.h"
#include "fem/wall_sdof.h"
#include "geometry/scene_ids.h"
#include "geometry/scene_mesh.h"

namespace kimp::app
{
  LumpedScene flexible_wall_scene(const LumpedScene &rigid, const StudyWallSdof &sdof)
  {
    LumpedScene s = rigid;
    for (WallScene *wall : {&s.walls.left, &s.walls.right})
    {
      wall->flexible  = true;
      wall->stiffness = sdof.stiffness;
      // The SDOF's mass gives the wall its inertia; the laws keep the wall mass of the rigid
      // run in their m_eff (walls.mass), so that both runs have the same dashpot constant.
      wall->sdof_mass     = sdof.mass;
      wall->damping_ratio = sdof.damping_ratio;
    }
    return s;
  }
} // namespace kimp::app

namespace kimp::app::study_internal
{
  StudyWallSdof
  compute_wall_sdof(const StudyScene &scene, const StudyHeight &h, const OutputDir &output)
  {
    const auto    start = Clock::now();
    StudyWallSdof sdof;
    sdof.wall_height   = h.wall_height;
    sdof.name          = h.name;
    sdof.damping_ratio = scene.walls.damping_ratio;
    sdof.h_contact     = used_h_contact(scene, h);
    try
    {
      // The mesh of the FEM level the height used, without the slab: the wall and backfill the
      // impact saw, loaded over the slab's band.
      const std::string name = h.name + "_wall_sdof";
      FemCaseSpec       spec =
        study_fem_case_spec(fem_level_scene(scene.fem, sdof.h_contact, used_penalty(scene, h)),
                            h.wall_height,
                            output,
                            name);
      spec.geometry.mesh_slab = false;
      std::filesystem::create_directories(spec.mesh_file.parent_path());
      write_scene_mesh(spec.geometry, spec.mesh_file);
      fem::WallSdofParameters p;
      p.mesh_file = spec.mesh_file;
      p.materials = spec.parameters.materials;
      p.materials.erase(geometry::slab_material);
      p.band_y0                         = spec.geometry.slab_bottom();
      p.band_y1                         = spec.geometry.resolved_slab_top();
      const fem::WallSdof fe            = fem::wall_sdof(p);
      sdof.stiffness_per_metre          = fe.static_stiffness;
      sdof.participation_mass_per_metre = fe.effective_mass;
      sdof.modal_sum_mass_per_metre     = fe.modal_sum_mass;
      sdof.mode                         = fe.mode;
      sdof.mode_frequency               = fe.mode_frequency;
      sdof.mode_share                   = fe.mode_share;
      sdof.mode_mass_per_metre          = fe.mode_mass;
      sdof.total_mass_per_metre         = fe.total_mass;
      sdof.n_dofs                       = fe.n_dofs;
      sdof.mass_per_metre =
        scene.walls.flexible_mass == WallSdofMass::mode ? fe.mode_mass : fe.effective_mass;
      sdof.frequency = std::sqrt(fe.static_stiffness / sdof.mass_per_metre) / (2 * M_PI);
      sdof.stiffness = fe.static_stiffness * scene.fit.width;
      sdof.mass      = sdof.mass_per_metre * scene.fit.width;
      for (const fem::WallMode &m : fe.modes)
      {
        sdof.mode_frequencies.push_back(m.frequency);
        sdof.mode_shares.push_back(m.share);
      }
      if (scene.walls.flexible_mass == WallSdofMass::mode && fe.mode_share < 0.5)
        logger().warn("{}: the wall's mode of the largest share ({} Hz) carries only {} % of "
                      "the static deflection at the slab; its SDOF is a rough model",
                      h.name,
                      base::sig(fe.mode_frequency),
                      base::sig(100 * fe.mode_share, 3));
    }
    catch (const std::exception &error)
    {
      sdof.status = "failed: " + error_message(error);
      logger().warn("{}: wall SDOF {}", h.name, sdof.status);
    }
    sdof.seconds = seconds_since(start);
    if (sdof.ok())
      logger().info("{}: wall SDOF k = {} MN/m/m, m = {} t/m, f = {} Hz (largest mode share: "
                    "mode {} of {} at {} Hz, {} % of the static deflection; wall + backfill {} "
                    "t/m); x W: k = {} MN/m, m = {} t; {} DoFs, {} s",
                    h.name,
                    base::sig(sdof.stiffness_per_metre / 1e6),
                    base::sig(sdof.mass_per_metre / 1e3),
                    base::sig(sdof.frequency),
                    sdof.mode + 1,
                    sdof.mode_frequencies.size(),
                    base::sig(sdof.mode_frequency),
                    base::sig(100 * sdof.mode_share, 3),
                    base::sig(sdof.total_mass_per_metre / 1e3),
                    base::sig(sdof.stiffness / 1e6),
                    base::sig(sdof.mass / 1e3),
                    sdof.n_dofs,
                    base::sig(sdof.seconds, 2));
    return sdof;
  }

  std::vector<StudyWallSdof> compute_wall_sdofs(const StudyScene               &scene,
                                                const std::vector<StudyHeight> &heights,
                                                const OutputDir                &output)
  {
    std::vector<StudyWallSdof> sdofs;
    for (const StudyHeight &h : heights)
      sdofs.push_back(compute_wall_sdof(scene, h, output));
    return sdofs;
  }

  std::vector<StudyBuildingRun>
  run_flexible_wall_building(const StudyScene                    &scene,
                             const std::vector<StudyHeight>      &heights,
                             const std::vector<StudyWallSdof>    &sdofs,
                             const std::vector<StudyBuildingRun> &rigid)
  {
    std::vector<StudyBuildingRun>        runs;
    const unsigned int                   top_dof = scene.building.n_storeys;
    const std::vector<GroundMotionScene> records = study_records(scene);
    // run_building() writes one row without walls per record, in the order of study_records().
    std::vector<const StudyBuildingRun *> bare;
    for (const StudyBuildingRun &r : rigid)
      if (r.law == "none")
        bare.push_back(&r);
    for (std::size_t i = 0; i < records.size() && i < bare.size(); ++i)
    {
      const StudyBuildingRun &none = *bare[i];
      if (none.status != "ok")
        continue;
      lumped::GroundMotion motion;
      try
      {
        motion = load_ground_motion(records[i]);
      }
      catch (const std::exception &error)
      {
        logger().warn("record {}: {}", none.record, base::error_text(error));
        continue;
      }
      const LumpedScene base = study_lumped_scene(scene, records[i]);
      const double      gap  = wall_gap(scene, none.base_displacement);
      for (std::size_t j = 0; j < heights.size() && j < sdofs.size(); ++j)
      {
        const StudyHeight   &h    = heights[j];
        const StudyWallSdof &sdof = sdofs[j];
        for (const auto &[law, fit] : building_laws(h))
        {
          StudyBuildingRun run;
          run.record        = none.record;
          run.wall_height   = h.wall_height;
          run.law           = law;
          run.gap           = gap;
          run.flexible_wall = true;
          if (!*fit || !sdof.ok())
          {
            run.status =
              !*fit ? "skipped: no fitted k for " + h.name : "skipped: no wall SDOF for " + h.name;
            runs.push_back(run);
            continue;
          }
          // The rigid run's scene (run_building()), then both walls flexible.
          run.exponent                = (*fit)->exponent.value;
          run.k_total                 = (*fit)->stiffness.value * scene.fit.width;
          const LumpedScene      s    = walled_scene(base, gap, law, run.k_total, scene.fit.cor);
          const LumpedCaseResult done = run_lumped_case(h.name + "_" + law + "_flexible_wall",
                                                        flexible_wall_scene(s, sdof),
                                                        motion,
                                                        records[i].scale);
          fill_building_peaks(run, done, top_dof, nullptr);
          if (done.ok())
          {
            // Amplification against the run without walls, from its row (the flexible run has
            // two more DOFs than it, so lumped::amplification_factors() does not apply).
            const auto ratio           = [](double a, double b) { return a / std::max(b, 1e-300); };
            run.amplification_base_acc = ratio(run.base_acceleration, none.base_acceleration);
            run.amplification_top_acc  = ratio(run.top_acceleration, none.top_acceleration);
            run.amplification_drift = ratio(run.max_interstorey_drift, none.max_interstorey_drift);
            const std::size_t n     = done.response.peak_displacement.size();
            run.peak_wall_displacement = std::max(done.response.peak_displacement.at(n - 1),
                                                  done.response.peak_displacement.at(n - 2));
            run.energy_error           = done.response.energy.max_relative_error;
          }
          else
            logger().warn("record {} {} {} flexible wall: {}",
                          none.record,
                          h.name,
                          law,
                          done.status);
          runs.push_back(run);
        }
      }
    }
    return runs;
  }
} // namespace kimp::app::study_internal
