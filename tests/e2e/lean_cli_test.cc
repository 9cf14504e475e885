// The lean `kimp` beside kimp-fem loads neither MPI nor the parallel HDF5 (its start-up is a few
// milliseconds), while kimp-fem loads exactly one HDF5 library, deal.II's. The dynamic loader
// lists what each executable would load (LD_TRACE_LOADED_OBJECTS, as ldd does) without running it.
#ifdef KIMP_WITH_FEM

#  include <filesystem>
#  include <gtest/gtest.h>
#  include <string>

#  include "tests/support/files.h"
#  include "tests/support/kimp_run.h"
#  include "tests/support/temp_dir.h"

namespace
{
  namespace fs = std::filesystem;
  using namespace kimp::testing;

  /// The shared libraries `executable` loads, one per line, as the dynamic loader lists them.
  std::string loaded_libraries(const fs::path &executable, const fs::path &dir)
  {
    const fs::path listing = dir / (executable.filename().string() + ".libraries");
    EXPECT_EQ(run_command("LD_TRACE_LOADED_OBJECTS=1 '" + executable.string() + "'", listing), 0)
      << read_text(listing);
    return read_text(listing);
  }

  TEST(LeanCli, KimpLoadsNoMpiAndKimpFemOneHdf5)
  {
    const TempDir     dir("e2e_lean");
    const fs::path    kimp = kimp_executable();
    const std::string lean = loaded_libraries(kimp, dir.path());
    ASSERT_NE(lean.find("libc.so"), std::string::npos) << lean;
    EXPECT_EQ(lean.find("libmpi"), std::string::npos) << lean;
    EXPECT_EQ(lean.find("openmpi"), std::string::npos) << lean;
    EXPECT_EQ(lean.find("libdeal"), std::string::npos) << lean;

    const std::string fem = loaded_libraries(kimp.parent_path() / "kimp-fem", dir.path());
    EXPECT_NE(fem.find("libhdf5_openmpi"), std::string::npos) << fem;
    EXPECT_EQ(fem.find("libhdf5_serial"), std::string::npos) << "two HDF5 libraries\n" << fem;
  }
} // namespace

#endif
