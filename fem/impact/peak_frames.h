// When the deformed-mesh frames of an impact are recorded (ImpactParameters::frame_interval):
// the force peak of an impact is a fraction of a millisecond wide, so frames at the interval alone
// miss it.
#pragma once

#include <algorithm>

namespace kimp::fem::internal
{
  /**
   * Frames every `frame_every` steps, and 50 times as often from the first contact until the
   * contact force has passed its peak, for at most `window` seconds. The peak is passed once the
   * force has stayed below half its largest value for `hold` seconds: an elastic slab's raw
   * force chatters at first touch (nodes touching and parting within microseconds), and a single
   * step below half would end the dense frames before the peak.
   */
  class PeakFrames
  {
  public:
    static constexpr double window = 2e-3;   ///< s
    static constexpr double hold   = 0.1e-3; ///< s

    explicit PeakFrames(unsigned long frame_every)
      : every_(frame_every)
      , fine_(std::max(1ul, frame_every / 50))
    {
    }

    /// Whether step `n` at time `t` (s) with the total contact force `force` (N/m) gets a frame.
    bool operator()(unsigned long n, double t, double force)
    {
      if (every_ == 0)
        return false;
      if (force > 0 && t_contact_ < 0)
        t_contact_ = t;
      largest_ = std::max(largest_, force);
      if (largest_ > 0 && force < 0.5 * largest_)
      {
        if (t_below_ < 0)
          t_below_ = t;
        if (t - t_below_ >= hold)
          past_peak_ = true;
      }
      else
        t_below_ = -1;
      const bool dense = t_contact_ >= 0 && !past_peak_ && t - t_contact_ <= window;
      return n % every_ == 0 || (dense && n % fine_ == 0);
    }

  private:
    unsigned long every_;
    unsigned long fine_;
    double        t_contact_ = -1;
    double        t_below_   = -1; ///< s: since when the force is below half its largest
    double        largest_   = 0;
    bool          past_peak_ = false;
  };
} // namespace kimp::fem::internal
