// Impact law 1, linear elastic spring: F = k·δ for δ > 0 (thesis eq. 2.4; Maison & Kasai 1990,
// Anagnostopoulos 1988 without the dashpot). Conservative: an impact returns all energy (COR = 1).
#pragma once

#include <string>

#include "lumped/laws/contact_law.h"

namespace kimp::lumped
{
  /// Parameters of the LinearElasticLaw.
  struct LinearElasticParams
  {
    double stiffness = 0.0; ///< k, N/m
  };

  /**
   * Linear elastic contact spring.
   *
   * | parameter | meaning           | unit | range |
   * |-----------|-------------------|------|-------|
   * | k         | contact stiffness | N/m  | > 0   |
   *
   * Limitation: no energy loss, so the impact is perfectly elastic whatever the materials.
   */
  class LinearElasticLaw final : public ContactLaw<LinearElasticLaw, LinearElasticParams>
  {
  public:
    static constexpr const char *law_name = "linear";

    /// @throws std::invalid_argument if k <= 0.
    explicit LinearElasticLaw(const Params &params);

    /// k (N/m) whatever the deformation.
    double stability_stiffness(double /*max_deformation*/) const override
    {
      return params_.stiffness;
    }

    /// The law itself, called by ContactLaw::set_trial (see there for the contract).
    void evaluate(const ContactState &committed, ContactState &trial) const;
  };
} // namespace kimp::lumped
