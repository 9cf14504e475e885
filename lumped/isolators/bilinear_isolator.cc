// Bilinear kinematic-hardening isolator: parameter checks and stored energy.
#include "lumped/isolators/bilinear_isolator.h"

#include <cmath>

namespace kimp::lumped
{
  void BilinearParameters::check() const
  {
    require_positive_isolator("K1", K1, "N/m");
    require_isolator_in("K2", K2, 0.0, K1, "N/m", "must be >= 0 and smaller than K1");
    require_positive_isolator("Q", Q, "N");
  }

  BilinearIsolator::BilinearIsolator(const double K1,
                                     const double K2,
                                     const double Q,
                                     const double c)
    : HystereticIsolatorLaw(c)
    , K1_(K1)
    , K2_(K2)
    , Q_(Q)
  {
    BilinearParameters{K1, K2, Q}.check();
    inv_k_ep_ = 1.0 / (K1_ - K2_);
  }
} // namespace kimp::lumped
