// One route to k: a small FEM result (`kimp fem`, rigid slab, coarse mesh) fitted by `kimp fit`
// and through the study's path (app::fit_study_laws) gives the same k to 1e-9 and the same
// status, with the default configuration and with flags equal to the study keys; a bad flag is
// refused like the scene key. Then `kimp export-opensees` turns explicit k into OpenSees input.
#ifdef KIMP_WITH_FEM

#  include <cmath>
#  include <filesystem>
#  include <gtest/gtest.h>
#  include <string>
#  include <vector>

#  include "app/study/study_fem.h"
#  include "io/fem_results.h"
#  include "tests/e2e/fem_scenes.h"
#  include "tests/support/files.h"
#  include "tests/support/hdf5_reader.h"
#  include "tests/support/kimp_run.h"
#  include "tests/support/temp_dir.h"

namespace
{
  using namespace kimp::testing;

  /// Same FEM result, same fitting code and configuration: only the HDF5 round trip of the
  /// double k (exact) separates the two routes.
  constexpr double same_k = 1e-9;

  /// `kimp fit` on `fem_file` with `flags` against fit_study_laws with `config`, case by case.
  void expect_same_k(const std::filesystem::path &dir,
                     const std::string           &flags,
                     const kimp::fit::FitConfig  &config,
                     const std::string           &out)
  {
    const KimpRun fit = run_kimp("-q fit fem/fem.h5 -o " + out + " " + flags, dir);
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const Hdf5Reader h5(dir / out / "fit.h5");
    ASSERT_TRUE(h5.ok());
    const auto cases = kimp::io::read_fem_cases(dir / "fem" / "fem.h5");
    ASSERT_FALSE(cases.empty());
    for (const auto &fem_case : cases)
    {
      const kimp::app::StudyFits study = kimp::app::fit_study_laws(fem_case, config);
      for (const kimp::app::StudyLawFit &law : study.laws)
      {
        const std::string group = "/fit/" + fem_case.name + "/" + law.law->fit_variant();
        EXPECT_EQ(h5.attribute(group, "status"), law.status) << group << " " << flags;
        if (!law.fit)
          continue;
        const double k_study = law.fit->stiffness.value;
        const double k_fit   = h5.doubles(group + "/stiffness").at(0);
        EXPECT_NEAR(k_fit, k_study, same_k * k_study) << group << " " << flags;
      }
    }
  }

  TEST(RouteCli, FitAndStudyGiveTheSameKOnOneFemResult)
  {
    const TempDir dir("route_cli");
    dir.write("scene.yaml",
              quick_fem_scene("dynamics: {end_time: \"40 ms\", output_interval: \"0.02 ms\"}\n"));
    const KimpRun fem = run_kimp("-q fem scene.yaml -o fem", dir.path());
    ASSERT_EQ(fem.exit_code, 0) << fem.err;

    expect_same_k(dir.path(), "", kimp::fit::FitConfig{}, "fit_default");

    kimp::fit::FitConfig merged;
    merged.separation_fraction = 10.0;
    merged.cor                 = 0.6;
    merged.width               = 30.0;
    expect_same_k(dir.path(),
                  "--separation-fraction 10 --cor 0.6 --width \"30 m\"",
                  merged,
                  "fit_merged");

    kimp::fit::FitConfig by_indentation;
    by_indentation.force_only_contact  = false;
    by_indentation.separation_fraction = 0.25;
    expect_same_k(dir.path(),
                  "--force-only-contact=false --separation-fraction 0.25",
                  by_indentation,
                  "fit_indentation");

    const KimpRun bad = run_kimp("-q fit fem/fem.h5 -o bad --separation-fraction -1", dir.path());
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.err.find("separation_fraction = -1"), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "bad"));
  }

  TEST(RouteCli, ExportOpenSeesWritesTclAndPythonWithUnits)
  {
    const TempDir dir("route_opensees");
    const KimpRun run =
      run_kimp("-q export-opensees -o os --k-kv \"2496 kN/mm\" --k-hertz "
               "\"1018 kN/mm^1.5\" --cor 0.7 --gap \"15 cm\" --effective-mass \"195 t\"",
               dir.path());
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::string tcl = read_text(dir.path() / "os" / "opensees_impact.tcl");
    EXPECT_NE(tcl.find("# Units: N, m, s"), std::string::npos) << tcl;
    EXPECT_NE(tcl.find("uniaxialMaterial ViscoelasticGap 1 2496000000 "), std::string::npos) << tcl;
    EXPECT_NE(tcl.find("uniaxialMaterial ImpactMaterial 5 "), std::string::npos) << tcl;
    const std::string py = read_text(dir.path() / "os" / "opensees_impact.py");
    EXPECT_NE(py.find("ops.uniaxialMaterial('JankowskiImpact', 3, "), std::string::npos) << py;

    const KimpRun none = run_kimp("-q export-opensees -o none", dir.path());
    EXPECT_EQ(none.exit_code, 1);
    EXPECT_NE(none.err.find("no k given"), std::string::npos) << none.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "none"));
  }
} // namespace

#endif
