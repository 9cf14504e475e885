// What the static solver's step control did in one run (the static plasticity solver and the
// pushover that runs it): Newton iterations, and the steps it halved, accepted at the loose
// tolerance or accepted above the IMPL-EX error tolerance.
#pragma once

namespace kimp::fem
{
  struct StaticStepStatistics
  {
    /** Newton iterations of the whole run, those of failed (halved) attempts included. */
    unsigned long n_newton_iterations = 0;
    /** Steps halved because Newton did not converge. */
    unsigned int n_newton_cuts = 0;
    /** Steps accepted at loose_tolerance, and the largest relative out-of-balance force among
     *  them. */
    unsigned int n_loose_steps          = 0;
    double       largest_loose_residual = 0;
    /** IMPL-EX step control: steps halved for their error; steps accepted above
     *  step_error_tolerance (at the last halving) and the largest error among them (in f_t). */
    unsigned int n_error_cuts        = 0;
    unsigned int n_large_error_steps = 0;
    double       largest_step_error  = 0;
  };
} // namespace kimp::fem
