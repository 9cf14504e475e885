// Constitutive laws of the plane-strain continuum, sigma = sigma(eps, h), with per-quadrature-point
// history h kept as trial and committed values (step-18's quadrature-point history; the
// trial / commit / revert split of OpenSees' Steel01). No deal.II: Voigt vectors and matrices.
#pragma once

#include <array>
#include <memory>
#include <vector>

namespace kimp::fem
{
  struct Material;

  /** Plane strain in Voigt notation: {eps_xx, eps_yy, gamma_xy = 2 eps_xy} (-). */
  using VoigtStrain = std::array<double, 3>;
  /** {sigma_xx, sigma_yy, sigma_xy} (Pa). */
  using VoigtStress = std::array<double, 3>;
  /** d sigma / d eps (Pa), row-major 3 x 3. */
  using VoigtTangent = std::array<double, 9>;
  /** A plane-strain stress state with its out-of-plane part: {xx, yy, zz, xy} (Pa). */
  using InitialStress = std::array<double, 4>;

  /** The central difference d sigma / d eps of @p stress (VoigtStrain -> VoigtStress) at @p e,
   *  each strain component moved by +-@p step. */
  template <class Stress>
  VoigtTangent central_difference_tangent(Stress &&stress, const VoigtStrain &e, double step)
  {
    VoigtTangent t{};
    for (unsigned int j = 0; j < 3; ++j)
    {
      VoigtStrain ep = e, em = e;
      ep[j] += step;
      em[j] -= step;
      const VoigtStress sp = stress(ep);
      const VoigtStress sm = stress(em);
      for (unsigned int i = 0; i < 3; ++i)
        t[3 * i + j] = (sp[i] - sm[i]) / (2 * step);
    }
    return t;
  }

  /** x with t x = b (t row-major) by Cramer's rule: not finite if t is singular. */
  inline VoigtStrain solve_tangent(const VoigtTangent &t, const VoigtStress &b)
  {
    const auto det = [](const VoigtTangent &m)
    {
      return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
             m[2] * (m[3] * m[7] - m[4] * m[6]);
    };
    const double d0 = det(t);
    VoigtStrain  x{};
    for (unsigned int c = 0; c < 3; ++c)
    {
      VoigtTangent m = t;
      for (unsigned int r = 0; r < 3; ++r)
        m[3 * r + c] = b[r];
      x[c] = det(m) / d0;
    }
    return x;
  }

  /** Per-point quantities for energy bookkeeping and field output. */
  struct PointOutput
  {
    double sigma_zz                  = 0; ///< out-of-plane stress, Pa
    double stored_energy             = 0; ///< recoverable strain energy density, J/m^3
    double plastic_dissipation       = 0; ///< accumulated, J/m^3
    double damage_dissipation        = 0; ///< accumulated, J/m^3
    double damage                    = 0; ///< scalar damage, -
    double equivalent_plastic_strain = 0; ///< -
    /** Smeared bars (ConcreteDamageLaw): their share of sigma_xx and sigma_yy (ratio times the
     *  bar's stress), Pa; the concrete carries the rest of the point's stress. */
    double reinforcement_stress_xx = 0, reinforcement_stress_yy = 0;
    /** Concrete: the tension damage d_t and its crack normal's n_y^2 (the weight cos^2 theta
     *  of the vertical bars in the crack check), -. */
    double tension_damage = 0, crack_normal_yy = 0;
  };

  /**
   * A constitutive law. Evaluation is const and pure: the law reads the committed history of a
   * quadrature point and writes its trial history; QuadraturePointHistory decides what becomes
   * committed (at the end of an accepted time step) and what is thrown away (a rejected Newton
   * attempt or step).
   */
  class MaterialLaw
  {
  public:
    virtual ~MaterialLaw() = default;

    /** Number of history variables per quadrature point (0: no history). */
    virtual unsigned int n_history() const = 0;
    /** Writes the history of the undeformed, virgin state (n_history() values). */
    virtual void initial_history(double *history) const;
    /**
     * Initial history of a point of an element of characteristic length @p h (m; the crack band
     * of softening laws). Default: initial_history().
     */
    virtual void initialize_point(double *history, double h) const;
    /**
     * As initialize_point(), for a point of a cell of height @p height (m, along y) on the
     * clamped base whose bars are anchored in it (a law may model their slip out of it).
     * Default: initialize_point().
     */
    virtual void initialize_anchored_point(double *history, double h, double height) const;
    /**
     * Stress at the total strain @p strain from the @p committed history; writes the history
     * that results to @p trial (both n_history() values; unused when 0).
     */
    virtual VoigtStress
    stress(const VoigtStrain &strain, const double *committed, double *trial) const = 0;
    /** Consistent tangent d sigma / d eps at @p strain from the @p committed history. */
    virtual VoigtTangent tangent(const VoigtStrain &strain, const double *committed) const = 0;
    /**
     * True if stress = tangent : strain with one constant tangent and no history. The impact
     * solver then computes the internal force as K u with K assembled once from the tangent;
     * otherwise it assembles the internal force from stress() at every quadrature point.
     */
    virtual bool is_linear() const { return false; }
    /**
     * Makes @p history (a point's initialized history) that of a point carrying the stress
     * @p sigma0 at zero strain, so that stress() returns sigma0 + the response to the strain
     * (the geostatic initial state). Returns false if the law cannot hold an initial stress
     * (default; the solver then carries it as a constant nodal force, which is exact for a
     * linear law).
     */
    virtual bool set_initial_stress(double *history, const InitialStress &sigma0) const;
    /**
     * Called by a load-stepping solver on the committed history of every point before it solves
     * the next step (and again before a retry of a halved step), with @p step_ratio =
     * increment of the coming step / increment of the last converged one (>= 0; 0: nothing to
     * extrapolate from, e.g. the first step). A law with an IMPL-EX update (Oliver, Huespe &
     * Cante 2008) writes its extrapolated internal variables here; the others ignore it
     * (default). Only the static solver calls it.
     */
    virtual void begin_step(double *committed, double step_ratio) const;
    /**
     * The IMPL-EX error of a point after a converged step, from the @p trial history that
     * stress() wrote at the converged strain: how far the extrapolated internal variables that
     * the step used lag the implicit ones, in units of the law's strength (ConcreteDamageLaw:
     * the tensile stress overshoot / f_t). A load-stepping solver halves a step whose largest
     * error exceeds its tolerance. Default (no IMPL-EX): 0.
     */
    virtual double step_error(const double * /*trial*/) const { return 0; }
    /**
     * Out-of-plane stress, stored energy and dissipation at @p strain with the history
     * @p history that stress() wrote for it. Default: sigma_zz = 0, stored = sigma : eps / 2.
     */
    virtual PointOutput output(const VoigtStrain &strain, const double *history) const;
    /**
     * Batched update of @p n points: for p < n, stress[p] = stress(strain[p], committed + p *
     * stride, trial + p * stride) and energy[p] = {stored, plastic, damage} of output() (J/m^3)
     * with the trial history written; @p energy may be nullptr (the energies are then not
     * computed). One virtual call per batch; the laws override it with their inlined point update
     * (same numbers as the point-wise calls). Default: the point-wise calls.
     */
    virtual void update_points(unsigned int           n,
                               const VoigtStrain     *strain,
                               const double          *committed,
                               double                *trial,
                               unsigned int           stride,
                               VoigtStress           *stress,
                               std::array<double, 3> *energy) const;
  };

  /**
   * The loop of MaterialLaw::update_points() over a law of static type @p Law: for a final Law
   * the compiler binds its stress() and output() statically and inlines them (BatchedLaw); for
   * Law = MaterialLaw they are virtual calls (the default update_points()).
   */
  template <class Law>
  void update_points_of(const Law             &law,
                        unsigned int           n,
                        const VoigtStrain     *strain,
                        const double          *committed,
                        double                *trial,
                        unsigned int           stride,
                        VoigtStress           *stress,
                        std::array<double, 3> *energy)
  {
    for (unsigned int p = 0; p < n; ++p)
    {
      const double *h0 = committed + static_cast<std::size_t>(p) * stride;
      double       *h1 = trial + static_cast<std::size_t>(p) * stride;
      stress[p]        = law.stress(strain[p], h0, h1);
      if (energy != nullptr)
      {
        const PointOutput po = law.output(strain[p], h1);
        energy[p]            = {{po.stored_energy, po.plastic_dissipation, po.damage_dissipation}};
      }
    }
  }

  /**
   * A MaterialLaw of final type Law whose update_points() is the loop update_points_of() over
   * Law's own stress() and output(), bound statically and inlined where Law defines them.
   */
  template <class Law>
  class BatchedLaw : public MaterialLaw
  {
  public:
    void update_points(unsigned int           n,
                       const VoigtStrain     *strain,
                       const double          *committed,
                       double                *trial,
                       unsigned int           stride,
                       VoigtStress           *stress,
                       std::array<double, 3> *energy) const final
    {
      update_points_of(static_cast<const Law &>(*this),
                       n,
                       strain,
                       committed,
                       trial,
                       stride,
                       stress,
                       energy);
    }
  };

  /** Lame constants lambda and mu (Pa) of isotropic elasticity. */
  struct Lame
  {
    double lambda = 0, mu = 0;
  };
  /** lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)) from E (Pa) and nu. */
  inline Lame lame(double E, double nu)
  {
    return {E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))};
  }

  /** Isotropic linear elasticity in plane strain (Lame lambda, mu from E, nu). */
  class LinearElasticLaw final : public BatchedLaw<LinearElasticLaw>
  {
  public:
    explicit LinearElasticLaw(const Material &material);
    unsigned int n_history() const override { return 0; }
    VoigtStress  stress(const VoigtStrain &strain, const double *, double *) const override;
    VoigtTangent tangent(const VoigtStrain &, const double *) const override { return tangent_; }
    bool         is_linear() const override { return true; }
    PointOutput  output(const VoigtStrain &strain, const double *) const override;

  private:
    VoigtTangent tangent_{};
  };

  /**
   * Trial and committed history of every quadrature point, n_values doubles per point, points
   * numbered cell * n_points_per_cell + q. A plain vector rather than deal.II's CellDataStorage:
   * the layout is known, contiguous, and commit / revert are single copies.
   */
  class QuadraturePointHistory
  {
  public:
    /** n_cells x n_points_per_cell points of n_values values each, all zero. */
    void reinit(unsigned int n_cells, unsigned int n_points_per_cell, unsigned int n_values);
    /** Sets the committed and trial history of all points of @p cell to the law's initial one. */
    void initialize_cell(unsigned int cell, const MaterialLaw &law);
    /** As initialize_cell(), for an element of characteristic length @p h (m). */
    void initialize_cell(unsigned int cell, const MaterialLaw &law, double h);
    /** As initialize_cell(), with initialize_anchored_point() for a cell of @p height (m) on
     *  the clamped base (0: not on it). */
    void initialize_cell(unsigned int cell, const MaterialLaw &law, double h, double height);

    const double *committed(unsigned int cell, unsigned int q) const
    {
      return committed_.data() + offset(cell, q);
    }
    /** The committed history, writable: for MaterialLaw::begin_step() between steps. */
    double *committed(unsigned int cell, unsigned int q)
    {
      return committed_.data() + offset(cell, q);
    }
    double *trial(unsigned int cell, unsigned int q) { return trial_.data() + offset(cell, q); }
    const double *trial(unsigned int cell, unsigned int q) const
    {
      return trial_.data() + offset(cell, q);
    }
    /** The trial history becomes the committed one (an accepted time step). */
    void commit() { committed_ = trial_; }
    /**
     * The trial history becomes the committed one by exchanging the two buffers: the trial
     * history is then stale until the next evaluation. For loops that rewrite the trial history
     * of every evaluated point before reading it (the explicit time loop): no copy per step.
     */
    void commit_by_swap() { committed_.swap(trial_); }
    /** The trial history is discarded (a rejected Newton attempt or time step). */
    void         revert() { trial_ = committed_; }
    unsigned int n_values() const { return n_values_; }

  private:
    std::size_t offset(unsigned int cell, unsigned int q) const
    {
      return (static_cast<std::size_t>(cell) * n_points_per_cell_ + q) * n_values_;
    }
    unsigned int        n_points_per_cell_ = 0, n_values_ = 0;
    std::vector<double> committed_, trial_;
  };
} // namespace kimp::fem
