// Central difference method for pounding (thesis eq. 3.9-3.13): the stability limit, the choice of
// Δt, the block-wise run loop and the stepper API. The kernels are in central_difference_fused.cc
// (<= 8 DOFs) and central_difference_reference.cc; set-up and check points in
// central_difference_session.cc.
#include "lumped/integrators/central_difference.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "lumped/integrators/central_difference_session.h"
#include "lumped/integrators/integration_errors.h"
#include "lumped/integrators/largest_omega.h"
#include "lumped/parameter_check.h"

namespace kimp::lumped
{
  namespace
  {
    /// largest_omega() of the model's masses and the stiffness `k`.
    double largest_omega(const PoundingModel &model, const Eigen::MatrixXd &k)
    {
      const std::vector<double> &m = model.masses();
      return lumped::largest_omega(
        Eigen::Map<const Eigen::VectorXd>(m.data(), static_cast<Eigen::Index>(m.size())),
        k);
    }
  } // namespace

  StabilityLimit stability_limit(const PoundingModel &model, const double expected_max_penetration)
  {
    require_expected_penetration(expected_max_penetration);
    StabilityLimit  s;
    Eigen::MatrixXd k = model.initial_stiffness_matrix();
    s.omega_structure = largest_omega(model, k);
    std::string impact_name;
    for (const ContactPair &c : model.contacts())
    {
      const double kt = c.law->stability_stiffness(expected_max_penetration);
      note_impact(s, impact_name, kt, c.effective_mass, c.name);
      if (c.left_dof >= 0)
        k(c.left_dof, c.left_dof) += kt;
      if (c.right_dof >= 0)
        k(c.right_dof, c.right_dof) += kt;
      if (c.left_dof >= 0 && c.right_dof >= 0)
      {
        k(c.left_dof, c.right_dof) -= kt;
        k(c.right_dof, c.left_dof) -= kt;
      }
    }
    s.omega_closed = model.contacts().empty() ? s.omega_structure : largest_omega(model, k);
    std::ostringstream closed;
    closed << "structure with all contacts closed: omega_max = " << s.omega_closed
           << " rad/s with k_t at a penetration of " << expected_max_penetration << " m";
    set_critical_step(s, impact_name, expected_max_penetration, closed.str());
    return s;
  }

  CentralDifference::CentralDifference(PoundingModel model, CentralDifferenceOptions options)
    : CentralDifferenceMethod(std::move(model), std::move(options))
  {
    check_stepping(options_, model_.n_dofs());
    const ParameterCheck check("central_difference.");
    const int            lanes = options_.vector_lanes;
    check(lanes == 0 || lanes == 2 || lanes == 4 || lanes == 8,
          "vector_lanes",
          lanes,
          "must be 0 (widest available), 2, 4 or 8");
    stability_ = stability_limit(model_, options_.expected_max_penetration);
  }

  void check_stepping(const SteppingOptions &options, const std::size_t n_dofs)
  {
    check_stepping_options(options.dt,
                           options.safety,
                           options.duration,
                           options.output_interval,
                           options.divergence_energy_factor);
    require_initial_state("central_difference.",
                          options.initial_displacement,
                          options.initial_velocity,
                          n_dofs);
  }

  double central_difference_step(const double           record_dt,
                                 const SteppingOptions &options,
                                 const StabilityLimit  &stability)
  {
    if (!(record_dt > 0.0 && std::isfinite(record_dt)))
    {
      std::ostringstream msg;
      msg << "ground motion dt = " << record_dt << " s (must be > 0)";
      throw std::invalid_argument(msg.str());
    }
    if (options.dt > 0.0)
    {
      if (options.dt >= stability.dt_critical)
      {
        std::ostringstream msg;
        msg << "time step dt = " << options.dt
            << " s exceeds the stability limit of the central difference method dt_cr = "
               "2/omega_max = "
            << stability.dt_critical << " s (governed by " << stability.governing << "); use dt < "
            << stability.dt_critical << " s or dt = auto";
        throw TimeStepError(msg.str(), options.dt, stability.dt_critical);
      }
      return options.dt;
    }
    if (!std::isfinite(stability.dt_critical))
      throw std::invalid_argument("central_difference.dt = auto needs a stability limit, and "
                                  "this model has no stiffness (give dt > 0)");
    const double target = options.safety * stability.dt_critical;
    const double n_sub  = std::ceil(record_dt / target * (1.0 - 1e-12));
    return record_dt / std::max(n_sub, 1.0);
  }


  void CentralDifferenceStepper::Session::advance(long count)
  {
    while (count > 0 && step <= n_steps)
    {
      // The block ends at the next checkpoint (history sample, every check_every steps, the
      // last step)
      // so that the checks see the laws and the isolator at exactly that step.
      long next = std::min(n_steps, (step + check_every - 1) / check_every * check_every);
      if (every > 0)
        next = std::min(next, (step + every - 1) / every * every);
      const long len = std::min({next - step + 1, cdm::block_steps, count});

      // ü_g(t_n), linear interpolation; integer sub-stepping when Δt divides the record's dt.
      const double     *rec   = motion->acceleration.data();
      const std::size_t n_rec = motion->acceleration.size();
      double           *agb   = ag_block.data();
      long              q     = 0;
      // Integer sub-stepping inside the record: a run of steps within one record interval
      // (rec[j] + frac·(rec[j+1] − rec[j]), frac = s/sub) at a time.
      while (integer_substeps && q < len && rec_j + 1 < n_rec)
      {
        const double r0  = rec[rec_j];
        const double dr  = rec[rec_j + 1] - rec[rec_j];
        const long   run = std::min(len - q, sub - rec_s);
        for (long m = 0; m < run; ++m)
          agb[q + m] = r0 + (static_cast<double>(rec_s + m) * inv_sub) * dr;
        q += run;
        rec_s += run;
        if (rec_s == sub)
        {
          rec_s = 0;
          ++rec_j;
        }
      }
      for (; q < len; ++q)
      {
        std::size_t j;
        double      frac;
        if (integer_substeps)
        {
          j    = rec_j;
          frac = static_cast<double>(rec_s) * inv_sub;
          if (++rec_s == sub)
          {
            rec_s = 0;
            ++rec_j;
          }
        }
        else
        {
          const double x = static_cast<double>(step + q) * dt / motion->dt;
          j              = static_cast<std::size_t>(x);
          frac           = x - static_cast<double>(j);
        }
        double ag;
        if (j + 1 < n_rec)
          ag = rec[j] + frac * (rec[j + 1] - rec[j]);
        else
          ag = (j + 1 == n_rec && frac == 0.0) ? rec[j] : 0.0;
        agb[q] = ag;
      }

      dynamics(*this, len);
      if (fused)
        checkpoint_energies(len);
      else
        bookkeeping(len);
      const long last = step + len - 1;
      if ((every > 0 && last % every == 0) || last % check_every == 0 || last == n_steps)
        checkpoint(len - 1);
      step += len;
      count -= len;
      // Keep u_{n−2}, u_{n−1}, u_n of the next step in columns 0-2.
      for (std::size_t i = 0; i < n; ++i)
        for (long c3 = 0; c3 < 3; ++c3)
          *column(i, c3) = *column(i, len + c3);
    }
  }

  CentralDifferenceStepper::CentralDifferenceStepper(const CentralDifference &integrator)
    : integrator_(&integrator)
    , session_(std::make_unique<Session>())
  {
  }

  CentralDifferenceStepper::~CentralDifferenceStepper() = default;
  CentralDifferenceStepper::CentralDifferenceStepper(CentralDifferenceStepper &&) noexcept =
    default;
  CentralDifferenceStepper &
  CentralDifferenceStepper::operator=(CentralDifferenceStepper &&) noexcept = default;

  void CentralDifferenceStepper::init(const GroundMotion &motion)
  {
    session_->init(*integrator_, motion);
    initialised_ = true;
  }

  void CentralDifferenceStepper::require_init(const char *what) const
  {
    if (!initialised_)
      throw std::logic_error(std::string("CentralDifferenceStepper::") + what +
                             " called before init()");
  }

  void CentralDifferenceStepper::step()
  {
    require_init("step");
    if (finished())
    {
      std::ostringstream msg;
      msg << "CentralDifferenceStepper::step: the run ended at step " << session_->n_steps
          << " (t = " << static_cast<double>(session_->n_steps) * session_->dt << " s)";
      throw std::logic_error(msg.str());
    }
    session_->advance(1);
  }

  long CentralDifferenceStepper::advance(const long count)
  {
    require_init("advance");
    const long before = session_->step;
    session_->advance(std::max(count, 0L));
    return session_->step - before;
  }

  long CentralDifferenceStepper::step_index() const
  {
    return session_->step;
  }

  double CentralDifferenceStepper::time() const
  {
    return static_cast<double>(session_->step) * session_->dt;
  }

  double CentralDifferenceStepper::dt() const
  {
    return session_->dt;
  }

  long CentralDifferenceStepper::last_step() const
  {
    return session_->n_steps;
  }

  bool CentralDifferenceStepper::uses_fused_kernel() const
  {
    require_init("uses_fused_kernel");
    return session_->fused;
  }

  bool CentralDifferenceStepper::finished() const
  {
    return initialised_ && session_->step > session_->n_steps;
  }

  std::vector<double> CentralDifferenceStepper::displacement(const int level) const
  {
    require_init("displacement");
    if (level < -2 || level > 0)
      throw std::invalid_argument("CentralDifferenceStepper::displacement: level = " +
                                  std::to_string(level) + " (must be 0, -1 or -2)");
    std::vector<double> u(session_->n);
    for (std::size_t i = 0; i < u.size(); ++i)
      u[i] = *session_->column(i, 2 + level);
    return u;
  }

  Response CentralDifferenceStepper::response() const
  {
    require_init("response");
    return session_->response();
  }

  Response CentralDifference::run(const GroundMotion &motion) const
  {
    CentralDifferenceStepper stepper(*this);
    stepper.init(motion);
    stepper.advance(stepper.last_step() + 1);
    return stepper.response();
  }
} // namespace kimp::lumped
