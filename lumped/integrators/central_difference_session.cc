// Set-up and check points of a central difference run (CentralDifferenceStepper::Session): the
// matrices of both kernels, the laws, the initial conditions, the energies and divergence checks
// at the check points, history samples and the final Response.
#include "lumped/integrators/central_difference_session.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "lumped/integrators/integration_errors.h"

namespace kimp::lumped
{
  TridiagonalMatrix CentralDifferenceStepper::Session::prepare_reference_matrices()
  {
    const double      inv_dt2     = 1.0 / (dt * dt);
    const double      half_inv_dt = 0.5 / dt;
    TridiagonalMatrix a(n);
    b_diag.assign(n, 0.0);
    d_diag.assign(n, 0.0);
    b_upper.assign(n > 0 ? n - 1 : 0, 0.0);
    d_upper.assign(n > 0 ? n - 1 : 0, 0.0);
    for (std::size_t i = 0; i < n; ++i)
    {
      const double mi = mass[i];
      a.diag[i]       = mi * inv_dt2 + c->diag[i] * half_inv_dt;
      b_diag[i]       = 2.0 * mi * inv_dt2 - k->diag[i];
      d_diag[i]       = -mi * inv_dt2 + c->diag[i] * half_inv_dt;
    }
    for (std::size_t i = 0; i + 1 < n; ++i)
    {
      a.upper[i] = c->upper[i] * half_inv_dt;
      b_upper[i] = -k->upper[i];
      d_upper[i] = c->upper[i] * half_inv_dt;
    }
    a_inverse = std::make_unique<cdm::EffectiveMatrixInverse>(a);

    return a;
  }

  void CentralDifferenceStepper::Session::choose_kernel()
  {
    // The fused kernels (up to 8 DOFs, or any size): every storey between DOF i − 1 and DOF i or
    // between the ground and DOF i (its drift is then lane i of u − shifted u).
    bool fits = n >= 1;
    drift_mask.assign(n, 0.0);
    for (const Storey &st : model->storeys())
    {
      fits = fits && st.upper_dof >= 0 && st.upper_dof < static_cast<int>(n) &&
             (st.lower_dof == st.upper_dof - 1 || st.lower_dof == -1);
      if (fits)
        drift_mask[static_cast<std::size_t>(st.upper_dof)] = st.lower_dof == -1 ? 0.0 : 1.0;
    }
    // Beyond 8 DOFs the any-size kernel's dense products cost O(b²) per building block of b
    // DOFs against the reference kernel's O(b) Thomas sweeps: it wins up to ≈ 20 DOFs per block
    // (bench/lumped_bench.cc BM_CdmTallBuilding), so automatic keeps it to blocks of at most
    // max_dense (16) DOFs, e.g. every building of the adjacent-building studies.
    std::size_t largest_block = n > 0 ? 1 : 0, block = 1;
    for (std::size_t i = 0; i + 1 < n; ++i)
    {
      block         = k->upper[i] != 0.0 || c->upper[i] != 0.0 ? block + 1 : 1;
      largest_block = std::max(largest_block, block);
    }
    const bool anysize_pays = n <= 8 || largest_block <= cdm::EffectiveMatrixInverse::max_dense;
    fused                   = fits && (opt->kernel == CdmKernel::any_size ||
                     (opt->kernel == CdmKernel::automatic && anysize_pays));
    dense_inverse.clear();
    dense_f.clear();
    dense_g.clear();
    dense_am.clear();
    lanes    = cdm::fused_lanes(opt->vector_lanes);
    padded_n = (n + static_cast<std::size_t>(lanes) - 1) / static_cast<std::size_t>(lanes) *
               static_cast<std::size_t>(lanes);
    fused_u.assign(padded_n, 0.0);
    fused_z.assign(padded_n, 0.0);
    fused_v.assign(padded_n, 0.0);
    deltas_current = true;
    fused_d.assign(padded_n, 0.0);
    last_accel.assign(padded_n, 0.0);
    fused_peaks.assign(3 * padded_n, 0.0);
    fused_sums.assign(3 * padded_n, 0.0);
    drift_mask.resize(padded_n, 0.0);
    p_in_0 = p_visc_0 = 0.0;
  }

  void CentralDifferenceStepper::Session::prepare_fused_matrices(const TridiagonalMatrix &a)
  {
    const std::size_t     p   = padded_n;
    const Eigen::MatrixXd inv = a.to_dense().inverse();
    const Eigen::MatrixXd kg  = inv * k->to_dense();
    const Eigen::MatrixXd h   = inv * (c->to_dense() * (1.0 / dt) + k->to_dense());
    const Eigen::VectorXd am =
      inv * Eigen::Map<const Eigen::VectorXd>(mass.data(), static_cast<Eigen::Index>(n));
    // Columns up to a multiple of 4 (zero): the any-size kernel sums four columns at a time.
    const auto pad = [&](const Eigen::MatrixXd &x, std::vector<double> &out)
    {
      out.assign(p * ((static_cast<std::size_t>(x.cols()) + 3) / 4 * 4), 0.0);
      for (Eigen::Index j = 0; j < x.cols(); ++j)
        for (Eigen::Index i = 0; i < x.rows(); ++i)
          out[static_cast<std::size_t>(j) * p + static_cast<std::size_t>(i)] = x(i, j);
    };
    pad(inv, dense_inverse);
    pad(h, dense_f);
    pad(kg, dense_g);
    pad(am, dense_am);
    // Any-size kernel: the columns each row vector needs (its buildings' blocks).
    const std::size_t n_vectors = p / static_cast<std::size_t>(lanes);
    any_lo.assign(n_vectors, 0);
    any_hi.assign(n_vectors, 0);
    for (std::size_t v = 0; v < n_vectors; ++v)
    {
      std::size_t first = n, end = 0;
      for (std::size_t i = v * static_cast<std::size_t>(lanes);
           i < std::min(n, (v + 1) * static_cast<std::size_t>(lanes));
           ++i)
        for (std::size_t j = 0; j < n; ++j)
        {
          const std::size_t at = j * p + i;
          if (dense_inverse[at] != 0.0 || dense_f[at] != 0.0 || dense_g[at] != 0.0)
          {
            first = std::min(first, j);
            end   = std::max(end, j + 1);
          }
        }
      any_lo[v] = static_cast<int>(first < end ? first / 4 * 4 : 0);
      any_hi[v] = static_cast<int>(first < end ? (end + 3) / 4 * 4 : 0);
    }
    // u, Δu twice (the any-size kernel's double buffer, up to a multiple of 4), v.
    any_work.assign(p + 2 * std::max(p, (n + 3) / 4 * 4) + p, 0.0);
  }

  void CentralDifferenceStepper::Session::prepare_buffers()
  {
    width = static_cast<std::size_t>(cdm::block_steps) + 3;
    if (fused)
    {
      // One column of padded_n (+ a vector if no padding lane is left for the ground) per step.
      row_stride = 1;
      col_stride = padded_n + (padded_n == n ? static_cast<std::size_t>(lanes) : 0);
      u_block.assign(width * col_stride, 0.0);
    }
    else
    {
      row_stride = width;
      col_stride = 1;
      u_block.assign((n + 1) * width, 0.0);
    }
    ag_block.assign(static_cast<std::size_t>(cdm::block_steps), 0.0);
    velocity.assign(n * static_cast<std::size_t>(cdm::block_steps), 0.0);
    mv.assign(static_cast<std::size_t>(cdm::block_steps), 0.0);
    cvv.assign(static_cast<std::size_t>(cdm::block_steps), 0.0);
    force.assign(n + 1, 0.0); // [n]: the ground, absorbs wall reactions
    rhs.assign(n, 0.0);
    solution.assign(n, 0.0);
  }

  void CentralDifferenceStepper::Session::prepare_contacts()
  {
    const int ground_slot = static_cast<int>(n);
    laws.clear();
    left.clear();
    right.clear();
    gap.clear();
    std::vector<char> carries_force(n + 1, 0);
    if (iso)
      carries_force[0] = 1;
    for (const ContactPair &cp : model->contacts())
    {
      std::unique_ptr<ForceLaw> law = cp.law->clone();
      law->revert_to_start();
      laws.push_back(std::move(law));
      left.push_back(cp.left_dof >= 0 ? cp.left_dof : ground_slot);
      right.push_back(cp.right_dof >= 0 ? cp.right_dof : ground_slot);
      carries_force[static_cast<std::size_t>(left.back())]  = 1;
      carries_force[static_cast<std::size_t>(right.back())] = 1;
      gap.push_back(cp.gap);
    }
    left_row.clear();
    right_row.clear();
    for (std::size_t q = 0; q < left.size(); ++q)
    {
      left_row.push_back(static_cast<std::size_t>(left[q]) * row_stride + 2 * col_stride);
      right_row.push_back(static_cast<std::size_t>(right[q]) * row_stride + 2 * col_stride);
    }
    force_dofs.clear();
    for (std::size_t j = 0; j < n; ++j)
      if (carries_force[j])
        force_dofs.push_back(static_cast<int>(j));
    const std::size_t nc = laws.size();
    // Not armed at first: called_prev starts at 1, so the first step takes the full path.
    gap_skip.assign(nc, -std::numeric_limits<double>::infinity());
    cf.assign(nc, 0.0);
    // A permanent pair's law is in contact from the start: evaluated at every step.
    active.assign(nc, 0);
    for (std::size_t q = 0; q < nc; ++q)
      active[q] = laws[q]->in_contact() ? 1 : 0;
    called_prev.assign(nc, 1);
    delta_prev.assign(nc, 0.0);
    delta_prev2.assign(nc, 0.0);
    storey_low.clear();
    storey_up.clear();
    for (const Storey &st : model->storeys())
    {
      storey_low.push_back(st.lower_dof >= 0 ? st.lower_dof : ground_slot);
      storey_up.push_back(st.upper_dof);
    }
    lane_peak_u.assign(n * static_cast<std::size_t>(cdm::block_steps), 0.0);
    lane_peak_a.assign(n * static_cast<std::size_t>(cdm::block_steps), 0.0);
    lane_peak_d.assign(storey_low.size() * static_cast<std::size_t>(cdm::block_steps), 0.0);
  }

  void CentralDifferenceStepper::Session::initial_conditions(const GroundMotion &g)
  {
    // Initial conditions: u_{−1}, u_{−2} from a Taylor expansion with a_0 = M⁻¹(p_0 − C·v_0 −
    // K·u_0 − f_nl(u_0)); the laws are only trialled here, the first step commits them.
    const std::size_t   nc = laws.size();
    std::vector<double> u0(n, 0.0), v0(n, 0.0);
    if (!opt->initial_displacement.empty())
      u0 = opt->initial_displacement;
    if (!opt->initial_velocity.empty())
      v0 = opt->initial_velocity;
    std::vector<double> f0(n + 1, 0.0), cv(n), ku(n);
    if (iso)
    {
      f0[0] += iso->set_trial(u0[0], v0[0]).force;
      iso->revert_to_last_commit();
    }
    std::vector<double> u0g = u0;
    u0g.push_back(0.0);
    std::vector<double> v0g = v0;
    v0g.push_back(0.0);
    for (std::size_t q = 0; q < nc; ++q)
    {
      const double delta =
        u0g[static_cast<std::size_t>(left[q])] - u0g[static_cast<std::size_t>(right[q])] - gap[q];
      const double rate =
        v0g[static_cast<std::size_t>(left[q])] - v0g[static_cast<std::size_t>(right[q])];
      delta_prev[q]  = delta - dt * rate;
      delta_prev2[q] = delta - 2.0 * dt * rate;
      if (delta > 0.0 || active[q])
      {
        const double fq = laws[q]->set_trial(delta, rate).force;
        laws[q]->revert_to_last_commit();
        f0[static_cast<std::size_t>(left[q])] += fq;
        f0[static_cast<std::size_t>(right[q])] -= fq;
      }
    }
    c->multiply(v0.data(), cv.data());
    k->multiply(u0.data(), ku.data());
    const double ag0 = g.acceleration[0];
    for (std::size_t i = 0; i < n; ++i)
    {
      const double a0 = (-mass[i] * ag0 - cv[i] - ku[i] - f0[i]) / mass[i];
      *column(i, 2)   = u0[i];
      *column(i, 1)   = u0[i] - dt * v0[i] + 0.5 * dt * dt * a0;
      *column(i, 0)   = u0[i] - 2.0 * dt * v0[i] + 2.0 * dt * dt * a0;
      fused_u[i]      = u0[i];
      fused_d[i]      = dt * v0[i] - 0.5 * dt * dt * a0; // u_0 − u_{−1} without cancellation
    }
    if (fused)
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) // z_{−1} = A⁻¹K·u_{−1}
          fused_z[i] += dense_g[j * padded_n + i] * (fused_u[j] - fused_d[j]);
  }

  void CentralDifferenceStepper::Session::prepare_recording(const GroundMotion &g)
  {
    const double ratio = g.dt / dt;
    sub                = std::lround(ratio);
    integer_substeps   = sub > 0 && std::abs(ratio - static_cast<double>(sub)) < 1e-9 * ratio;
    inv_sub            = 1.0 / static_cast<double>(sub > 0 ? sub : 1);
    rec_j              = 0;
    rec_s              = 0;
    every = opt->output_interval > 0.0 ? std::max(1L, std::lround(opt->output_interval / dt)) : 0L;
    check_every = 512;
    if (every > 0 && every <= 512)
      check_every = every * (512 / every);
    else if (every > 512)
      for (long parts = (every + 511) / 512; parts <= every; ++parts)
        if (every % parts == 0)
        {
          check_every = every / parts;
          break;
        }
    rec.start(*model, dt, n_steps, every);
    w_in = w_visc = w_contact = p_in_prev = p_visc_prev = 0.0;
    e0 = e_kin = e_strain = 0.0;
  }

  void CentralDifferenceStepper::Session::init(const CentralDifference &cdm, const GroundMotion &g)
  {
    model  = &cdm.model();
    opt    = &cdm.options();
    motion = &g;
    if (!(g.dt > 0.0) || g.acceleration.empty())
      throw std::invalid_argument("ground motion '" + g.name +
                                  "': dt must be > 0 and the record non-empty");
    dt = cdm.time_step(g.dt);
    const double duration =
      opt->duration > 0.0 ? opt->duration : g.dt * static_cast<double>(g.acceleration.size());
    n_steps = std::lround(duration / dt);
    step    = 0;
    scheme  = opt->law_velocity;
    n       = model->n_dofs();
    mass    = model->masses();
    k       = &model->stiffness();
    c       = &model->damping();

    const TridiagonalMatrix a     = prepare_reference_matrices();
    const Isolator         *proto = model->isolator();
    iso.reset();
    if (proto)
    {
      iso = proto->clone();
      iso->revert_to_start();
    }
    choose_kernel();
    if (fused)
      prepare_fused_matrices(a);
    prepare_buffers();
    prepare_contacts();
    initial_conditions(g);
    prepare_recording(g);

    // Up to 8 DOFs the fused kernel keeps the whole state in registers (unless the any-size
    // kernel is requested, for comparisons).
    const bool small = n <= 8 && opt->kernel == CdmKernel::automatic;
    dynamics         = !fused ? cdm::reference_kernel(iso.get()) :
                       small  ? cdm::fused_kernel(n, lanes, iso.get()) :
                                cdm::anysize_kernel(lanes, iso.get());
  }

  /// E_kin and E_strain at the block's last step if it is a check point (E_0, checks, samples,
  /// end: the only places they are used); for the fused kernel also E_0 at step 0.
  void CentralDifferenceStepper::Session::checkpoint_energies(const long len)
  {
    const long last = step + len - 1;
    if ((every > 0 && last % every == 0) || last % check_every == 0 || last == n_steps)
    {
      const std::size_t B   = static_cast<std::size_t>(cdm::block_steps);
      const std::size_t q   = static_cast<std::size_t>(len - 1);
      double            mvv = 0.0, kuu = 0.0;
      for (std::size_t i = 0; i < n; ++i)
      {
        const double vi = velocity[i * B + q];
        const double ui = *column(i, len + 1);
        mvv += mass[i] * vi * vi;
        kuu += k->diag[i] * ui * ui;
      }
      for (std::size_t i = 0; i + 1 < n; ++i)
        kuu += 2.0 * k->upper[i] * *column(i, len + 1) * *column(i + 1, len + 1);
      e_kin    = 0.5 * mvv;
      e_strain = 0.5 * kuu + (iso ? iso->stored_energy() : 0.0);
    }
    if (!fused)
      return;
    // The fused kernel keeps per-DOF sums; the trapezoid rule over steps 0..n is
    // W(t_n) = Δt·(Σ_{q<=n} p_q − (p_0 + p_n)/2), evaluated here at the check points (step 0 is
    // a block of its own and a check point). max_supplied is therefore the maximum of E_0 + W_in
    // over the check points (the reference kernel: over every step).
    if (!((every > 0 && last % every == 0) || last % check_every == 0 || last == n_steps))
      return;
    const std::size_t B    = static_cast<std::size_t>(cdm::block_steps);
    const std::size_t q    = static_cast<std::size_t>(len - 1);
    const std::size_t p    = padded_n;
    double            mv_n = 0.0, cvv_n = 0.0, sum_in = 0.0, sum_visc = 0.0;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double vi = velocity[i * B + q];
      mv_n += mass[i] * vi;
      cvv_n += c->diag[i] * vi * vi;
      sum_in -= mass[i] * fused_sums[i];
      sum_visc += c->diag[i] * fused_sums[p + i];
    }
    for (std::size_t i = 0; i + 1 < n; ++i)
    {
      cvv_n += 2.0 * c->upper[i] * velocity[i * B + q] * velocity[(i + 1) * B + q];
      sum_visc += 2.0 * c->upper[i] * fused_sums[2 * p + i];
    }
    const double p_in_n = -ag_block[q] * mv_n;
    if (last == 0)
    {
      e0       = e_kin + e_strain;
      p_in_0   = p_in_n;
      p_visc_0 = cvv_n;
      w_in = w_visc = 0.0;
    }
    else
    {
      w_in   = dt * (sum_in - 0.5 * (p_in_0 + p_in_n));
      w_visc = dt * (sum_visc - 0.5 * (p_visc_0 + cvv_n));
    }
    rec.supplied(e0 + w_in);
  }

  /// Energy balance, divergence checks and the history sample at the block's last step.
  void CentralDifferenceStepper::Session::checkpoint(const long q)
  {
    const long        this_step = step + q;
    const double      t         = static_cast<double>(this_step) * dt;
    const std::size_t B         = static_cast<std::size_t>(cdm::block_steps);
    const std::size_t qq        = static_cast<std::size_t>(q);
    EnergyBalance     terms;
    terms.initial      = e0;
    terms.input        = w_in;
    terms.kinetic      = e_kin;
    terms.strain       = e_strain;
    terms.viscous      = w_visc;
    terms.hysteretic   = iso ? iso->dissipated_energy() : 0.0;
    terms.contact_work = w_contact;
    const double err   = rec.check_energy(terms);
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(*column(i, q + 3)))
      {
        std::ostringstream msg;
        msg << "central difference diverged: u[" << i << "] is not finite at t = " << t + dt
            << " s (step " << this_step + 1 << ", dt = " << dt << " s)";
        throw DivergenceError(msg.str(), t + dt, this_step + 1, static_cast<int>(i));
      }
    const double factor       = opt->divergence_energy_factor;
    const double max_supplied = rec.max_supplied();
    if (e_kin + e_strain > factor * max_supplied && e_kin + e_strain > 1e-12)
    {
      std::size_t worst = 0;
      for (std::size_t i = 1; i < n; ++i)
        if (std::abs(velocity[i * B + qq]) > std::abs(velocity[worst * B + qq]))
          worst = i;
      std::ostringstream msg;
      msg << "central difference diverged: mechanical energy " << e_kin + e_strain << " J exceeds "
          << factor << " x the energy supplied (" << max_supplied << " J) at t = " << t
          << " s (step " << this_step << ", fastest DoF " << worst << ", dt = " << dt << " s)";
      throw DivergenceError(msg.str(), t, this_step, static_cast<int>(worst));
    }
    if (every > 0 && this_step % every == 0)
    {
      // The step's acceleration (u_{n+1} − 2u_n + u_{n−1})/Δt² + ü_g(t_n), as in bookkeeping().
      const double inv_dt = 1.0 / dt;
      rec.sample(
        t,
        [&](const std::size_t i) { return *column(i, q + 2); },
        [&](const std::size_t i)
        {
          return fused ? last_accel[i] :
                         (*column(i, q + 3) - 2.0 * *column(i, q + 2) + *column(i, q + 1)) *
                             (inv_dt * inv_dt) +
                           ag_block[qq];
        },
        [&](const std::size_t s)
        {
          return *column(static_cast<std::size_t>(storey_up[s]), q + 2) -
                 *column(static_cast<std::size_t>(storey_low[s]), q + 2);
        },
        cf,
        e0 + w_in,
        err);
    }
  }

  Response CentralDifferenceStepper::Session::response() const
  {
    Response          out    = rec.finish(laws);
    const std::size_t B      = static_cast<std::size_t>(cdm::block_steps);
    const auto        reduce = [B](const std::vector<double> &per_lane, std::vector<double> &peak)
    {
      for (std::size_t i = 0; i < peak.size(); ++i)
        for (std::size_t q = 0; q < B; ++q)
          peak[i] = std::max(peak[i], per_lane[i * B + q]);
    };
    reduce(lane_peak_u, out.peak_displacement);
    reduce(lane_peak_a, out.peak_absolute_acceleration);
    reduce(lane_peak_d, out.peak_interstorey_drift);
    if (fused)
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        out.peak_displacement[i]          = fused_peaks[i];
        out.peak_absolute_acceleration[i] = fused_peaks[padded_n + i];
      }
      for (std::size_t s = 0; s < storey_up.size(); ++s)
        out.peak_interstorey_drift[s] =
          fused_peaks[2 * padded_n + static_cast<std::size_t>(storey_up[s])];
    }
    return out;
  }
} // namespace kimp::lumped
