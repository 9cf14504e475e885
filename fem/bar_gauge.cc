// The bars' strain over a gauge length.
#include "fem/bar_gauge.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <stdexcept>

namespace kimp::fem
{
  namespace
  {
    constexpr double same_line = 1e-9; ///< m: segments this close in x are one vertical line

    /** ∫ε dy from the line's lowest end to y (clamped to the line), `cumulative[k]` the
     *  integral up to ends[k]; `k` a segment index at or below y's, advanced to y's (the
     *  windows' ends move up monotonically: one pass per line). */
    double integral_to(const std::vector<double> &ends,
                       const std::vector<double> &cumulative,
                       const std::vector<double> &strain_by_y,
                       double                     y,
                       std::size_t               &k)
    {
      if (y <= ends.front())
        return 0.0;
      if (y >= ends.back())
        return cumulative.back();
      while (k + 2 < ends.size() && ends[k + 1] <= y)
        ++k;
      return cumulative[k] + strain_by_y[k] * (y - ends[k]);
    }
  } // namespace

  BarGauge::BarGauge(const std::vector<GaugeSegment> &segments, const double length)
    : gauge_length(length)
    , n_segments(segments.size())
  {
    if (!(length > 0))
      throw std::invalid_argument("bar gauge: the gauge length must be positive");
    std::vector<std::size_t> by_x(segments.size());
    std::iota(by_x.begin(), by_x.end(), std::size_t{0});
    for (const GaugeSegment &s : segments)
      if (!(s.y_hi > s.y_lo))
        throw std::invalid_argument("bar gauge: a segment with y_hi <= y_lo");
    std::sort(by_x.begin(),
              by_x.end(),
              [&](std::size_t a, std::size_t b) { return segments[a].x < segments[b].x; });
    for (std::size_t i = 0; i < by_x.size();)
    {
      std::size_t j = i;
      while (j < by_x.size() && segments[by_x[j]].x - segments[by_x[i]].x <= same_line)
        ++j;
      Line line;
      line.order.assign(by_x.begin() + static_cast<std::ptrdiff_t>(i),
                        by_x.begin() + static_cast<std::ptrdiff_t>(j));
      std::sort(line.order.begin(),
                line.order.end(),
                [&](std::size_t a, std::size_t b) { return segments[a].y_lo < segments[b].y_lo; });
      // The line's ends: each segment's lower end, then the top. A gap between segments is
      // closed onto the lower end of the next (no strain sample there: none in the wall).
      for (const std::size_t k : line.order)
        line.ends.push_back(segments[k].y_lo);
      line.ends.push_back(segments[line.order.back()].y_hi);
      lines.push_back(std::move(line));
      i = j;
    }
  }

  GaugeStrain BarGauge::largest_mean(const std::vector<double> &strain) const
  {
    if (strain.size() != n_segments)
      throw std::invalid_argument("bar gauge: one strain per segment expected");
    GaugeStrain best;
    for (const Line &line : lines)
    {
      by_y.resize(line.order.size());
      cumulative.assign(1, 0.0);
      for (std::size_t k = 0; k < line.order.size(); ++k)
      {
        by_y[k] = strain[line.order[k]];
        cumulative.push_back(cumulative.back() + by_y[k] * (line.ends[k + 1] - line.ends[k]));
      }
      const double bottom = line.ends.front(), top = line.ends.back();
      const double span = std::min(gauge_length, top - bottom);
      // Windows from each segment end up, then windows down to each segment end: within each
      // sweep both ends of the window move up, so each keeps its own segment pointer.
      for (int sweep = 0; sweep < 2; ++sweep)
      {
        std::size_t k_lo = 0, k_hi = 0;
        for (const double y : line.ends)
        {
          const double lo   = std::clamp(sweep == 0 ? y : y - span, bottom, top - span);
          const double hi   = lo + span;
          const double mean = (integral_to(line.ends, cumulative, by_y, hi, k_hi) -
                               integral_to(line.ends, cumulative, by_y, lo, k_lo)) /
                              span;
          if (std::abs(mean) > best.strain)
            best = {std::abs(mean), lo + 0.5 * span};
        }
      }
    }
    return best;
  }
} // namespace kimp::fem
