// The part of an FEM force history that the impact-law fitter matches (private to fit/): where
// the first contact starts and ends, its peak and impulse, and the window of samples that enter
// the misfit (the contact phase and a tail after it, FitOptions::tail_fraction).
#pragma once

#include <cstddef>
#include <vector>

#include "fit/fitter.h"

namespace kimp::fit::detail
{
  /// Where the FEM history is in contact and which samples enter the misfit.
  struct ContactWindow
  {
    double      start       = 0.0;   ///< first contact, s (FEM time)
    double      separation  = 0.0;   ///< end of the first contact phase, s
    double      peak_force  = 0.0;   ///< N/m
    double      impulse     = 0.0;   ///< N·s/m
    std::size_t first       = 0;     ///< first sample of the misfit window
    std::size_t last        = 0;     ///< last sample of the misfit window (inclusive)
    bool        open_at_end = false; ///< the contact phase lasts to the last sample
  };

  /// @throws FitError for an empty history, mismatched lengths, non-finite values or times that
  /// do not increase.
  void check_history(const ForceHistory &h);

  /// The first contact of `h` and its misfit window. @throws FitError without contact.
  ContactWindow find_contact_window(const ForceHistory &h, const FitOptions &options);

  /// Piecewise-linear interpolation of (t, y) at `at`; `t` increasing, at inside [t0, tn].
  double interpolate(const std::vector<double> &t, const std::vector<double> &y, double at);
} // namespace kimp::fit::detail
