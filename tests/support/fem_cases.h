// kimp::testing::write_fem_cases(): a results file of FEM cases, as `kimp fem` writes it, for the
// tests that read one back (the FEM results reader, `kimp fit`); add_sample(): one sample of a
// synthetic FEM record. Only for targets linking kimp::io.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/fem_results.h"
#include "io/results_file.h"

namespace kimp::testing
{
  /// Appends one sample of a synthetic record, unsmoothed (its smoothed force is the force): time
  /// t (s), contact force (N/m) and slab displacement (m); the caller adds the other series.
  inline void add_sample(io::FemCase &c, double t, double force, double slab_displacement)
  {
    c.time.push_back(t);
    c.contact_force.push_back(force);
    c.smoothed_contact_force.push_back(force);
    c.slab_displacement.push_back(slab_displacement);
  }

  /// Writes `cases` under /fem of a new results file `path` whose scene text is `scene`.
  inline void write_fem_cases(const std::filesystem::path    &path,
                              const std::vector<io::FemCase> &cases,
                              const std::string              &scene = "")
  {
    io::ResultsFile file(path, scene, "{}");
    auto            root = file.root();
    auto            fem  = root.group("fem");
    for (const auto &c : cases)
      io::write_fem_case(fem, c);
    file.commit();
  }
} // namespace kimp::testing
