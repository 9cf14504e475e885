// main() of the kimp::fem test executables: MPI, p4est and Trilinos through MpiSession; only
// rank 0 prints the GoogleTest results. The scratch directory the tests share
// (tests/fem/impact_test_support.h scratch()) goes with the job.
#include <gtest/gtest.h>

#include "fem/mpi_session.h"
#include "tests/support/mpi_temp_dir.h"

int main(int argc, char **argv)
{
  const kimp::fem::MpiSession mpi(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (mpi.rank() != 0)
  {
    auto &listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int result = RUN_ALL_TESTS();
  kimp::testing::remove_shared_temp_dir("fem_test", MPI_COMM_WORLD);
  return result;
}
