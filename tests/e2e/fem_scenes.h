// The small FEM scenes of the end-to-end tests, as YAML: the quick `kimp fem` scene (one wall
// height, a coarse mesh) and the reduced `kimp study` (a coarse mesh, a rigid slab, 40 ms of
// contact and one short synthetic record, so that a whole study runs in seconds); and `kimp study`
// run on it.
#pragma once

#include <filesystem>
#include <string>

#include "tests/support/files.h"
#include "tests/support/kimp_run.h"

namespace kimp::testing
{
  /// The quick FEM scene: H = 1.25 m, contact elements of 5 cm (at most 25 cm, grading 1.5), a
  /// rigid slab (or not), then the lines `extra`.
  inline std::string quick_fem_scene(const std::string &extra = "", bool rigid = true)
  {
    return std::string("wall_heights: [\"1.25 m\"]\n"
                       "mesh: {h_contact: \"5 cm\", h_max: \"25 cm\", grading: 1.5}\n") +
           (rigid ? "slab: {rigid: true}\n" : "slab: {rigid: false}\n") + extra;
  }

  /// Lines under `fem:`: a rigid slab, 40 ms of contact sampled every 0.02 ms.
  inline const std::string rigid_slab_40_ms = R"(  slab:
    rigid: true
  dynamics:
    end_time: "40 ms"
    output_interval: "0.02 ms"
)";

  /// Top-level lines: one 8 s synthetic record, contact phases separated by up to 10 times their
  /// duration merged (the rigid slab chatters on the wall), no PEER records.
  inline const std::string one_short_record = R"(records:
  - record: synthetic
    duration: "8 s"
fit:
  separation_fraction: 10
peer_records: false
)";

  /**
   * The reduced study: `wall_heights` (a YAML list), contact elements of 5 cm (at most 25 cm,
   * grading 1.5), rigid_slab_40_ms, fidelity fixed, then the lines `fem_extra` under `fem:`;
   * one_short_record; charts if `charts`, no stability map, no accuracy study.
   */
  inline std::string reduced_study(const std::string &wall_heights = R"(["1.0 m", "2.0 m"])",
                                   const std::string &fem_extra    = "",
                                   bool               charts       = false)
  {
    return "fem:\n  wall_heights: " + wall_heights + "\n" + R"(  mesh:
    h_contact: "5 cm"
    h_max: "25 cm"
    grading: 1.5
)" + rigid_slab_40_ms +
           "  fidelity: fixed\n" + fem_extra + one_short_record +
           "charts: " + (charts ? "true" : "false") +
           "\nstability_map: false\naccuracy_study: false\n";
  }

  /// `kimp study study.yaml -o out` in `dir`, `study` written to study.yaml first.
  inline KimpRun run_study(const std::string &study, const std::filesystem::path &dir)
  {
    write_text(dir / "study.yaml", study);
    return run_kimp("study study.yaml -o out", dir);
  }
} // namespace kimp::testing
