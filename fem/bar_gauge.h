// The bars' strain over a gauge length (docs/physics.md "Engineer's quantities"): the mean
// strain of a vertical line of the wall over a window of given length, the elongation a strain
// gauge of that length reads. Perfectly bonded smeared bars localise their plastic strain in the
// one row of cells where the crack forms, so the largest point strain grows as the row shrinks; the
// elongation over a fixed length does not. No deal.II: a piecewise-constant strain per vertical
// line.
#pragma once

#include <cstddef>
#include <vector>

namespace kimp::fem
{
  /** The part of a vertical line of the wall one strain sample stands for: the line's x and
   *  the span [y_lo, y_hi] (m) over which the sample's strain holds. */
  struct GaugeSegment
  {
    double x = 0, y_lo = 0, y_hi = 0;
  };

  /** The largest |mean strain| over a gauge window and the height of the window's centre. */
  struct GaugeStrain
  {
    double strain = 0; ///< |mean|, the sign of the strain dropped
    double centre = 0; ///< m
  };

  /**
   * Vertical lines of segments (segments of equal x, within 1e-9 m, form one line; sorted by
   * y) and a gauge length L > 0. largest_mean() slides a window [y, y + L] along each line
   * (clamped to the line's extent; a line shorter than L is read over its whole length) and
   * returns the largest |∫ε dy / L| with the window's centre. The strain is constant over each
   * segment (a Q1 cell's ∂u_y/∂y is constant along y at fixed x, so a 2-point Gauss column
   * splits the cell into two halves of one strain), so ∫ε dy over the window is the elongation
   * between its ends, and the mean is piecewise linear in the window's position with kinks where
   * an end meets a segment's end: the largest is at such a position, and those are all tried.
   * @throws std::invalid_argument for L <= 0 or a segment with y_hi <= y_lo.
   */
  class BarGauge
  {
  public:
    BarGauge(const std::vector<GaugeSegment> &segments, double length);
    /** `strain[i]` the strain of the constructor's segment i (size: the number of segments). */
    GaugeStrain largest_mean(const std::vector<double> &strain) const;
    double      length() const { return gauge_length; }

  private:
    struct Line
    {
      std::vector<std::size_t> order; ///< segment indices by y
      std::vector<double>      ends;  ///< y of the segments' ends, size order.size() + 1
    };
    std::vector<Line> lines;
    double            gauge_length;
    std::size_t       n_segments;
    /// Scratch of largest_mean() (one line's strains by y and their running integral), kept so
    /// that the reading at every sampled step does not allocate.
    mutable std::vector<double> by_y, cumulative;
  };
} // namespace kimp::fem
