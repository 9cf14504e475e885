// Central difference method in plan: the model's assembly, the stability limit and the time loop
// (one step: forces at u_n, the increment, the bookkeeping of step n).
#include "lumped/plan/plan_central_difference.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "lumped/integrators/integration_errors.h"
#include "lumped/integrators/largest_omega.h"
#include "lumped/parameter_check.h"

namespace kimp::lumped::plan
{
  namespace
  {
    StabilityLimit plan_stability(const PlanModel &model, const double penetration)
    {
      require_expected_penetration(penetration);
      StabilityLimit  s;
      Eigen::MatrixXd k = model.initial_stiffness_matrix();
      s.omega_structure = largest_omega(model.masses(), k);
      std::string impact_name;
      for (const PlanContact &c : model.contacts())
      {
        const double kt = c.law->stability_stiffness(penetration);
        note_impact(s, impact_name, kt, c.effective_mass, c.name);
        k.topLeftCorner<3, 3>() += c.weight * kt * c.normal_row.transpose() * c.normal_row;
      }
      s.omega_closed =
        model.contacts().empty() ? s.omega_structure : largest_omega(model.masses(), k);
      // A yielding face's DOF between its wall-and-backfill part and its closed contact points.
      for (const PlanWallDof &wd : model.wall_dofs())
      {
        double kt = wd.law->stability_stiffness(penetration);
        for (const PlanContact &c : model.contacts())
          if (c.segment == wd.segment)
            kt += c.weight * c.law->stability_stiffness(penetration);
        note_impact(s, impact_name, kt, wd.mass, "yielding wall " + std::to_string(wd.segment));
      }
      std::ostringstream closed;
      closed << "structure with all contact points closed: omega_max = " << s.omega_closed
             << " rad/s";
      set_critical_step(s, impact_name, penetration, closed.str());
      return s;
    }

    /**
     * y = H·x for a column-major H of `rows` rows (a multiple of 16) and n columns: each row
     * summed as (Σ over even j) + (Σ over odd j), each over ascending j, so that the two chains
     * of additions overlap and every vector width gives bitwise the same y. Vectors of four
     * doubles (GCC vector extensions: two SSE2 registers each in the baseline build, one AVX2
     * register in the AVX2 build; no FMA, so no contraction). NC > 0: n = NC known at compile
     * time (the loops unrolled) and rows = R·NC rounded up to 16; NC = 0: n and rows at run
     * time.
     */
    template <std::size_t NC, std::size_t R = 2>
    inline __attribute__((always_inline)) void dense_product_body(const double *__restrict h,
                                                                  const double *__restrict x,
                                                                  double *__restrict y,
                                                                  const std::size_t rows_rt,
                                                                  const std::size_t n_rt)
    {
      typedef double    V __attribute__((vector_size(32)));
      typedef double    U __attribute__((vector_size(32), aligned(8), may_alias));
      const std::size_t n    = NC > 0 ? NC : n_rt;
      const std::size_t rows = NC > 0 ? (R * NC + 15) / 16 * 16 : rows_rt;
      for (std::size_t r = 0; r < rows; r += 16)
      {
        V           e0 = {}, e1 = {}, e2 = {}, e3 = {}, o0 = {}, o1 = {}, o2 = {}, o3 = {};
        std::size_t j = 0;
        for (; j + 1 < n; j += 2)
        {
          const U *c  = reinterpret_cast<const U *>(h + j * rows + r);
          const U *c1 = reinterpret_cast<const U *>(h + (j + 1) * rows + r);
          const V  d = V{} + x[j], d1 = V{} + x[j + 1];
          e0 += c[0] * d;
          e1 += c[1] * d;
          e2 += c[2] * d;
          e3 += c[3] * d;
          o0 += c1[0] * d1;
          o1 += c1[1] * d1;
          o2 += c1[2] * d1;
          o3 += c1[3] * d1;
        }
        if (j < n)
        {
          const U *c = reinterpret_cast<const U *>(h + j * rows + r);
          const V  d = V{} + x[j];
          e0 += c[0] * d;
          e1 += c[1] * d;
          e2 += c[2] * d;
          e3 += c[3] * d;
        }
        *reinterpret_cast<U *>(y + r)      = e0 + o0;
        *reinterpret_cast<U *>(y + r + 4)  = e1 + o1;
        *reinterpret_cast<U *>(y + r + 8)  = e2 + o2;
        *reinterpret_cast<U *>(y + r + 12) = e3 + o3;
      }
    }

    /// What one increment reads and writes (see Run::advance), as plain pointers.
    struct StepArrays
    {
      std::size_t   n = 0, rows = 0, c_rows = 0;
      const double *cm = nullptr; ///< C, c_rows × n column-major (rows padded with zeros to 16)
      double       *cv = nullptr; ///< C·v_n, c_rows
      const double *hg = nullptr, *af = nullptr, *amx = nullptr, *amy = nullptr, *un = nullptr,
                   *rx = nullptr, *ry = nullptr, *mx = nullptr, *my = nullptr;
      double *y = nullptr, *du = nullptr, *z = nullptr, *inc = nullptr, *dun = nullptr,
             *unp = nullptr, *v = nullptr, *a = nullptr, *pu = nullptr, *pa = nullptr,
             *acc2 = nullptr; ///< per level max (ü_x + ü_g,x)² + (ü_y + ü_g,y)²
      double f[3] = {0.0, 0.0, 0.0}, ag_x = 0.0, ag_y = 0.0, half_inv_dt = 0.0, inv_dt2 = 0.0;
      double p_in   = 0.0; ///< out: −(r_xᵀM·v·ü_g,x + r_yᵀM·v·ü_g,y), W
      double p_visc = 0.0; ///< out: v_nᵀC·v_n, W
    };

    /**
     * The increment of one step from y (Run::advance), v_n, a_n (r_x, r_y pick the DOFs that
     * ü_g,x and ü_g,y add to: 1·ü_g + 0·ü_g is ü_g exactly), the peaks of |u_n| and |a_n|, of
     * the levels' horizontal acceleration and the input power. The element-wise pass has no
     * reduction (so it vectorises); the power's two sums then run over the DOFs along x and y
     * in ascending order (the others add exact zeros). NC as dense_product_body.
     */
    template <std::size_t NC>
    inline __attribute__((always_inline)) void update_body(StepArrays &k)
    {
      const std::size_t n        = NC > 0 ? NC : k.n;
      const double *__restrict y = k.y, *__restrict du = k.du, *__restrict af = k.af,
                               *__restrict amx = k.amx, *__restrict amy = k.amy,
                               *__restrict un = k.un, *__restrict rx = k.rx, *__restrict ry = k.ry,
                               *__restrict mx = k.mx, *__restrict my = k.my;
      double *__restrict z = k.z, *__restrict inc = k.inc, *__restrict dun = k.dun,
                         *__restrict unp = k.unp, *__restrict v = k.v, *__restrict a = k.a,
                         *__restrict pu = k.pu, *__restrict pa = k.pa, *__restrict acc2 = k.acc2;
      // Scalars in locals: read through `k` they could alias the stores.
      const double ag_x = k.ag_x, ag_y = k.ag_y, f0 = k.f[0], f1 = k.f[1], f2 = k.f[2];
      const double h = k.half_inv_dt, i2 = k.inv_dt2;
      // Four DOFs at a time (vectors of four doubles, unaligned; element-wise, so bitwise the
      // scalar results), then the rest one by one.
      typedef double V __attribute__((vector_size(32)));
      typedef double U __attribute__((vector_size(32), aligned(8), may_alias));
      std::size_t    i = 0;
      for (; i + 4 <= n; i += 4)
      {
        const V yi = *reinterpret_cast<const U *>(y + i), zi = *reinterpret_cast<const U *>(z + i);
        const V d = -(yi + zi + *reinterpret_cast<const U *>(amx + i) * ag_x +
                      *reinterpret_cast<const U *>(amy + i) * ag_y) -
                    (*reinterpret_cast<const U *>(af + i) * f0 +
                     *reinterpret_cast<const U *>(af + n + i) * f1 +
                     *reinterpret_cast<const U *>(af + 2 * n + i) * f2);
        const V dui = *reinterpret_cast<const U *>(du + i), next = dui + d;
        *reinterpret_cast<U *>(inc + i) = d;
        *reinterpret_cast<U *>(dun + i) = next;
        *reinterpret_cast<U *>(z + i)   = zi + *reinterpret_cast<const U *>(y + n + i);
        const V uni                     = *reinterpret_cast<const U *>(un + i);
        *reinterpret_cast<U *>(unp + i) = uni + next;
        const V ai                      = d * i2 + (*reinterpret_cast<const U *>(rx + i) * ag_x +
                               *reinterpret_cast<const U *>(ry + i) * ag_y);
        *reinterpret_cast<U *>(v + i)   = (dui + next) * h;
        *reinterpret_cast<U *>(a + i)   = ai;
        const V aun = uni < 0.0 ? -uni : uni, aai = ai < 0.0 ? -ai : ai;
        const V pui                    = *reinterpret_cast<const U *>(pu + i),
                pai                    = *reinterpret_cast<const U *>(pa + i);
        *reinterpret_cast<U *>(pu + i) = pui < aun ? aun : pui;
        *reinterpret_cast<U *>(pa + i) = pai < aai ? aai : pai;
      }
      for (; (NC == 0 || NC % 4 != 0) && i < n; ++i)
      {
        const double d = -(y[i] + z[i] + amx[i] * ag_x + amy[i] * ag_y) -
                         (af[i] * f0 + af[n + i] * f1 + af[2 * n + i] * f2);
        const double next = du[i] + d;
        inc[i]            = d;
        dun[i]            = next;
        z[i] += y[n + i];
        unp[i]          = un[i] + next;
        const double ai = d * i2 + (rx[i] * ag_x + ry[i] * ag_y);
        v[i]            = (du[i] + next) * h;
        a[i]            = ai;
        pu[i]           = std::max(pu[i], std::abs(un[i]));
        pa[i]           = std::max(pa[i], std::abs(ai));
      }
      double p_x = 0.0, p_y = 0.0;
      for (std::size_t l = 0; 3 * l + 2 < n; ++l)
      {
        p_x += mx[3 * l] * v[3 * l];
        p_y += my[3 * l + 1] * v[3 * l + 1];
        const double ax = a[3 * l], ay = a[3 * l + 1];
        acc2[l] = std::max(acc2[l], ax * ax + ay * ay);
      }
      k.p_in = -(p_x * ag_x + p_y * ag_y);
    }

    using StepKernel = void (*)(StepArrays &);

    /// The viscous power v_nᵀ(C·v_n), the sum in four lanes (i mod 4) then added up.
    template <std::size_t NC>
    inline __attribute__((always_inline)) void viscous_body(StepArrays &k)
    {
      const std::size_t n = NC > 0 ? NC : k.n;
      dense_product_body<NC, 1>(k.cm, k.v, k.cv, k.c_rows, n);
      double lane[4] = {0.0, 0.0, 0.0, 0.0};
      for (std::size_t i = 0; i < n; ++i)
        lane[i % 4] += k.v[i] * k.cv[i];
      k.p_visc = (lane[0] + lane[1]) + (lane[2] + lane[3]);
    }

    template <std::size_t NC>
    void step_base(StepArrays &k)
    {
      dense_product_body<NC>(k.hg, k.du, k.y, k.rows, k.n);
      update_body<NC>(k);
      viscous_body<NC>(k);
    }

    template <std::size_t NC>
    __attribute__((target("avx2"))) void step_avx2(StepArrays &k)
    {
      dense_product_body<NC>(k.hg, k.du, k.y, k.rows, k.n);
      update_body<NC>(k);
      viscous_body<NC>(k);
    }

    /// The kernel for n DOFs: unrolled for buildings of up to 8 levels, else the run-time loop.
    template <std::size_t... L>
    StepKernel pick_kernel(const std::size_t n, const bool avx2, std::index_sequence<L...>)
    {
      StepKernel k = avx2 ? step_avx2<0> : step_base<0>;
      ((n == 3 * (L + 1) ? (k = avx2 ? step_avx2<3 * (L + 1)> : step_base<3 * (L + 1)>) : k), ...);
      return k;
    }

    /// The state of one run (allocated once; the loop does not allocate).
    class Run
    {
    public:
      Run(const PlanCentralDifference &cdm, const PlanGroundMotion &g);
      PlanResponse execute();

    private:
      void   forces(long                   n,
                    const Eigen::VectorXd &u,
                    const Eigen::VectorXd &u_prev,
                    const Eigen::VectorXd &u_prev2);
      void   contact(std::size_t c, double delta, double s, double s_prev, double t);
      bool   contacts_far(long n, const double *q0);
      void   set_up_matrices();
      void   set_up_points();
      void   set_up_kernel();
      void   ground(long n, double &ag_x, double &ag_y);
      void   advance(double ag_x, double ag_y);
      void   bookkeeping(long n);
      void   initial_conditions();
      void   collect_results();
      void   checkpoint(long n);
      double strain_energy() const;

      const PlanModel        &model_;
      const PlanOptions      &opt_;
      const PlanGroundMotion &g_;
      std::size_t             n_  = 0;
      double                  dt_ = 0.0, inv_dt_ = 0.0;
      long                    n_steps_ = 0;
      long                    every_ = 0, check_every_ = 512;
      // Records' interpolation (as the planar integrator).
      bool   integer_substeps_ = false;
      long   sub_              = 1;
      double inv_sub_          = 1.0;
      long   sub_n_ = -1, sub_j_ = 0, sub_r_ = 0; ///< the next n expected, its n / sub_, n % sub_

      Eigen::MatrixXd hg_;    ///< [A⁻¹(C/Δt + K); A⁻¹K; 0], hg_rows_ × n
      Eigen::MatrixXd c_pad_; ///< [C; 0], c_rows_ × n
      Eigen::VectorXd cv_;    ///< C·v_n (c_rows_)
      std::size_t     c_rows_  = 0;
      std::size_t     hg_rows_ = 0;
      StepKernel      step_    = nullptr;
      StepArrays      k_;
      Eigen::MatrixXd a_inv_f_; ///< A⁻¹ restricted to level 0's columns, n × 3
      Eigen::VectorXd am_x_, am_y_;
      Eigen::VectorXd r_x_, r_y_;   ///< the DOFs along x and along y (1, else 0)
      Eigen::VectorXd rx_m_, ry_m_; ///< M·r_x, M·r_y

      // state: u_{n−2}, u_{n−1}, u_n, u_{n+1}, Δu_n, Δu_{n+1}, z_{n−1}, products
      Eigen::VectorXd u_nm2_, u_nm1_, u_n_, u_np1_, du_n_, du_np1_, z_, y_, inc_, v_, a_;
      Eigen::Vector3d f0_;

      std::vector<std::unique_ptr<PlanIsolator>> iso_;
      /// iso_ as bilinear isolators when every one is (else empty).
      std::vector<PlanBilinearIsolator *>    bilinear_;
      std::vector<std::unique_ptr<ForceLaw>> laws_;
      std::vector<double> dp_, dpp_, cf_, phi_; ///< δ_{n−1}, δ_{n−2}, w·F, φ
      std::vector<int>    active_, called_;
      std::vector<double> wall_force_;
      double              mu_ = 0.0, v_stick_ = 1.0;
      LawVelocity         scheme_;
      /// Contacts skipped as a whole: no point can reach its face while 2(|u_0|² + θ_0²·R²) <
      /// g_min² (R the largest lever arm of a normal row, g_min the smallest gap), once every
      /// contact is open and carries no force (quiet_).
      double contact_r2_ = 0.0, contact_g2_ = 0.0;
      bool   quiet_ = false, skipped_ = false;
      double iso_peak_sq_ = 0.0; ///< max |Σ_j f_j|², N²
      /// Per contact: the face has an end (the sliding coordinate is needed).
      std::vector<char> ends_;

      /// The DOF of a yielding face (PlanWallDof) and its state: w_{n−2}, w_{n−1}, w_n, w_{n+1},
      /// Δw_n, Δw_{n+1}, ẇ_n, the wall-and-backfill force F(w_n, ẇ_n) and Σ w_c·F_c at step n.
      struct WallState
      {
        std::size_t               segment = 0;
        double                    nx = 0.0, ny = 0.0, mass = 0.0, a_inv = 0.0, am = 0.0;
        std::unique_ptr<ForceLaw> owner;
        WallBackfillLaw          *law = nullptr;
        double w2 = 0.0, w1 = 0.0, w = 0.0, w_next = 0.0, dw = 0.0, dw_next = 0.0, v = 0.0;
        double fb = 0.0, contact = 0.0;
        std::optional<double> failure_time;
      };
      std::vector<WallState> walls_;
      std::vector<int>       wall_of_segment_; ///< per face: index in walls_, or −1 (rigid)
      double                 w_wall_ = 0.0;    ///< Σ ∫F dw
      void                   wall_forces(long n);
      void                   advance_walls(double ag_x, double ag_y);
      double                 wall_at(std::size_t c, int lag) const;

      // corners of each level at rest and their kinematics
      std::vector<std::vector<Eigen::Matrix<double, 2, 3>>> corner_t_;
      std::vector<double>                                   corner_sq_, drift_sq_, accel_sq_;
      /// A corner of a level: the level's first DOF and the corner from its centre of mass.
      struct CornerRef
      {
        int   level = 0;
        Point r;
      };
      /// A point of a storey's upper level (its centre of mass first, then its corners): the
      /// first DOFs of the two levels (lower −1: the ground) and the point from their centres.
      struct CornerDrift
      {
        std::size_t storey = 0;
        int         upper = 0, lower = -1;
        Point       a, b;
      };
      std::vector<CornerRef>   corners_;
      std::vector<CornerDrift> corner_drifts_;
      /// corners_ of level l: [corner_first_[l], corner_first_[l + 1]); drift_first_ likewise.
      std::vector<std::size_t> corner_first_, drift_first_;
      /// Per level the largest squared distance of a corner from the centre of mass, m².
      std::vector<double> corner_r2_;
      /// Per storey: the levels' first DOFs and the largest squared lever arms from the upper
      /// and lower centres of mass over the upper level's corners (and its centre), m².
      struct DriftBound
      {
        int    upper = 0, lower = -1;
        double a2 = 0.0, b2 = 0.0;
      };
      std::vector<DriftBound> drift_bound_;
      Eigen::VectorXd         peak_u_, peak_a_;

      // energies
      double w_in_ = 0.0, w_visc_ = 0.0, w_contact_ = 0.0, w_friction_ = 0.0;
      double p_visc_ = 0.0; ///< v_nᵀC·v_n from the step kernel
      double p_in_ = 0.0, p_in_prev_ = 0.0, p_visc_prev_ = 0.0, e0_ = 0.0, e_kin_ = 0.0,
             e_strain_     = 0.0;
      double max_supplied_ = 0.0, max_residual_ = 0.0, last_error_ = 0.0;

      PlanResponse out_;
    };

    Run::Run(const PlanCentralDifference &cdm, const PlanGroundMotion &g)
      : model_(cdm.model())
      , opt_(cdm.options())
      , g_(g)
      , scheme_(cdm.options().law_velocity)
    {
      validate(g);
      n_      = model_.n_dofs();
      dt_     = cdm.time_step(g.dt);
      inv_dt_ = 1.0 / dt_;
      const double duration =
        opt_.duration > 0.0 ? opt_.duration : g.dt * static_cast<double>(g.x.size());
      n_steps_ = std::lround(duration / dt_);

      set_up_matrices();
      const auto nn = static_cast<Eigen::Index>(n_);

      for (const PlanIsolatorSpec &spec : model_.building().isolators)
      {
        iso_.push_back(spec.law->clone());
        iso_.back()->revert_to_start();
      }
      for (const auto &iso : iso_)
        if (auto *b = dynamic_cast<PlanBilinearIsolator *>(iso.get()))
          bilinear_.push_back(b);
      if (bilinear_.size() != iso_.size())
        bilinear_.clear();
      const std::size_t nc = model_.contacts().size();
      for (const PlanContact &pc : model_.contacts())
      {
        laws_.push_back(pc.law->clone());
        laws_.back()->revert_to_start();
      }
      wall_of_segment_.assign(model_.moat() ? model_.moat()->wall.size() : 0, -1);
      for (const PlanWallDof &wd : model_.wall_dofs())
      {
        WallState st;
        st.segment = wd.segment;
        st.nx      = wd.normal.x();
        st.ny      = wd.normal.y();
        st.mass    = wd.mass;
        st.a_inv   = 1.0 / (wd.mass * (inv_dt_ * inv_dt_)); // A = m/Δt² (no C, no K)
        st.am      = st.a_inv * wd.mass;
        st.owner   = wd.law->clone();
        st.owner->revert_to_start();
        st.law                       = static_cast<WallBackfillLaw *>(st.owner.get());
        wall_of_segment_[wd.segment] = static_cast<int>(walls_.size());
        walls_.push_back(std::move(st));
      }
      contact_g2_ = std::numeric_limits<double>::infinity();
      for (const PlanContact &pc : model_.contacts())
      {
        // |n·q_0| <= |(u_x, u_y)| + |θ|·|n_θ| for a unit normal n.
        contact_r2_ = std::max(contact_r2_, pc.normal_row(2) * pc.normal_row(2));
        contact_g2_ = std::min(contact_g2_, pc.gap * pc.gap);
        ends_.push_back(pc.s_lo > -std::numeric_limits<double>::infinity() ||
                        pc.s_hi < std::numeric_limits<double>::infinity());
      }
      if (model_.moat())
      {
        mu_      = model_.moat()->friction;
        v_stick_ = model_.moat()->stick_velocity;
      }
      dp_.assign(nc, 0.0);
      dpp_.assign(nc, 0.0);
      cf_.assign(nc, 0.0);
      phi_.assign(nc, 0.0);
      active_.assign(nc, 0);
      called_.assign(nc, 1); // the first step takes the laws as they are (planar integrator)
      wall_force_.assign(model_.moat() ? model_.moat()->wall.size() : 0, 0.0);

      set_up_points();

      const double ratio = g.dt / dt_;
      sub_               = std::lround(ratio);
      integer_substeps_  = sub_ > 0 && std::abs(ratio - static_cast<double>(sub_)) < 1e-9 * ratio;
      inv_sub_           = 1.0 / static_cast<double>(sub_ > 0 ? sub_ : 1);
      every_ =
        opt_.output_interval > 0.0 ? std::max(1L, std::lround(opt_.output_interval / dt_)) : 0L;
      if (every_ > 0 && every_ <= 512)
        check_every_ = every_ * (512 / every_);

      u_nm2_ = u_nm1_ = u_n_ = u_np1_ = du_n_ = du_np1_ = z_ = inc_ = v_ = a_ =
        Eigen::VectorXd::Zero(nn);
      y_      = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(hg_rows_));
      peak_u_ = Eigen::VectorXd::Zero(nn);
      peak_a_ = Eigen::VectorXd::Zero(nn);

      const PlanBuilding &b = model_.building();
      out_.n_levels         = b.n_levels();
      out_.peak_displacement.assign(n_, 0.0);
      out_.peak_absolute_acceleration.assign(n_, 0.0);
      out_.peak_corner_displacement.assign(b.n_levels(), 0.0);
      out_.peak_horizontal_acceleration.assign(b.n_levels(), 0.0);
      out_.peak_drift_x.assign(b.storeys.size(), 0.0);
      out_.peak_drift_y.assign(b.storeys.size(), 0.0);
      out_.peak_corner_drift.assign(b.storeys.size(), 0.0);
      out_.peak_wall_force.assign(wall_force_.size(), 0.0);
      corner_sq_.assign(b.n_levels(), 0.0);
      accel_sq_.assign(b.n_levels(), 0.0);
      drift_sq_.assign(b.storeys.size(), 0.0);
      for (const PlanContact &pc : model_.contacts())
      {
        PlanContactResult r;
        r.name    = pc.name;
        r.segment = pc.segment;
        out_.contacts.push_back(r);
      }
      out_.history.interval = every_ > 0 ? static_cast<double>(every_) * dt_ : 0.0;
    }

    void Run::set_up_matrices()
    {
      const auto             nn = static_cast<Eigen::Index>(n_);
      const Eigen::VectorXd  m  = model_.masses();
      const Eigen::MatrixXd &k  = model_.stiffness();
      const Eigen::MatrixXd &c  = model_.damping();
      const Eigen::MatrixXd  a =
        Eigen::MatrixXd(m.asDiagonal()) * (inv_dt_ * inv_dt_) + c * (0.5 * inv_dt_);
      const Eigen::MatrixXd inv = a.partialPivLu().inverse();
      // [A⁻¹(C/Δt + K); A⁻¹K], its rows padded with zeros to a multiple of 16.
      hg_rows_ = (2 * n_ + 15) / 16 * 16;
      step_    = pick_kernel(n_, __builtin_cpu_supports("avx2"), std::make_index_sequence<8>{});
      hg_      = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(hg_rows_), nn);
      hg_.topRows(nn)        = inv * (c * inv_dt_ + k);
      hg_.middleRows(nn, nn) = inv * k;
      a_inv_f_               = inv.leftCols(3);
      c_rows_                = (n_ + 15) / 16 * 16;
      c_pad_                 = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(c_rows_), nn);
      c_pad_.topRows(nn)     = c;
      cv_                    = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(c_rows_));
      r_x_                   = Eigen::VectorXd::Zero(nn);
      r_y_                   = Eigen::VectorXd::Zero(nn);
      rx_m_                  = Eigen::VectorXd::Zero(nn);
      ry_m_                  = Eigen::VectorXd::Zero(nn);
      for (Eigen::Index i = 0; i < nn; i += 3)
      {
        r_x_(i)      = 1.0;
        r_y_(i + 1)  = 1.0;
        rx_m_(i)     = m(i);
        ry_m_(i + 1) = m(i + 1);
      }
      am_x_ = inv * rx_m_;
      am_y_ = inv * ry_m_;
    }

    void Run::set_up_kernel()
    {
      StepArrays &k = k_;
      k.n           = n_;
      k.rows        = hg_rows_;
      k.hg          = hg_.data();
      k.af          = a_inv_f_.data();
      k.amx         = am_x_.data();
      k.amy         = am_y_.data();
      k.y           = y_.data();
      k.z           = z_.data();
      k.inc         = inc_.data();
      k.v           = v_.data();
      k.a           = a_.data();
      k.half_inv_dt = 0.5 * inv_dt_;
      k.inv_dt2     = inv_dt_ * inv_dt_;
      k.rx          = r_x_.data();
      k.ry          = r_y_.data();
      k.mx          = rx_m_.data();
      k.my          = ry_m_.data();
      k.pu          = peak_u_.data();
      k.pa          = peak_a_.data();
      k.acc2        = accel_sq_.data();
      k.c_rows      = c_rows_;
      k.cm          = c_pad_.data();
      k.cv          = cv_.data();
    }

    void Run::set_up_points()
    {
      // The corners and the storeys' reference points.
      const PlanBuilding &b = model_.building();
      for (std::size_t l = 0; l < b.n_levels(); ++l)
      {
        const Point cm = b.levels[l].centre_of_mass();
        double      r2 = 0.0;
        corner_first_.push_back(corners_.size());
        corner_t_.emplace_back();
        for (const Point &p : b.levels[l].outline)
        {
          corner_t_.back().push_back(level_kinematics(b, l, p));
          corners_.push_back({static_cast<int>(3 * l), p - cm});
          r2 = std::max(r2, (p - cm).squaredNorm());
        }
        corner_r2_.push_back(r2);
      }
      corner_first_.push_back(corners_.size());
      const int offset = b.is_isolated() ? 1 : 0;
      for (std::size_t s = 0; s < b.storeys.size(); ++s)
      {
        drift_first_.push_back(corner_drifts_.size());
        const int        upper = static_cast<int>(s) + offset, lower = upper - 1;
        const PlanLevel &lu = b.levels[static_cast<std::size_t>(upper)];
        const Point      cu = lu.centre_of_mass();
        const Point      cl =
          lower >= 0 ? b.levels[static_cast<std::size_t>(lower)].centre_of_mass() : Point::Zero();
        corner_drifts_.push_back({s, 3 * upper, lower >= 0 ? 3 * lower : -1, cu - cu, cu - cl});
        DriftBound bound{3 * upper, lower >= 0 ? 3 * lower : -1, 0.0, (cu - cl).squaredNorm()};
        for (const Point &p : lu.outline)
        {
          corner_drifts_.push_back({s, 3 * upper, lower >= 0 ? 3 * lower : -1, p - cu, p - cl});
          bound.a2 = std::max(bound.a2, (p - cu).squaredNorm());
          bound.b2 = std::max(bound.b2, (p - cl).squaredNorm());
        }
        drift_bound_.push_back(bound);
      }
      drift_first_.push_back(corner_drifts_.size());
    }

    void Run::ground(const long n, double &ag_x, double &ag_y)
    {
      // ü_g(t_n) by linear interpolation, as the planar integrator forms it.
      std::size_t       j;
      double            frac;
      const std::size_t n_rec = g_.x.size();
      if (integer_substeps_)
      {
        // n = j·sub + r, kept by counting (n / sub_ and n % sub_ without a division per step).
        if (n != sub_n_)
        {
          sub_j_ = n / sub_;
          sub_r_ = n % sub_;
        }
        j      = static_cast<std::size_t>(sub_j_);
        frac   = static_cast<double>(sub_r_) * inv_sub_;
        sub_n_ = n + 1;
        if (++sub_r_ == sub_)
        {
          sub_r_ = 0;
          ++sub_j_;
        }
      }
      else
      {
        const double x = static_cast<double>(n) * dt_ / g_.dt;
        j              = static_cast<std::size_t>(x);
        frac           = x - static_cast<double>(j);
      }
      const auto at = [&](const std::vector<double> &rec)
      {
        if (j + 1 < n_rec)
          return rec[j] + frac * (rec[j + 1] - rec[j]);
        return (j + 1 == n_rec && frac == 0.0) ? rec[j] : 0.0;
      };
      ag_x = at(g_.x);
      ag_y = at(g_.y);
    }

    void Run::contact(const std::size_t c,
                      const double      delta,
                      const double      s,
                      const double      s_prev,
                      const double      t)
    {
      const PlanContact &pc   = model_.contacts()[c];
      ForceLaw          &law  = *laws_[c];
      const double       dp   = dp_[c];
      const double       rate = law_rate(scheme_, delta, dp, dpp_[c], inv_dt_);
      if (!called_[c])
      {
        // Bring the law to the last open state it skipped (planar integrator).
        law.set_trial(dp, (dp - dpp_[c]) * inv_dt_);
        law.commit();
      }
      const double force = pc.weight * law.set_trial(delta, rate).force;
      law.commit();
      const int now_active = law.in_contact() ? 1 : 0;
      if (now_active && !active_[c])
        out_.contacts[c].impacts.push_back({t, rate});
      active_[c] = now_active;
      called_[c] = 1;
      w_contact_ += 0.5 * (cf_[c] + force) * (delta - dp);
      cf_[c] = force;
      f0_ += force * pc.normal_row.transpose();
      wall_force_[pc.segment] += force;
      if (!walls_.empty() && wall_of_segment_[pc.segment] >= 0)
        walls_[static_cast<std::size_t>(wall_of_segment_[pc.segment])].contact += force;
      out_.contacts[c].peak_normal_force = std::max(out_.contacts[c].peak_normal_force, force);

      // Regularised Coulomb friction along the face, resisting the backward sliding velocity.
      double phi = 0.0;
      if (mu_ > 0.0 && force > 0.0)
      {
        const double v_t   = (s - s_prev) * inv_dt_;
        const double limit = mu_ * force;
        const double v_r   = std::max(v_stick_, limit * dt_ / pc.tangential_mass);
        phi                = limit * std::clamp(v_t / v_r, -1.0, 1.0);
      }
      const double work = 0.5 * (phi_[c] + phi) * (s - s_prev);
      w_friction_ += work;
      out_.contacts[c].friction_work += work;
      phi_[c] = phi;
      f0_ += phi * pc.tangent_row.transpose();
      out_.contacts[c].peak_friction_force =
        std::max(out_.contacts[c].peak_friction_force, std::abs(phi));
    }

    double Run::wall_at(const std::size_t c, const int lag) const
    {
      const int k = wall_of_segment_.empty() ? -1 : wall_of_segment_[model_.contacts()[c].segment];
      if (k < 0)
        return 0.0;
      const WallState &wd = walls_[static_cast<std::size_t>(k)];
      return lag == 0 ? wd.w : lag == 1 ? wd.w1 : wd.w2;
    }

    void Run::wall_forces(const long n)
    {
      // The wall-and-backfill parts at w_n (committed every step: permanently attached), their
      // work ∫F dw by the trapezoid rule, the failure time.
      const double t = static_cast<double>(n) * dt_;
      for (WallState &wd : walls_)
      {
        const double rate = law_rate(scheme_, wd.w, wd.w1, wd.w2, inv_dt_);
        const double f    = wd.law->set_trial(wd.w, rate).force;
        wd.law->commit();
        w_wall_ += 0.5 * (wd.fb + f) * (wd.w - wd.w1);
        wd.fb      = f;
        wd.contact = 0.0;
        if (!wd.failure_time && wd.law->failed())
          wd.failure_time = t;
      }
    }

    void Run::advance_walls(const double ag_x, const double ag_y)
    {
      // m·ẅ = −m·(n·ü_g) − (F − Σ w_c·F_c): the planar step of a DOF without C and K.
      for (WallState &wd : walls_)
      {
        const double f = wd.fb - wd.contact;
        const double d = -(wd.am * wd.nx * ag_x + wd.am * wd.ny * ag_y) - wd.a_inv * f;
        wd.dw_next     = wd.dw + d;
        wd.w_next      = wd.w + wd.dw_next;
        wd.v           = (wd.dw + wd.dw_next) * (0.5 * inv_dt_);
        p_in_ -= wd.mass * (wd.nx * ag_x + wd.ny * ag_y) * wd.v;
      }
    }

    bool Run::contacts_far(const long n, const double *q0)
    {
      // The first two steps use the initial δ_{−1}, δ_{−2}; later a resumed pass recomputes
      // them from u_{n−1}, u_{n−2} (what the skipped passes would have stored).
      if (n < 2 || !quiet_)
        return false;
      const double r2 = 2.0 * (q0[0] * q0[0] + q0[1] * q0[1] + q0[2] * q0[2] * contact_r2_);
      if (walls_.empty())
        return r2 < contact_g2_ * (1.0 - 1e-9);
      // A yielding face moved towards the slab (w < 0) narrows its gaps.
      double g = std::sqrt(contact_g2_);
      for (const WallState &wd : walls_)
        g = std::min(g, std::sqrt(contact_g2_) + wd.w);
      return g > 0.0 && r2 < g * g * (1.0 - 1e-9);
    }

    void Run::forces(const long             n,
                     const Eigen::VectorXd &u,
                     const Eigen::VectorXd &u_prev,
                     const Eigen::VectorXd &u_prev2)
    {
      const double          t  = static_cast<double>(n) * dt_;
      const Eigen::Vector3d q0 = u.head<3>();
      const Eigen::Vector3d q1 = u_prev.head<3>();
      const Eigen::Vector3d q2 = u_prev2.head<3>();
      f0_.setZero();
      const auto &kin       = model_.isolator_kinematics();
      Point       resultant = Point::Zero();
      if (!bilinear_.empty())
      {
        // Bilinear isolators (the law needs no velocity): called directly, inlined; T_j =
        // [1, 0, t_x; 0, 1, t_y] written out (the same sums as T_j·q and T_jᵀ·f), the sums in
        // registers.
        double fx = 0.0, fy = 0.0, ft = 0.0, rx = 0.0, ry = 0.0;
        for (std::size_t j = 0; j < bilinear_.size(); ++j)
        {
          const double tx = kin[j](0, 2), ty = kin[j](1, 2);
          const Point  uj(q0(0) + tx * q0(2), q0(1) + ty * q0(2));
          const Point  fj = bilinear_[j]->set_trial(uj, uj);
          bilinear_[j]->commit();
          rx += fj.x();
          ry += fj.y();
          fx += fj.x();
          fy += fj.y();
          ft += tx * fj.x() + ty * fj.y();
        }
        f0_       = Eigen::Vector3d(fx, fy, ft);
        resultant = Point(rx, ry);
      }
      else
        for (std::size_t j = 0; j < iso_.size(); ++j)
        {
          const Point uj = kin[j] * q0, uj1 = kin[j] * q1, uj2 = kin[j] * q2;
          const Point vj(law_rate(scheme_, uj.x(), uj1.x(), uj2.x(), inv_dt_),
                         law_rate(scheme_, uj.y(), uj1.y(), uj2.y(), inv_dt_));
          const Point fj = iso_[j]->set_trial(uj, vj);
          iso_[j]->commit();
          resultant += fj;
          f0_ += kin[j].transpose() * fj;
        }
      iso_peak_sq_ = std::max(iso_peak_sq_, resultant.squaredNorm());
      wall_forces(n);
      if (contacts_far(n, q0.data()))
      {
        skipped_ = true;
        return;
      }
      const bool resumed = skipped_;
      skipped_           = false;
      quiet_             = true;
      std::fill(wall_force_.begin(), wall_force_.end(), 0.0);
      for (std::size_t c = 0; c < laws_.size(); ++c)
      {
        const PlanContact &pc   = model_.contacts()[c];
        const auto         s_at = [&](const Eigen::Vector3d &q)
        { return pc.s_rest + pc.tangent_row.dot(q); };
        // Beyond the ends of its face a point meets nothing: the law sees the gap at rest.
        // The sliding coordinate only where it matters: a face with an end, a contact, friction.
        // A yielding face's displacement w (at the same step as q) widens the gap.
        const auto delta_at = [&](const Eigen::Vector3d &q, const int lag)
        {
          const bool   on_face = !ends_[c] || (s_at(q) >= pc.s_lo && s_at(q) <= pc.s_hi);
          const double gap     = walls_.empty() ? pc.gap : pc.gap + wall_at(c, lag);
          return on_face ? pc.normal_row.dot(q) - gap : -gap;
        };
        if (resumed)
        {
          dp_[c]  = delta_at(q1, 1);
          dpp_[c] = delta_at(q2, 2);
        }
        const double delta = delta_at(q0, 0);
        if (delta > 0.0 || active_[c])
        {
          contact(c, delta, s_at(q0), s_at(q1), t);
          quiet_ = false;
        }
        else
        {
          called_[c] = 0;
          if (cf_[c] != 0.0)
          {
            w_contact_ += 0.5 * cf_[c] * (delta - dp_[c]);
            cf_[c] = 0.0;
          }
          if (phi_[c] != 0.0)
          {
            const double work = 0.5 * phi_[c] * (s_at(q0) - s_at(q1));
            w_friction_ += work;
            out_.contacts[c].friction_work += work;
            phi_[c] = 0.0;
          }
        }
        dpp_[c] = dp_[c];
        dp_[c]  = delta;
      }
      for (std::size_t j = 0; j < wall_force_.size(); ++j)
        out_.peak_wall_force[j] = std::max(out_.peak_wall_force[j], wall_force_[j]);
    }

    double Run::strain_energy() const
    {
      double e = 0.5 * u_n_.dot(model_.stiffness() * u_n_);
      for (const auto &iso : iso_)
        e += iso->stored_energy();
      return e;
    }

    void Run::advance(const double ag_x, const double ag_y)
    {
      // Increment: Δu_{n+1} − Δu_n = −(A⁻¹(C/Δt + K)Δu_n + z_{n−1} + A⁻¹M·r·ü_g + A⁻¹f), with
      // y = [A⁻¹(C/Δt + K); A⁻¹K]·Δu_n by columns (each row summed over ascending columns),
      // then per DOF in one pass: Δu_{n+1}, z_n, u_{n+1}, v_n = (Δu_n + Δu_{n+1})/(2Δt),
      // a_n = (Δu_{n+1} − Δu_n)/Δt² (+ ü_g in x and y), the peaks of u_n and a_n and the input
      // power. Raw loops over the DOFs: the products and updates of a 15-DOF step cost less
      // than the set-up of Eigen's dynamic-size kernels.
      StepArrays &k = k_; // the fixed pointers set once (set_up_kernel)
      k.un          = u_n_.data();
      k.du          = du_n_.data();
      k.dun         = du_np1_.data();
      k.unp         = u_np1_.data();
      k.f[0]        = f0_(0);
      k.f[1]        = f0_(1);
      k.f[2]        = f0_(2);
      k.ag_x        = ag_x;
      k.ag_y        = ag_y;
      step_(k);
      p_in_   = k.p_in;
      p_visc_ = k.p_visc;
      if (!walls_.empty())
        advance_walls(ag_x, ag_y);
    }

    void Run::bookkeeping(const long n)
    {
      // Peaks of the corner displacements and drifts as squares (the roots at the end), in
      // scalars: d = (u_x − θ·r_y, u_y + θ·r_x) with r the corner from the centre of mass.
      // (Maxima in registers, one store per level: the stores of a running maximum in memory
      // stall on their own reloads.)
      const double *u = u_n_.data();
      for (std::size_t l = 0; l < corner_sq_.size(); ++l)
      {
        // |d| <= |u| + |θ|·R: no corner can beat the peak while 2(|u|² + θ²R²) does not.
        const double *q0 = u + 3 * l;
        if (2.0 * (q0[0] * q0[0] + q0[1] * q0[1] + q0[2] * q0[2] * corner_r2_[l]) <= corner_sq_[l])
          continue;
        double      m = corner_sq_[l];
        const auto *c = corners_.data() + corner_first_[l];
        const auto *e = corners_.data() + corner_first_[l + 1];
        for (; c != e; ++c)
        {
          const double *q  = u + c->level;
          const double  dx = q[0] - q[2] * c->r.y(), dy = q[1] + q[2] * c->r.x();
          m = std::max(m, dx * dx + dy * dy);
        }
        corner_sq_[l] = m;
      }
      for (std::size_t s = 0; s < drift_sq_.size(); ++s)
      {
        // The drift at the centre of mass (the storey's first entry) every step; the corners'
        // only when |d| <= |Δu| + |θ_u|·A + |θ_l|·B (A, B the largest lever arms) could beat
        // their peak: 3(|Δu|² + θ_u²A² + θ_l²B²) > the peak².
        const DriftBound &db = drift_bound_[s];
        const double     *bu = u + db.upper;
        const double      bx = db.lower >= 0 ? u[db.lower] : 0.0;
        const double      by = db.lower >= 0 ? u[db.lower + 1] : 0.0;
        const double      tl = db.lower >= 0 ? u[db.lower + 2] : 0.0;
        const double      ex = bu[0] - bx, ey = bu[1] - by;
        const double bound = 3.0 * (ex * ex + ey * ey + bu[2] * bu[2] * db.a2 + tl * tl * db.b2);
        const auto   drift = [&](const CornerDrift &c, double &dx, double &dy)
        {
          const double *qu = u + c.upper;
          const double  lx = c.lower >= 0 ? u[c.lower] - u[c.lower + 2] * c.b.y() : 0.0;
          const double  ly = c.lower >= 0 ? u[c.lower + 1] + u[c.lower + 2] * c.b.x() : 0.0;
          dx               = qu[0] - qu[2] * c.a.y() - lx;
          dy               = qu[1] + qu[2] * c.a.x() - ly;
        };
        const auto *c = corner_drifts_.data() + drift_first_[s];
        const auto *e = corner_drifts_.data() + drift_first_[s + 1];
        double      dx, dy;
        drift(*c, dx, dy); // the centre
        out_.peak_drift_x[s] = std::max(out_.peak_drift_x[s], std::abs(dx));
        out_.peak_drift_y[s] = std::max(out_.peak_drift_y[s], std::abs(dy));
        if (bound <= drift_sq_[s])
          continue;
        double m = drift_sq_[s];
        for (++c; c != e; ++c)
        {
          drift(*c, dx, dy);
          m = std::max(m, dx * dx + dy * dy);
        }
        drift_sq_[s] = m;
      }
      // Input and viscous power at t_n (from the step kernel), trapezoid sums from t_0.
      const double p_in   = p_in_;
      const double p_visc = p_visc_;
      if (n > 0)
      {
        w_in_ += 0.5 * dt_ * (p_in_prev_ + p_in);
        w_visc_ += 0.5 * dt_ * (p_visc_prev_ + p_visc);
      }
      p_in_prev_   = p_in;
      p_visc_prev_ = p_visc;
    }

    void Run::checkpoint(const long n)
    {
      const double t = static_cast<double>(n) * dt_;
      e_kin_         = 0.5 * v_.dot(model_.masses().cwiseProduct(v_));
      for (const WallState &wd : walls_)
        e_kin_ += 0.5 * wd.mass * wd.v * wd.v;
      e_strain_ = strain_energy();
      if (n == 0)
        e0_ = e_kin_ + e_strain_;
      double hysteretic = 0.0;
      for (const auto &iso : iso_)
        hysteretic += iso->dissipated_energy();
      const double supplied = e0_ + w_in_;
      max_supplied_         = std::max(max_supplied_, supplied);
      const double residual = std::abs(supplied - (e_kin_ + e_strain_ + w_visc_ + hysteretic +
                                                   w_contact_ + w_friction_ + w_wall_));
      last_error_           = residual / std::max(max_supplied_, 1e-300);
      max_residual_         = std::max(max_residual_, residual);
      for (const WallState &wd : walls_)
        if (!std::isfinite(wd.w_next))
        {
          std::ostringstream msg;
          msg << "central difference in plan diverged: the yielding wall of face " << wd.segment
              << " is not finite at t = " << t + dt_ << " s (step " << n + 1 << ", dt = " << dt_
              << " s)";
          throw DivergenceError(msg.str(), t + dt_, n + 1, static_cast<int>(n_ + wd.segment));
        }
      for (std::size_t i = 0; i < n_; ++i)
        if (!std::isfinite(u_np1_(static_cast<Eigen::Index>(i))))
        {
          std::ostringstream msg;
          msg << "central difference in plan diverged: u[" << i
              << "] is not finite at t = " << t + dt_ << " s (step " << n + 1 << ", dt = " << dt_
              << " s)";
          throw DivergenceError(msg.str(), t + dt_, n + 1, static_cast<int>(i));
        }
      if (e_kin_ + e_strain_ > opt_.divergence_energy_factor * max_supplied_ &&
          e_kin_ + e_strain_ > 1e-12)
      {
        Eigen::Index worst = 0;
        v_.cwiseAbs().maxCoeff(&worst);
        std::ostringstream msg;
        msg << "central difference in plan diverged: mechanical energy " << e_kin_ + e_strain_
            << " J exceeds " << opt_.divergence_energy_factor << " x the energy supplied ("
            << max_supplied_ << " J) at t = " << t << " s (step " << n << ", fastest DoF " << worst
            << ", dt = " << dt_ << " s)";
        throw DivergenceError(msg.str(), t, n, static_cast<int>(worst));
      }
      if (every_ > 0 && n % every_ == 0)
      {
        PlanHistory &h = out_.history;
        h.time.push_back(t);
        for (std::size_t i = 0; i < n_; ++i)
        {
          h.displacement.push_back(u_n_(static_cast<Eigen::Index>(i)));
          h.absolute_acceleration.push_back(a_(static_cast<Eigen::Index>(i)));
        }
        const Eigen::Vector3d q0 = u_n_.head<3>();
        for (const auto &tk : corner_t_[0])
        {
          const Point d = tk * q0;
          h.corner_displacement.push_back(d.x());
          h.corner_displacement.push_back(d.y());
        }
        for (std::size_t c = 0; c < laws_.size(); ++c)
        {
          h.contact_force.push_back(cf_[c]);
          h.friction_force.push_back(phi_[c]);
        }
        h.energy_error.push_back(last_error_);
      }
    }

    void Run::initial_conditions()
    {
      const auto nn = static_cast<Eigen::Index>(n_);
      // Initial conditions: u_{−1}, u_{−2} by a Taylor expansion with a_0 = M⁻¹(p_0 − C·v_0 −
      // K·u_0 − f_nl(u_0)), the laws only trialled (the first step commits them).
      Eigen::VectorXd u0 = Eigen::VectorXd::Zero(nn), v0 = Eigen::VectorXd::Zero(nn);
      if (!opt_.initial_displacement.empty())
        u0 = Eigen::Map<const Eigen::VectorXd>(opt_.initial_displacement.data(), nn);
      if (!opt_.initial_velocity.empty())
        v0 = Eigen::Map<const Eigen::VectorXd>(opt_.initial_velocity.data(), nn);
      Eigen::VectorXd f0  = Eigen::VectorXd::Zero(nn);
      const auto     &kin = model_.isolator_kinematics();
      for (std::size_t j = 0; j < iso_.size(); ++j)
      {
        f0.head<3>() +=
          kin[j].transpose() * iso_[j]->set_trial(kin[j] * u0.head<3>(), kin[j] * v0.head<3>());
        iso_[j]->revert_to_last_commit();
      }
      for (std::size_t c = 0; c < laws_.size(); ++c)
      {
        const PlanContact &pc    = model_.contacts()[c];
        const double       delta = pc.normal_row.dot(u0.head<3>()) - pc.gap;
        const double       rate  = pc.normal_row.dot(v0.head<3>());
        dp_[c]                   = delta - dt_ * rate;
        dpp_[c]                  = delta - 2.0 * dt_ * rate;
        if (delta > 0.0)
        {
          const double fc = pc.weight * laws_[c]->set_trial(delta, rate).force;
          f0.head<3>() += fc * pc.normal_row.transpose();
          laws_[c]->revert_to_last_commit();
          if (!walls_.empty() && wall_of_segment_[pc.segment] >= 0)
            walls_[static_cast<std::size_t>(wall_of_segment_[pc.segment])].contact += fc;
        }
      }
      double ag_x0, ag_y0;
      ground(0, ag_x0, ag_y0);
      const Eigen::VectorXd &m = model_.masses();
      const Eigen::VectorXd  a0 =
        (-(rx_m_ * ag_x0 + ry_m_ * ag_y0) - model_.damping() * v0 - model_.stiffness() * u0 - f0)
          .cwiseQuotient(m);
      // The yielding walls start at rest at w = 0 (the law trialled, the first step commits it).
      for (WallState &wd : walls_)
      {
        const double fb = wd.law->set_trial(0.0, 0.0).force;
        wd.law->revert_to_last_commit();
        const double aw =
          (-wd.mass * (wd.nx * ag_x0 + wd.ny * ag_y0) - (fb - wd.contact)) / wd.mass;
        wd.contact = 0.0;
        wd.w1      = 0.5 * dt_ * dt_ * aw;
        wd.w2      = 2.0 * dt_ * dt_ * aw;
        wd.dw      = -0.5 * dt_ * dt_ * aw;
      }
      u_n_   = u0;
      u_nm1_ = u0 - dt_ * v0 + 0.5 * dt_ * dt_ * a0;
      u_nm2_ = u0 - 2.0 * dt_ * v0 + 2.0 * dt_ * dt_ * a0;
      du_n_  = dt_ * v0 - 0.5 * dt_ * dt_ * a0;
      // z_{−1} = A⁻¹K·u_{−1}.
      z_ = hg_.middleRows(nn, nn) * (u_n_ - du_n_);
      set_up_kernel();
    }

    void Run::collect_results()
    {
      out_.dt       = dt_;
      out_.n_steps  = n_steps_;
      out_.duration = static_cast<double>(n_steps_) * dt_;
      PlanEnergy &e = out_.energy;
      e.initial     = e0_;
      e.input       = w_in_;
      e.kinetic     = e_kin_;
      e.strain      = e_strain_;
      e.viscous     = w_visc_;
      for (const auto &iso : iso_)
        e.hysteretic += iso->dissipated_energy();
      e.contact_work           = w_contact_;
      out_.peak_isolator_force = std::sqrt(iso_peak_sq_);
      e.friction               = w_friction_;
      for (std::size_t c = 0; c < laws_.size(); ++c)
      {
        out_.contacts[c].dissipated_energy =
          model_.contacts()[c].weight * laws_[c]->dissipated_energy();
        e.impact_dissipated += out_.contacts[c].dissipated_energy;
      }
      for (std::size_t i = 0; i < n_; ++i)
      {
        out_.peak_displacement[i]          = peak_u_(static_cast<Eigen::Index>(i));
        out_.peak_absolute_acceleration[i] = peak_a_(static_cast<Eigen::Index>(i));
      }
      for (std::size_t l = 0; l < corner_sq_.size(); ++l)
      {
        out_.peak_corner_displacement[l]     = std::sqrt(corner_sq_[l]);
        out_.peak_horizontal_acceleration[l] = std::sqrt(accel_sq_[l]);
      }
      for (std::size_t q = 0; q < drift_sq_.size(); ++q)
        out_.peak_corner_drift[q] = std::sqrt(drift_sq_[q]);
      e.wall_work = w_wall_;
      for (const WallState &wd : walls_)
      {
        PlanYieldingWallResult y;
        y.segment              = wd.segment;
        y.capacity             = wd.law->parameters().capacity;
        y.failure_displacement = wd.law->parameters().failure_displacement;
        y.peak_resistance      = wd.law->peak_resistance();
        y.peak_displacement    = wd.law->peak_deformation();
        y.permanent_set        = wd.law->permanent_indentation();
        y.final_displacement   = wd.w;
        y.plastic_work         = wd.law->plastic_work();
        y.radiated_work        = wd.law->radiated_work();
        y.failure_time         = wd.failure_time;
        e.wall_plastic += y.plastic_work;
        e.wall_radiated += y.radiated_work;
        out_.yielding_walls.push_back(y);
      }
      e.relative_error     = last_error_;
      e.max_relative_error = max_residual_ / std::max(max_supplied_, 1e-300);
    }

    PlanResponse Run::execute()
    {
      initial_conditions();
      // The check points (n a multiple of every_ or of check_every_, and the last step) by
      // counting down, not by a division per step; every_ divides check_every_ when both are set.
      const long period = every_ > 0 && check_every_ % every_ == 0 ? every_ : check_every_;
      const bool exact  = every_ == 0 || check_every_ % every_ == 0;
      long       to_go  = 0;
      for (long n = 0; n <= n_steps_; ++n)
      {
        double ag_x, ag_y;
        ground(n, ag_x, ag_y);
        forces(n, u_n_, u_nm1_, u_nm2_);
        advance(ag_x, ag_y);
        bookkeeping(n);
        const bool due =
          exact ? to_go == 0 : (every_ > 0 && n % every_ == 0) || n % check_every_ == 0;
        to_go = to_go == 0 ? period - 1 : to_go - 1;
        if (due || n == n_steps_)
          checkpoint(n);
        u_nm2_.swap(u_nm1_);
        u_nm1_.swap(u_n_);
        u_n_.swap(u_np1_);
        du_n_.swap(du_np1_);
        for (WallState &wd : walls_)
        {
          wd.w2 = wd.w1;
          wd.w1 = wd.w;
          wd.w  = wd.w_next;
          wd.dw = wd.dw_next;
        }
      }

      collect_results();
      return out_;
    }
  } // namespace

  PlanModel::PlanModel(const PlanScene &scene)
    : building_(scene.building)
    , moat_(scene.moat)
  {
    validate(building_);
    mass_      = plan_masses(building_);
    stiffness_ = plan_stiffness(building_, false);
    damping_   = plan_damping(building_);
    for (const PlanIsolatorSpec &iso : building_.isolators)
      isolator_t_.push_back(level_kinematics(building_, 0, iso.position));
    if (moat_)
    {
      contacts_ = moat_contacts(*moat_, building_);
      // The yielding faces' DOFs: w along the face's normal away from the slab (the wall
      // counter-clockwise, as the contacts number its faces).
      const Polygon     wall = counter_clockwise(moat_->wall);
      const std::size_t nw   = wall.size();
      for (const PlanYieldingWall &y : moat_->yielding)
      {
        const Point t = (wall[(y.segment + 1) % nw] - wall[y.segment]).normalized();
        walls_.push_back({y.segment,
                          Point(t.y(), -t.x()),
                          y.params.mass,
                          std::make_shared<const WallBackfillLaw>(y.params)});
      }
    }
  }

  Eigen::MatrixXd PlanModel::initial_stiffness_matrix() const
  {
    return plan_stiffness(building_, true);
  }

  std::size_t PlanResponse::n_impacts() const
  {
    std::size_t n = 0;
    for (const PlanContactResult &c : contacts)
      n += c.impacts.size();
    return n;
  }

  PlanCentralDifference::PlanCentralDifference(PlanModel model, PlanOptions options)
    : CentralDifferenceMethod(std::move(model), std::move(options))
  {
    check_stepping(options_, model_.n_dofs());
    stability_ = plan_stability(model_, options_.expected_max_penetration);
  }

  PlanResponse PlanCentralDifference::run(const PlanGroundMotion &motion) const
  {
    Run run(*this, motion);
    return run.execute();
  }
} // namespace kimp::lumped::plan
