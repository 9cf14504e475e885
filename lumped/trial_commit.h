// The trial/commit protocol of the lumped engine's path-dependent elements: the contact force
// laws and the isolators, planar and in plan (docs/architecture.md "Force laws").
#pragma once

namespace kimp::lumped
{
  /**
   * An element with a committed and a trial state. Each interface adds its own `set_trial(...)`,
   * which starts from the committed state every time (repeated calls with the same arguments
   * return the same result), never changes the committed state and does no I/O.
   */
  class TrialCommit
  {
  public:
    virtual ~TrialCommit() = default;

    /// Accepts the last trial state.
    virtual void commit() = 0;
    /// Discards the trial state: back to the committed one.
    virtual void revert_to_last_commit() = 0;
    /// Returns to the virgin state.
    virtual void revert_to_start() = 0;
  };
} // namespace kimp::lumped
