// FreeRunPrefix: the contact-free run's check points (the dynamic part of the central difference
// session) and the restart of a run with contacts from the last one before its first contact.
#include "lumped/integrators/free_run_prefix.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "lumped/integrators/central_difference_session.h"

namespace kimp::lumped
{
  /// The dynamic state of a Session at the start of step `step` (a block boundary), and the
  /// extremes of every DOF's u over the steps from it to the next check point.
  struct FreeRunPrefix::Snapshot
  {
    long                step = 0;
    std::vector<double> columns; ///< u_{n−2}, u_{n−1}, u_n of rows 0..n (ground: n)
    std::vector<double> fused_u, fused_d, fused_z, fused_v, last_accel, fused_peaks, fused_sums;
    std::vector<double> lane_peak_u, lane_peak_a, lane_peak_d; ///< reference kernel
    double              p_in_0 = 0.0, p_visc_0 = 0.0;
    std::size_t         rec_j = 0;
    long                rec_s = 0;
    std::unique_ptr<Isolator> iso;
    double                    w_in = 0.0, w_visc = 0.0, p_in_prev = 0.0, p_visc_prev = 0.0;
    double                    e0 = 0.0, e_kin = 0.0, e_strain = 0.0;
    ResponseRecorder          rec;
    std::vector<double>       hi, lo; ///< max and min of u_i over the steps until the next point

    /// f(mine, theirs) for each member that save() and restore() copy as it is, with theirs
    /// the session's (columns, isolator and recorder need more than a copy).
    template <class Snap, class Sess, class F>
    static void each_copied(Snap &snap, Sess &s, const F &f)
    {
      f(snap.step, s.step);
      f(snap.fused_u, s.fused_u);
      f(snap.fused_d, s.fused_d);
      f(snap.fused_z, s.fused_z);
      f(snap.fused_v, s.fused_v);
      f(snap.last_accel, s.last_accel);
      f(snap.fused_peaks, s.fused_peaks);
      f(snap.fused_sums, s.fused_sums);
      if (!s.fused)
      {
        f(snap.lane_peak_u, s.lane_peak_u);
        f(snap.lane_peak_a, s.lane_peak_a);
        f(snap.lane_peak_d, s.lane_peak_d);
      }
      f(snap.p_in_0, s.p_in_0);
      f(snap.p_visc_0, s.p_visc_0);
      f(snap.rec_j, s.rec_j);
      f(snap.rec_s, s.rec_s);
      f(snap.w_in, s.w_in);
      f(snap.w_visc, s.w_visc);
      f(snap.p_in_prev, s.p_in_prev);
      f(snap.p_visc_prev, s.p_visc_prev);
      f(snap.e0, s.e0);
      f(snap.e_kin, s.e_kin);
      f(snap.e_strain, s.e_strain);
    }

    void save(CentralDifferenceStepper::Session &s)
    {
      each_copied(*this, s, [](auto &mine, const auto &theirs) { mine = theirs; });
      columns.resize(3 * (s.n + 1));
      for (std::size_t i = 0; i <= s.n; ++i)
        for (long c = 0; c < 3; ++c)
          columns[3 * i + static_cast<std::size_t>(c)] = *s.column(i, c);
      iso = s.iso ? s.iso->clone() : nullptr;
      rec = s.rec;
      hi.assign(s.n, -std::numeric_limits<double>::infinity());
      lo.assign(s.n, std::numeric_limits<double>::infinity());
    }

    /// Put this state into `s` (a session of the same model with contacts, just initialised);
    /// its contacts are left as after open steps: not called, not in contact, no force, the
    /// pre-check armed, δ_{n−1} and δ_{n−2} formed from the displacement columns.
    void restore(CentralDifferenceStepper::Session &s) const
    {
      each_copied(*this, s, [](const auto &mine, auto &theirs) { theirs = mine; });
      for (std::size_t i = 0; i <= s.n; ++i)
        for (long c = 0; c < 3; ++c)
          *s.column(i, c) = columns[3 * i + static_cast<std::size_t>(c)];
      s.iso = iso ? iso->clone() : nullptr;
      s.rec.continue_from(rec);
      s.w_contact = 0.0;
      for (std::size_t c = 0; c < s.laws.size(); ++c)
      {
        // As contacts() leaves a law it skipped: δ of the last two steps, nothing active.
        s.delta_prev[c] = (*s.column(static_cast<std::size_t>(s.left[c]), 1) -
                           *s.column(static_cast<std::size_t>(s.right[c]), 1)) -
                          s.gap[c];
        s.delta_prev2[c] = (*s.column(static_cast<std::size_t>(s.left[c]), 0) -
                            *s.column(static_cast<std::size_t>(s.right[c]), 0)) -
                           s.gap[c];
        s.active[c]      = 0;
        s.called_prev[c] = 0;
        s.cf[c]          = 0.0;
        s.gap_skip[c]    = s.gap[c];
      }
      s.deltas_current = false;
    }

    std::size_t bytes() const
    {
      return sizeof(*this) +
             sizeof(double) *
               (columns.size() + fused_u.size() * 5 + fused_peaks.size() + fused_sums.size() +
                lane_peak_u.size() + lane_peak_a.size() + lane_peak_d.size() + 2 * hi.size());
    }
  };

  namespace
  {
    template <class T>
    void put(std::string &key, const T &x)
    {
      key.append(reinterpret_cast<const char *>(&x), sizeof(T));
    }

    void put(std::string &key, const std::vector<double> &x)
    {
      put(key, x.size());
      key.append(reinterpret_cast<const char *>(x.data()), x.size() * sizeof(double));
    }
  } // namespace

  std::string FreeRunPrefix::contacts_key(const PoundingModel &model)
  {
    std::string key;
    for (const ContactPair &c : model.contacts())
    {
      key += c.name;
      key += '|';
      put(key, c.left_dof);
      put(key, c.right_dof);
      put(key, c.gap);
      put(key, c.effective_mass);
      key += c.law->name();
      key += '|';
      for (const double delta : {1e-4, 1e-3, 1e-2, 5e-2})
        put(key, c.law->stability_stiffness(delta));
      // Laws have no parameter list: their response along a path of approach, indentation at
      // several rates, release and a second impact identifies them.
      std::unique_ptr<ForceLaw> law = c.law->clone();
      law->revert_to_start();
      for (const auto &[delta, rate] : {std::pair{-0.01, 0.5},
                                        std::pair{1e-4, 0.8},
                                        std::pair{1e-3, 0.6},
                                        std::pair{5e-3, 0.3},
                                        std::pair{0.02, 0.1},
                                        std::pair{0.05, 0.0},
                                        std::pair{0.03, -0.3},
                                        std::pair{0.01, -0.6},
                                        std::pair{1e-3, -0.8},
                                        std::pair{-0.01, -0.5},
                                        std::pair{2e-3, 1.5},
                                        std::pair{0.1, 2.0},
                                        std::pair{0.0, -1.0}})
      {
        put(key, law->set_trial(delta, rate).force);
        law->commit();
        put(key, law->dissipated_energy());
        put(key, law->permanent_indentation());
        put(key, law->in_contact());
      }
    }
    return key;
  }

  std::string
  FreeRunPrefix::key(const CentralDifference &cdm, const double dt, const GroundMotion &motion)
  {
    const PoundingModel            &m   = cdm.model();
    const CentralDifferenceOptions &opt = cdm.options();
    std::string                     key;
    put(key, m.n_dofs());
    put(key, m.masses());
    put(key, m.stiffness().diag);
    put(key, m.stiffness().upper);
    put(key, m.damping().diag);
    put(key, m.damping().upper);
    for (const Storey &s : m.storeys())
    {
      put(key, s.lower_dof);
      put(key, s.upper_dof);
    }
    key += '|';
    if (const Isolator *proto = m.isolator())
    {
      // Isolators have no parameter list: their name and their response along a fixed path of
      // displacements and velocities (elastic, yielding, reversing) identify them.
      key += proto->name();
      put(key, proto->initial_stiffness());
      put(key, proto->viscous_coefficient());
      std::unique_ptr<Isolator> iso = proto->clone();
      iso->revert_to_start();
      for (const double u : {1e-4, 2e-3, 1e-2, 5e-2, 0.2, 0.6, 0.3, -0.1, -0.5, 0.05, 1.5})
        for (const double v : {0.02, 1.0})
        {
          put(key, iso->set_trial(u, v).force);
          iso->commit();
          put(key, iso->stored_energy());
          put(key, iso->dissipated_energy());
        }
    }
    key += '|';
    put(key, dt);
    put(key, opt.duration);
    put(key, opt.output_interval);
    put(key, static_cast<int>(opt.law_velocity));
    put(key, opt.initial_displacement);
    put(key, opt.initial_velocity);
    put(key, opt.divergence_energy_factor);
    put(key, static_cast<int>(opt.kernel));
    put(key, opt.vector_lanes);
    put(key, motion.dt);
    put(key, motion.acceleration);
    return key;
  }

  FreeRunPrefix::FreeRunPrefix(const CentralDifference &free, const GroundMotion &motion)
  {
    if (free.options().output_interval > 0.0)
      throw std::invalid_argument("FreeRunPrefix: runs with histories (output_interval > 0) "
                                  "cannot be shared");
    CentralDifferenceStepper stepper(free);
    stepper.init(motion);
    key_                                     = key(free, stepper.dt(), motion);
    CentralDifferenceStepper::Session &s     = *stepper.session_;
    const std::size_t                  n     = s.n;
    auto                               point = std::make_unique<Snapshot>();
    point->save(s);
    Snapshot *current = point.get();
    points_.push_back(std::move(point));
    while (s.step <= s.n_steps)
    {
      // The block Session::advance() would take next (it ends at the next check point), so that
      // the free run is partitioned exactly as every run with contacts.
      const long next =
        std::min(s.n_steps, (s.step + s.check_every - 1) / s.check_every * s.check_every);
      const long len = std::min(next - s.step + 1, cdm::block_steps);
      s.advance(len);
      // Columns 2..len+1 hold u at the block's steps: what the contact pre-check looks at.
      for (std::size_t i = 0; i < n; ++i)
        for (long c = 2; c < len + 2; ++c)
        {
          const double u = *s.column(i, c);
          current->hi[i] = std::max(current->hi[i], u);
          current->lo[i] = std::min(current->lo[i], u);
        }
      if ((s.step - 1) % s.check_every == 0 || s.step > s.n_steps)
      {
        point = std::make_unique<Snapshot>();
        point->save(s);
        current = point.get();
        points_.push_back(std::move(point));
      }
    }
    response_ = stepper.response();
  }

  FreeRunPrefix::~FreeRunPrefix() = default;

  std::size_t FreeRunPrefix::start_point(const CentralDifference &with_contacts) const
  {
    const PoundingModel &m      = with_contacts.model();
    const int            ground = static_cast<int>(m.n_dofs());
    // A permanent pair acts from the start: its state is not the free run's.
    for (const ContactPair &c : m.contacts())
      if (c.permanent)
        return 0;
    // The last point before the first interval in which some contact may close.
    for (std::size_t p = 0; p + 1 < points_.size(); ++p)
    {
      const Snapshot &pt = *points_[p];
      for (const ContactPair &c : m.contacts())
      {
        const int    l  = c.left_dof >= 0 ? c.left_dof : ground;
        const int    r  = c.right_dof >= 0 ? c.right_dof : ground;
        const double hl = l == ground ? 0.0 : pt.hi[static_cast<std::size_t>(l)];
        const double lr = r == ground ? 0.0 : pt.lo[static_cast<std::size_t>(r)];
        // δ = (u_L − u_R) − gap <= (max u_L − min u_R) − gap (rounding is monotonic).
        if (!(hl - lr <= c.gap))
          return p;
      }
    }
    return points_.size() - 1;
  }

  long FreeRunPrefix::steps_skipped(const CentralDifference &with_contacts) const
  {
    const long step = points_[start_point(with_contacts)]->step;
    return step >= 2 ? step : 0;
  }

  Response FreeRunPrefix::run(const CentralDifference &with_contacts,
                              const GroundMotion      &motion) const
  {
    CentralDifferenceStepper stepper(with_contacts);
    stepper.init(motion);
    if (key(with_contacts, stepper.dt(), motion) != key_)
      throw std::invalid_argument("FreeRunPrefix::run: the model, time step, options or ground "
                                  "motion differ from the free run's");
    const std::string contacts = contacts_key(with_contacts.model());
    {
      const std::lock_guard<std::mutex> lock(memo_mutex_);
      const auto                        found = memo_.find(contacts);
      if (found != memo_.end())
        return *found->second;
    }
    CentralDifferenceStepper::Session &s = *stepper.session_;
    const std::size_t                  p = start_point(with_contacts);
    // Steps 0 and 1 read δ_{−1}, δ_{−2} from the initial conditions, not from the columns.
    if (p > 0 && points_[p]->step >= 2)
      points_[p]->restore(s);
    s.advance(s.n_steps + 1 - s.step);
    auto response = std::make_shared<const Response>(stepper.response());
    const std::lock_guard<std::mutex> lock(memo_mutex_);
    if (memo_.size() < 4096)
      memo_.emplace(contacts, response);
    return *response;
  }

  std::size_t FreeRunPrefix::memory_bytes() const
  {
    std::size_t bytes = key_.size();
    for (const auto &p : points_)
      bytes += p->bytes();
    return bytes;
  }
} // namespace kimp::lumped
