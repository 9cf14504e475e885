// Inelastic plane-strain laws behind the MaterialLaw interface: Mohr-Coulomb with tension cut-off
// and Drucker-Prager (soil), scalar tension/compression damage with crack band and smeared steel
// bars (concrete). Plain C++ (no deal.II): allocation-free quadrature-point code that unit tests
// compile in seconds. Soil laws in soil_laws.cc, concrete in concrete_damage_law.cc.
#pragma once

#include <string>
#include <vector>

#include "fem/material_law.h"

namespace kimp::fem
{
  /** Perfectly plastic soil: elasticity and the Mohr-Coulomb strength parameters. */
  struct SoilParameters
  {
    double youngs_modulus = 50e6; ///< E, Pa
    double poisson_ratio  = 0.3;  ///< nu, -
    double density        = 1900; ///< rho, kg/m^3
    double cohesion       = 0;    ///< c, Pa
    double friction_angle = 0;    ///< phi, rad
    double dilatancy      = 0;    ///< psi, rad (<= phi)
    double tension_cutoff = 0;    ///< largest principal stress allowed, Pa (<= c cot phi)
  };

  /** A named soil preset (docs/physics.md gives the sources). */
  struct SoilPreset
  {
    std::string    name;
    SoilParameters parameters;
  };
  /** loose_sand, medium_dense_sand, dense_sand, soft_clay, stiff_clay. */
  const std::vector<SoilPreset> &soil_presets();
  /** The preset named @p name; throws std::invalid_argument listing the names otherwise. */
  const SoilParameters &soil_preset(const std::string &name);

  /** Which surfaces the last return mapping ended on (history value, for tests and output). */
  enum class ReturnType
  {
    elastic = 0,
    main    = 1, ///< one Mohr-Coulomb plane
    edge    = 2, ///< two Mohr-Coulomb planes (triaxial compression or extension edge)
    apex    = 3, ///< three or more planes meet (Mohr-Coulomb apex or tension corner)
    tension = 4, ///< tension cut-off planes only
    mixed   = 5, ///< Mohr-Coulomb plane(s) and tension cut-off plane(s)
    dp_cone = 6,
    dp_apex = 7,
  };

  /**
   * What the perfectly plastic soil laws (Mohr-Coulomb, Drucker-Prager) share: the soil
   * parameters and Lame constants, and a history that starts with the plastic strain {xx, yy,
   * zz, gamma_xy}, the equivalent plastic strain and the plastic dissipation density (J/m^3).
   * `Law` provides, public, the return mapping `update(strain, committed, trial, tangent)`
   * (stress, trial history and, if tangent != nullptr, the consistent tangent), which stress() and
   * tangent() call.
   */
  template <class Law>
  class PlasticSoilLaw : public BatchedLaw<Law>
  {
  public:
    VoigtStress
    stress(const VoigtStrain &strain, const double *committed, double *trial) const override
    {
      return static_cast<const Law &>(*this).update(strain, committed, trial, nullptr);
    }
    VoigtTangent tangent(const VoigtStrain &strain, const double *committed) const override;
    /** sigma_zz and the stored energy of the elastic strain, the plastic history values. */
    PointOutput output(const VoigtStrain &strain, const double *history) const override;
    /** The initial stress enters as an initial elastic strain: the plastic-strain slots start
     *  at -D^-1 sigma0 (the dissipation and equivalent plastic strain stay zero). */
    bool set_initial_stress(double *history, const InitialStress &sigma0) const override;

  protected:
    explicit PlasticSoilLaw(const SoilParameters &p);

    SoilParameters p_;
    double         lambda_, mu_;
  };

  /**
   * Mohr-Coulomb with tension cut-off and non-associated flow (dilatancy psi), perfectly plastic.
   * Implicit (backward Euler) return mapping in principal stresses (in-plane pair and sigma_zz):
   * the 6 Mohr-Coulomb planes and 3 cut-off planes are linear in principal space, so each active
   * set is one small linear solve; the admissible set closest in the energy norm is taken. That
   * covers de Souza Neto, Peric & Owen (2008) Box 8.4's main-plane, left/right edge and apex
   * returns. Consistent tangent from the principal tangent plus the eigenvector spin term.
   * History: plastic strain {xx, yy, zz, gamma_xy}, equivalent plastic strain, plastic
   * dissipation density (J/m^3), return type.
   */
  class MohrCoulombLaw final : public PlasticSoilLaw<MohrCoulombLaw>
  {
  public:
    /** @p exhaustive: search every active set at every plastic point (the oracle of the
     *  tests; the default tries the most violated plane and the point's last set first). */
    explicit MohrCoulombLaw(const SoilParameters &p, bool exhaustive = false);
    /** History: plastic strain {xx, yy, zz, gamma_xy}, equivalent plastic strain, plastic
     *  dissipation, ReturnType of the last update, bit mask of its active set (0: elastic). */
    unsigned int n_history() const override { return 8; }
    /** Largest yield function value (Pa) at principal stresses {s1, s2, s3}. */
    double yield_function(const std::array<double, 3> &principal) const;
    /** The return mapping: stress, trial history and (if tangent != nullptr) the consistent
     *  tangent (PlasticSoilLaw's stress() and tangent() call it). */
    VoigtStress update(const VoigtStrain &strain,
                       const double      *committed,
                       double            *trial,
                       VoigtTangent      *tangent) const;

  private:
    bool exhaustive_;
    /** The 9 planes a.sigma <= b in principal space (6 Mohr-Coulomb, 3 cut-off), their flow
     *  directions' images D g: constants of the law, computed once. */
    double a_[9][3], b_[9], dg_[9][3];
    /** One candidate active set of 1-3 planes with the Gauss elimination of its matrix
     *  M_ij = a_i . D g_j (constant) precomputed, so that a point only replays it on its
     *  right-hand side (the same operations, hence the same numbers, as a fresh elimination). */
    struct ActiveSet
    {
      unsigned int k = 0, idx[3] = {0, 0, 0}, perm[3] = {0, 1, 2};
      unsigned int set = 0; ///< bit mask of the planes
      /// Elimination steps b[op_dst] -= op_f * b[op_src], in order.
      unsigned int n_ops = 0, op_dst[3] = {0, 0, 0}, op_src[3] = {0, 0, 0};
      double       op_f[3] = {0, 0, 0};
      double       upper[3][3]{}; ///< the reduced matrix (rows as stored, used through perm)
    };
    std::vector<ActiveSet> active_sets_; ///< the non-singular sets in ascending mask order
    /// Index in active_sets_ of the set of plane n alone (-1 if singular).
    int single_set_[9] = {-1, -1, -1, -1, -1, -1, -1, -1, -1};
    /// Index in active_sets_ of each bit mask of planes (-1: not a candidate set).
    std::array<int, 512> set_index_;
  };

  /**
   * Drucker-Prager matched to Mohr-Coulomb in plane strain (the plane-strain collapse strength of
   * both is t + m sin(phi) = c cos(phi); with dilatancy eta_bar from psi). Perfectly plastic,
   * cone and apex returns (de Souza Neto et al. 2008 Box 8.8). History as MohrCoulombLaw.
   */
  class DruckerPragerLaw final : public PlasticSoilLaw<DruckerPragerLaw>
  {
  public:
    explicit DruckerPragerLaw(const SoilParameters &p);
    unsigned int n_history() const override { return 7; }
    /** f = sqrt(J2) + eta p - xi c (Pa) at the 3D stress {xx, yy, zz, xy}. */
    double yield_function(const std::array<double, 4> &sigma) const;
    double eta() const { return eta_; }
    double eta_bar() const { return eta_bar_; }
    double xi() const { return xi_; }
    /** The cone and apex returns, as MohrCoulombLaw::update(). */
    VoigtStress update(const VoigtStrain &strain,
                       const double      *committed,
                       double            *trial,
                       VoigtTangent      *tangent) const;

  private:
    double bulk_, eta_, eta_bar_, xi_;
  };

  extern template class PlasticSoilLaw<MohrCoulombLaw>;
  extern template class PlasticSoilLaw<DruckerPragerLaw>;

  /** Concrete parameters; ConcreteParameters::from_f_cm() derives them by fib MC2010. */
  struct ConcreteParameters
  {
    double f_cm            = 38e6; ///< mean cylinder compressive strength, Pa
    double youngs_modulus  = 0;    ///< E_ci, Pa (tangent modulus at the origin)
    double poisson_ratio   = 0.2;  ///< nu, -
    double f_ctm           = 0;    ///< mean tensile strength, Pa
    double fracture_energy = 0;    ///< G_F, N/m
    double eps_c1          = 0;    ///< strain at peak compressive stress (> 0)
    double eps_c_lim       = 0;    ///< nominal ultimate compressive strain (> eps_c1)
    double dif_compression = 1;    ///< dynamic increase factor on f_cm (>= 1)
    double dif_tension     = 1;    ///< dynamic increase factor on f_ctm (>= 1)
    /** b_c: fraction of the compressive inelastic strain that is plastic (irreversible), in
     *  [0, 1); 0: secant unloading to the origin. */
    double plastic_fraction = 0;
    /** d_agg, m: largest aggregate size. The shear retention of a crack falls linearly with its
     *  opening w to shear_retention_floor at w = d_agg / 2 (>= 1 mm). */
    double aggregate_size = 0.016;
    /** beta_min: shear retention of a crack opened wider than d_agg / 2, in [0, 1]. */
    double shear_retention_floor = 0.01;
    /**
     * The crack frame: false, fixed at the point's first crack (shear retention and dowels act
     * in it); true, rotating with the principal directions (coaxial: no shear in the frame, no
     * dowels; the shear goes by the rotated compression). A fixed frame locks tension across
     * the cracks of a wall's plastic hinge (docs/physics.md §6 "Crack frame of the pushover").
     * With IMPL-EX the rotating frame of a step is the converged step's principal direction.
     */
    bool rotating_crack = false;
    /**
     * Crack band in compression, m (0: the local curve at every point). With l_c > 0 the
     * descending branch of compression_curve() past eps_c1 is read at a point of crack band h
     * as that of a crush band of l_c: the strain beyond eps_c1 is scaled by h / l_c, so the
     * energy of crushing per unit area (post-peak energy density times h) is that of the curve
     * over l_c on every mesh, as the tensile crack band keeps G_F (docs/physics.md §6).
     */
    double compression_band = 0;
    /**
     * fib Model Code 2010 §5.1.4-5.1.8 from f_cm (Pa): f_ck = f_cm - 8 MPa,
     * E_ci = 21.5 GPa (f_cm / 10 MPa)^(1/3), f_ctm = 0.3 f_ck^(2/3) (<= C50) or
     * 2.12 ln(1 + 0.1 f_cm), G_F = 73 f_cm^0.18 N/m; eps_c1, eps_c,lim by EN 1992-1-1 Table 3.1.
     */
    static ConcreteParameters from_f_cm(double f_cm);
    /** fib MC2010 §7.2 (5.1-?) dynamic increase factors at the strain rate @p rate (1/s). */
    void apply_strain_rate(double rate);
    /** MC2010 / EN 1992-1-1 eq. 3.14 compressive stress (Pa, > 0) at compressive strain e > 0:
     *  the curve to eps_c_lim, then a linear descent to zero at 2 eps_c_lim. */
    double compression_curve(double e) const;
    /** compression_curve() at a point of crack band @p band (m) with compression_band (the
     *  local curve when either is 0). */
    double compression_curve(double e, double band) const;
  };

  /**
   * Smeared reinforcement of a concrete body: steel bars along x and along y, their area per
   * concrete area ratio_x, ratio_y, perfectly bonded (the bar strain is the concrete's normal
   * strain eps_xx or eps_yy), no tension stiffening; across a crack they add dowel action
   * (ConcreteDamageLaw, docs/physics.md §6).
   */
  struct ReinforcementParameters
  {
    double ratio_x        = 0;     ///< steel area / concrete area of the bars along x, -
    double ratio_y        = 0;     ///< steel area / concrete area of the bars along y, -
    double yield_stress   = 500e6; ///< f_y, Pa (B500)
    double youngs_modulus = 200e9; ///< E_s, Pa
    double hardening      = 0.01;  ///< b = post-yield tangent / E_s, in [0, 1)
    /** k of the dowel strength of one bar across a crack, D_u = k d_b^2 sqrt(f_cm f_y)
     *  (Rasmussen 1963; >= 0, 0: no dowel action). */
    double dowel_coefficient = 1.3;
    /**
     * L_p, m: plastic hinge length over which a yielding bar's plastic elongation is spread
     * (0: off). A point of crack band h then hardens with H h / L_p instead of H, so that the
     * post-yield force of a hinge that localises in one row of cells is that of a hinge of
     * length L_p on every mesh (docs/physics.md §6 "Mesh-objective bar yielding"; >= 0).
     */
    double hinge_length = 0;
    /**
     * L_sp, m: strain penetration of the vertical bars into the clamped base (0: off, perfect
     * bond up to the base). A bar anchored in the base slips out of it as it is pulled; with
     * the slip linearised as s = sigma L_sp / E_s (the elastic part of Zhao and Sritharan's
     * bond-slip law, ACI Struct. J. 104(2), 2007), the opening at the base, h eps_yy of a row
     * of height h, stretches the bar over h + L_sp. The points of the cells on the base
     * (initialize_anchored_point(), h the cell's height) read their y bars at the strain
     * eps_yy h / (h + L_sp),
     * so the opening at which they yield and the elongation per unit of plastic strain no
     * longer depend on h (docs/physics.md §6 "Strain penetration at the base"; >= 0).
     */
    double strain_penetration = 0;
    /**
     * f_j, Pa: the tension a construction joint at the clamped base carries (0: off, the base
     * row cracks as the wall's concrete). With strain penetration, the concrete of the cells on
     * the base then has no strength criterion in tension: its damage is
     * d_t = kappa_t / (kappa_t + f_j / E), so it carries E kappa_t f_j / (E kappa_t + f_j),
     * rising from the first tensile strain and saturating at f_j, and never softens. The
     * elastic stress at the clamped corner is singular, so a strength criterion there cracks at
     * a load that falls as the cells shrink; this joint has no such onset (docs/physics.md §6
     * "The base joint"; >= 0).
     */
    double base_joint_tension = 0;
    /**
     * s_rm, m: the mean spacing of the cracks the bars impose (0: off, each cell's own crack
     * band). Bars spread the cracking of a tension zone over cracks about s_rm apart, so a
     * cracked zone's mean strain is w / s_rm for a crack opening w whatever the cells' size.
     * With s_rm > 0 the concrete of the points of this law softens in tension over s_rm instead
     * of their cell's height h: G_F / s_rm per unit volume, and the crack opening of the shear
     * retention is s_rm times the crack strain (the crack band of reinforced concrete equal to
     * the crack spacing, Bazant and Oh, J. Struct. Eng. 109(9), 1983). Without it the crack
     * band h makes a finer mesh's cracked-but-bridged rows carry tension to a larger strain
     * (G_F / (h f_t)), so they turn less and the base row more (docs/physics.md §6 "Crack
     * spacing of the reinforced wall"; >= 0).
     */
    double crack_spacing = 0;
    /**
     * Tension stiffening (needs crack_spacing > 0): the concrete between the cracks the bars
     * impose carries, on average, f_t / (1 + sqrt(500 eps_1)) at the crack-normal strain eps_1
     * (Collins and Mitchell, Prestressed Concrete Structures, 1991; the modified compression
     * field theory's average tension) instead of softening to nothing over s_rm. It is capped
     * by what the bars can still take at a crack, sum rho_i (f_y - E_s eps_i) cos^2 theta_i with
     * eps_i = eps_1 cos^2 theta_i (the crack check in its strain form, exact for monotonic
     * loading), so it is gone where the bars at the point reach yield. Each point checks its
     * own strain, not the section's bars at the crack (docs/physics.md §6 "Tension
     * stiffening": the bare wall's force past yield is 6.4 % above its bars alone).
     */
    bool tension_stiffening = false;
    /** The steel ratios the crack check of tension stiffening reads (< 0: ratio_x, ratio_y).
     *  The pushover's wall concentrates its bars in columns of cells, but every cell's cracks
     *  are bridged by the section's smeared steel: it sets both to that. Not a scene key. */
    double bridging_ratio_x = -1, bridging_ratio_y = -1;
    /** True if any bar is present. */
    bool any() const { return ratio_x > 0 || ratio_y > 0; }
    /** Kinematic hardening modulus H = b E_s / (1 - b) (Pa): E_s H / (E_s + H) = b E_s. */
    double hardening_modulus() const { return hardening * youngs_modulus / (1 - hardening); }
  };

  /** One step of a uniaxial steel bar (SteelBar::update()). */
  struct SteelState
  {
    double stress         = 0; ///< Pa
    double tangent        = 0; ///< consistent d sigma / d eps, Pa
    double plastic_strain = 0; ///< eps_p, -
    double back_stress    = 0; ///< alpha, Pa
    double plastic_work   = 0; ///< increment of the plastic work int sigma d eps_p, J/m^3
  };

  /**
   * Uniaxial elastic-plastic steel with linear kinematic hardening (Simo & Hughes 1998 §1.4):
   * yield function |sigma - alpha| <= f_y, alpha = H eps_p, so that reversed loading yields at
   * alpha - f_y (Bauschinger effect). Backward-Euler return mapping, exact for this linear law.
   */
  struct SteelBar
  {
    double f_y = 500e6, E_s = 200e9, H = 0; ///< Pa
    explicit SteelBar(const ReinforcementParameters &r)
      : f_y(r.yield_stress)
      , E_s(r.youngs_modulus)
      , H(r.hardening_modulus())
    {
    }
    /** The state at total strain @p strain from the committed @p plastic_strain and
     *  @p back_stress. The plastic work increment f_y |d eps_p| + (alpha_0 + alpha_1) / 2
     *  d eps_p is the exact integral along the step (the flow direction is constant in it). */
    SteelState update(double strain, double plastic_strain, double back_stress) const
    {
      SteelState   s;
      const double trial = E_s * (strain - plastic_strain);
      const double xi = trial - back_stress, f = (xi < 0 ? -xi : xi) - f_y;
      if (f <= 0)
      {
        s.stress         = trial;
        s.tangent        = E_s;
        s.plastic_strain = plastic_strain;
        s.back_stress    = back_stress;
        return s;
      }
      const double sign = xi < 0 ? -1.0 : 1.0, dgamma = f / (E_s + H);
      s.plastic_strain = plastic_strain + sign * dgamma;
      s.back_stress    = back_stress + sign * H * dgamma;
      s.stress         = trial - sign * E_s * dgamma;
      s.tangent        = E_s * H / (E_s + H);
      s.plastic_work   = f_y * dgamma + 0.5 * (back_stress + s.back_stress) * sign * dgamma;
      return s;
    }
  };

  /**
   * Concrete: tension damage d_t on a fixed crack with unilateral closure and shear retention,
   * compression damage d_c on top (docs/physics.md §6):
   *   psi = (1 - d_c) [psi_0(eps) - d_t L(eps)],  sigma = d psi / d eps,
   * psi_0 = eps : D eps / 2 and L = psi_0 - psi_cracked, where psi_cracked, the energy a fully
   * cracked point keeps, is in the crack frame (n, t) the no-tension energy of the normal block
   * (min over crack strains e_c >= 0 of (eps - e_c) : D (eps - e_c) / 2: a crack closed in
   * compression carries as the intact concrete) plus beta(w) mu gamma_nt^2 / 2 (aggregate
   * interlock; w = h e_open, the crack opening of the band). n is fixed at the step the point
   * first cracks, along the largest principal effective stress. Tension measure kappa_t (largest
   * principal effective stress / E) with exponential crack-band softening G_F / h (Bazant & Oh
   * 1983), compression measure kappa_c (-smallest principal effective stress / E) along
   * compression_curve(). History: kappa_t, kappa_c, d_t, d_c, damage dissipation density
   * (J/m^3), h (m), crack normal (cos, sin).
   *
   * With reinforcement, smeared steel bars (SteelBar) add ratio_i sigma_s(eps_ii) to the normal
   * stress i = x, y and ratio_i E_t to the tangent; once cracked, the bars crossing the crack add
   * dowel action, elastic-perfectly plastic in gamma_nt (dowel()). The history then also holds
   * eps_p and alpha of the x bars, of the y bars, the steel's plastic work density (J/m^3,
   * bars and dowels, reported as plastic dissipation) and the dowels' plastic slip strain. The
   * steel's elastic energy is stored.
   *
   * With plastic_fraction b_c > 0, compression leaves plastic strain: eps_p grows by b_c times
   * the growth of the uniaxial curve's inelastic strain kappa_c - sigma_c(kappa_c) / E along the
   * direction of the largest compression, the law above acts on eps - eps_p, and d_c is such
   * that uniaxial compression still follows the curve. The history then also holds eps_p {xx,
   * yy, gamma_xy} and its plastic dissipation density (J/m^3) before the bars' values.
   */
  class ConcreteDamageLaw final : public BatchedLaw<ConcreteDamageLaw>
  {
  public:
    /**
     * How the damage of a step is found. implicit: from the measures kappa_t, kappa_c at the
     * step's own strain (backward Euler; the impact solver). implex: IMPL-EX (Oliver, Huespe &
     * Cante, CMAME 197, 2008): the stress of step n+1 uses the damage of the measures
     * extrapolated from steps n and n-1 (begin_step()), so it is piecewise linear in the strain
     * within a step and Newton needs 1-2 iterations; the implicit measures at the converged
     * strain are stored for the next extrapolation. Damage never decreases. For the static
     * solver (docs/physics.md §6 "Static pushover"); the history then has 4 more values
     * (extrapolated kappa_t, kappa_c; kappa_t, kappa_c of the step before), the last ones.
     */
    enum class DamageUpdate
    {
      implicit,
      implex
    };
    explicit ConcreteDamageLaw(const ConcreteParameters      &p,
                               const ReinforcementParameters &reinforcement = {},
                               DamageUpdate                   update = DamageUpdate::implicit);
    unsigned int n_history() const override { return implex_ + (implex_on_ ? 4 : 0); }
    /** IMPL-EX: extrapolates kappa_t, kappa_c to the coming step (no-op when implicit). */
    void begin_step(double *committed, double step_ratio) const override;
    /** IMPL-EX: (d_t(kappa_t) - d_t used) E kappa_t / f_t, the tensile stress the lagging
     *  damage let through beyond the implicit update's, over f_t (>= 0; 0 when implicit). */
    double step_error(const double *trial) const override;
    void   initialize_point(double *history, double characteristic_length) const override;
    /** As initialize_point(), for a point of a cell of @p height on the clamped base: its y
     *  bars see the strain scaled by height / (height + L_sp)
     *  (ReinforcementParameters::strain_penetration). */
    void initialize_anchored_point(double *history,
                                   double  characteristic_length,
                                   double  height) const override;
    void initial_history(double *history) const override;
    VoigtStress
    stress(const VoigtStrain &strain, const double *committed, double *trial) const override;
    /** The tangent at @p strain from the committed state. Where the implicit update's step
     *  grows the damage, the consistent one (a central difference of the stress: the damage's
     *  growth, the crack frame it turns, beta, the plastic strain); elsewhere, and with
     *  IMPL-EX, that of the step's damage (beta's change with the opening left out). */
    VoigtTangent tangent(const VoigtStrain &strain, const double *committed) const override;
    PointOutput  output(const VoigtStrain &strain, const double *history) const override;
    /** The length over which a point of crack band h softens in tension: the bars' crack
     *  spacing if set (ReinforcementParameters::crack_spacing), else h. */
    double tension_band(double h) const;
    /** Tensile strength used at crack-band length h (reduced if tension_band(h) exceeds the
     *  snap-back limit). */
    double                         effective_tensile_strength(double h) const;
    const ConcreteParameters      &parameters() const { return p_; }
    const ReinforcementParameters &reinforcement() const { return r_; }
    /**
     * Shear retention beta(w) of a crack of opening w (m): beta_min + (1 - beta_min)(1 - 2w /
     * d_agg) up to w = d_agg / 2, beta_min beyond (the aggregate-size-based retention of
     * smeared-crack codes after Walraven's aggregate interlock tests; 1 for a closed crack).
     */
    double shear_retention(double w) const;
    /** Smeared dowel action across a crack of normal (c, s): shear stiffness rho_n G_s and
     *  strength rho_n min(f_y / sqrt 3, k (4 / pi) sqrt(f_cm f_y)) (Pa), rho_n = rho_x c^2 +
     *  rho_y s^2, G_s = E_s / (2 (1 + 0.3)). */
    struct Dowel
    {
      double stiffness = 0, strength = 0;
    };
    Dowel dowel(double c, double s) const;
    /** History slot of the compressive plastic strain (plastic_fraction > 0). */
    static constexpr unsigned int p_slot = 8;

  private:
    static constexpr double steel_poisson_ratio = 0.3;
    /** Most history values of any configuration (the tangent's stack scratch). */
    static constexpr unsigned int max_history = 32;
    /** True if the implicit update at @p strain from @p committed grows d_t, d_c or kappa_c. */
    bool step_grows_damage(const VoigtStrain &strain, const double *committed) const;
    /** The implicit update's tangent where the step grows the damage: a central difference of
     *  the concrete's stress, plus the bars' and dowels'. */
    VoigtTangent growing_damage_tangent(const VoigtStrain &strain, const double *committed) const;
    /** Adds the bars' and dowels' consistent tangent at @p strain from @p committed to @p t. */
    void add_reinforcement_tangent(VoigtTangent      &t,
                                   const VoigtStrain &strain,
                                   const double      *committed) const;
    /** psi_0, the loss L, their stress d psi_0 / d eps and d L / d eps (x, y), their sigma_zz
     *  parts, the crack opening strain and beta at strain e in the frame (c, s), band h. */
    struct Split
    {
      VoigtStress sigma0{}, dloss{};
      double      psi0 = 0, loss = 0, szz0 = 0, dloss_zz = 0, opening = 0, beta = 1;
    };
    Split split(const VoigtStrain &e, double c, double s, double h) const;
    /** The stress at elastic strain @p ee with damage dt, dc (written to h1 with the crack
     *  frame, set to (sa_x, sa_y) if the point cracks now, and the dissipation). */
    VoigtStress damaged_stress(const VoigtStrain &ee,
                               const double      *h0,
                               double            *h1,
                               double             dt,
                               double             dc,
                               double             sa_x,
                               double             sa_y) const;
    /** The damaged concrete's stress (history slots 0-7). */
    VoigtStress concrete_stress(const VoigtStrain &strain, const double *h0, double *h1) const;
    /** As concrete_stress() with compressive plastic strain (history slots 0-11). */
    VoigtStress
    plastic_concrete_stress(const VoigtStrain &strain, const double *h0, double *h1) const;
    /** Tension damage at the tension measure kappa_t (history slot 0) of a crack band h (m)
     *  across a crack of normal (c, s): exponential softening with the energy
     *  G_F / tension_band(h), 0 up to the tensile strength; with tension stiffening
     *  1 - sigma_ts / (E kappa_t) instead, sigma_ts read at the y bars' strain scale @p a
     *  (anchor_scale()). */
    double tension_damage(double kappa_t, double h, double c, double s, double a) const;
    /** The tension-stiffening stress sigma_ts at kappa_t across a crack of normal (c, s), Pa
     *  (ReinforcementParameters::tension_stiffening). On the clamped base (@p a < 1) the y
     *  part of the opening spreads over the bars' height + L_sp, as for the bars: the average
     *  tension and the y bars' reserve read kappa_t scaled by @p a along y. */
    double stiffened_tension(double kappa_t, double c, double s, double a) const;
    /** The y bars' strain scale of a point: h / (h + L_sp) on the clamped base, else 1. */
    double anchor_scale(const double *history) const
    {
      return bar_slots_ > 6 ? history[bars_ + 6] : 1.0;
    }
    /** b_c times the uniaxial curve's inelastic strain at the compression measure kappa_c. */
    double plastic_strain(double kappa_c, double band) const;
    /** The bars' steel at a point of crack band @p h (m): H scaled by h / L_p with a hinge
     *  length, else steel_. */
    SteelBar steel_at(double h) const;
    /** IMPL-EX: the damage (d_t, d_c) of the measures extrapolated in h0, never below the
     *  committed one; writes the committed measures as the previous ones to h1. */
    std::array<double, 2>   implex_damage(const double *h0, double *h1) const;
    ConcreteParameters      p_;
    ReinforcementParameters r_;
    SteelBar                steel_;
    bool                    reinforced_ = false;
    bool                    plastic_    = false;
    unsigned int            bars_       = p_slot; ///< first history slot of the bars
    /** History slots of the bars: eps_p and alpha of x and y, plastic work, dowel slip, and
     *  with strain penetration the y bars' strain scale (1 off the base). */
    unsigned int bar_slots_ = 0;
    bool         implex_on_ = false;
    unsigned int implex_    = p_slot; ///< first history slot of IMPL-EX
    double       lambda_, mu_;
  };
} // namespace kimp::fem
