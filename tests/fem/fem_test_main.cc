// main() of the kimp::fem test executables: MPI, p4est and Trilinos through MpiSession; only
// rank 0 prints the GoogleTest results.
#include <gtest/gtest.h>

#include "fem/mpi_session.h"

int main(int argc, char **argv)
{
  const kimp::fem::MpiSession mpi(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (mpi.rank() != 0)
  {
    auto &listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  return RUN_ALL_TESTS();
}
