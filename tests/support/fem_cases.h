// kimp::testing::write_fem_cases(): a results file of FEM cases, as `kimp fem` writes it, for the
// tests that read one back (the FEM results reader, `kimp fit`). Only for targets linking
// kimp::io.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/fem_results.h"
#include "io/results_file.h"

namespace kimp::testing
{
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
