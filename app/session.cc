// Process runtime of kimp; see session.h.
#include "app/session.h"

#ifdef KIMP_WITH_FEM
#  include "fem/mpi_session.h"
#endif

namespace kimp::app
{
  struct Session::Impl
  {
#ifdef KIMP_WITH_FEM
    Impl(int &argc, char **&argv)
      : mpi(argc, argv)
    {
    }
    fem::MpiSession mpi;
#else
    Impl(int &, char **&) {}
#endif
  };

  Session::Session(int &argc, char **&argv)
    : impl(std::make_unique<Impl>(argc, argv))
  {
  }

  Session::~Session() = default;

  unsigned int Session::rank() const
  {
#ifdef KIMP_WITH_FEM
    return impl->mpi.rank();
#else
    return 0;
#endif
  }
} // namespace kimp::app
