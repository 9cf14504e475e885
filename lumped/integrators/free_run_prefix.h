// A contact-free central difference run kept at its check points, from which runs of the same
// model with contacts (sweep cases that differ only in gaps or contact laws) start at their
// first possible contact instead of at t = 0, with bitwise the same results.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "lumped/excitation/ground_motion.h"
#include "lumped/integrators/central_difference.h"
#include "lumped/integrators/response.h"

namespace kimp::lumped
{
  /**
   * Until a contact acts, a run with contacts does exactly what the run of the same model without
   * contacts does: the fused and reference kernels skip a law whose gap is open, so the
   * displacements, the isolator, the peaks and the energy sums are the same bits. A sweep over
   * gaps (or contact stiffness, COR, walls present or not) therefore shares that prefix:
   * FreeRunPrefix runs the model without contacts once, keeps its state at every check point
   * (every ≤ 512 steps; a block boundary of every run) and the extremes of each DOF's
   * displacement between check points. run() then starts a run with contacts from the last
   * check point before which no contact can have closed (u_L − u_R > gap with the extremes: a
   * conservative test), and a case that never closes a gap costs no steps at all. The free run's
   * response is the case's companion run (integration.companion).
   *
   * Results are bitwise equal to CentralDifference::run() of the model with contacts (tested in
   * tests/lumped/free_run_prefix_test.cc): the restart point is a block boundary of the full run,
   * so every later step does the same operations on the same values. A run whose contacts equal
   * an earlier one's (contacts_key()) returns that run's response. run() may be called from
   * several threads at once.
   *
   * Requirements (checked; std::invalid_argument otherwise): no histories (output_interval = 0),
   * and the run with contacts has the same masses, stiffness, damping, storeys, isolator, time
   * step, step count and options as the free run.
   */
  class FreeRunPrefix
  {
  public:
    /**
     * Run `free` (typically model.without_contacts() with the case's Δt set explicitly) under
     * `motion` to the end, keeping the check points.
     * @throws std::invalid_argument with histories requested, TimeStepError, DivergenceError.
     */
    FreeRunPrefix(const CentralDifference &free, const GroundMotion &motion);
    ~FreeRunPrefix();
    FreeRunPrefix(const FreeRunPrefix &)            = delete;
    FreeRunPrefix &operator=(const FreeRunPrefix &) = delete;

    /// The free run's response (the companion run without contacts).
    const Response &response() const { return response_; }

    /**
     * The run of `with_contacts` under `motion`, bitwise equal to with_contacts.run(motion).
     * @throws std::invalid_argument if the model, Δt, options or motion differ from the free
     *         run's (see key()); DivergenceError as run().
     */
    Response run(const CentralDifference &with_contacts, const GroundMotion &motion) const;

    /// Steps run() skips for `with_contacts` (0 when it starts at t = 0), for statistics.
    long steps_skipped(const CentralDifference &with_contacts) const;

    /**
     * Bytes that identify a free run: the model's masses, stiffness, damping, storeys and
     * isolator (its name and its response to a fixed probe path), the time step, the options
     * that change a run, and the motion's samples. Runs with equal keys may share a prefix.
     * @param dt the time step the run will use (CentralDifference::time_step), s
     */
    static std::string key(const CentralDifference &free, double dt, const GroundMotion &motion);

    /// Memory held by the check points, bytes (approximate).
    std::size_t memory_bytes() const;

    struct Snapshot; ///< one check point (free_run_prefix.cc)

    /**
     * Bytes that identify the contacts of a model: per contact its name, DOFs, gap, effective
     * mass and law (name, stability stiffness and response along a fixed path of deformations
     * and rates). Two runs of the same free run with equal contact keys are the same run.
     */
    static std::string contacts_key(const PoundingModel &model);

  private:
    /// Index of the check point to start `with_contacts` from (0: from t = 0).
    std::size_t start_point(const CentralDifference &with_contacts) const;

    std::string                            key_;
    Response                               response_;
    std::vector<std::unique_ptr<Snapshot>> points_;
    /// Responses of the runs with contacts so far, by contacts_key() (a sweep may repeat a case,
    /// e.g. a neighbour's storey count without the neighbour): computed once.
    mutable std::mutex                                             memo_mutex_;
    mutable std::map<std::string, std::shared_ptr<const Response>> memo_;
  };
} // namespace kimp::lumped
