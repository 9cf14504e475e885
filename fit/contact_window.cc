// The contact window of an FEM force history (see contact_window.h): checks of the samples,
// first contact, separation, peak, impulse and the samples the misfit uses.
#include "fit/contact_window.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <utility>

namespace kimp::fit::detail
{
  double interpolate(const std::vector<double> &t, const std::vector<double> &y, double at)
  {
    const auto   upper = std::upper_bound(t.begin(), t.end(), at);
    const size_t i     = static_cast<size_t>(std::distance(t.begin(), upper));
    if (i == 0)
      return y.front();
    if (i >= t.size())
      return y.back();
    const double s = (at - t[i - 1]) / (t[i] - t[i - 1]);
    return y[i - 1] + s * (y[i] - y[i - 1]);
  }


  void check_history(const ForceHistory &h)
  {
    const std::size_t n = h.time.size();
    if (n == 0 || h.force.empty())
      throw FitError("force history: empty (no samples)");
    if (h.force.size() != n)
      throw FitError(
        fmt::format("force history: {} force samples for {} times", h.force.size(), n));
    for (const auto &[name, v] :
         {std::pair<const char *, const std::vector<double> *>{"indentation", &h.indentation},
          {"slab_displacement", &h.slab_displacement}})
      if (!v->empty() && v->size() != n)
        throw FitError(
          fmt::format("force history: {} has {} samples for {} times", name, v->size(), n));
    for (std::size_t i = 0; i < n; ++i)
    {
      const bool finite = std::isfinite(h.time[i]) && std::isfinite(h.force[i]) &&
                          (h.indentation.empty() || std::isfinite(h.indentation[i])) &&
                          (h.slab_displacement.empty() || std::isfinite(h.slab_displacement[i]));
      if (!finite)
        throw FitError(fmt::format("force history: non-finite value at sample {} (t = {} s, "
                                   "F = {} N/m)",
                                   i,
                                   h.time[i],
                                   h.force[i]));
      if (i > 0 && !(h.time[i] > h.time[i - 1]))
        throw FitError(fmt::format("force history: time not increasing at sample {} ({} s "
                                   "after {} s)",
                                   i,
                                   h.time[i],
                                   h.time[i - 1]));
    }
  }

  ContactWindow find_contact_window(const ForceHistory &h, const FitOptions &options)
  {
    const std::size_t n      = h.time.size();
    const bool        by_gap = !h.indentation.empty();
    const double      peak   = *std::max_element(h.force.begin(), h.force.end());
    if (!(peak > 0.0))
      throw FitError(fmt::format("force history: no contact (largest force {} N/m over {} "
                                 "samples, {} s to {} s)",
                                 peak,
                                 n,
                                 h.time.front(),
                                 h.time.back()));
    const auto in_contact = [&](std::size_t i)
    { return by_gap ? h.indentation[i] > 0.0 : h.force[i] > options.contact_threshold * peak; };

    std::size_t i0 = 0;
    while (i0 < n && !in_contact(i0))
      ++i0;
    if (i0 == n)
      throw FitError("force history: no contact (indentation never > 0)");

    ContactWindow w;
    if (i0 == 0)
      w.start = h.time[0];
    else if (by_gap)
    {
      const double d0 = h.indentation[i0 - 1], d1 = h.indentation[i0];
      w.start = h.time[i0 - 1] + (h.time[i0] - h.time[i0 - 1]) * (-d0) / (d1 - d0);
    }
    else
    {
      // Back to the last force-free sample (the force below the threshold may already be
      // contact); a force rising linearly from zero (penalty contact) then points at the
      // touch, a force that jumps (viscous contact) points before that sample, which bounds it.
      std::size_t q = i0 - 1;
      while (q > 0 && h.force[q] > 0.0)
        --q;
      w.start = h.time[q];
      if (q + 2 < n && h.force[q + 2] > h.force[q + 1])
      {
        const double slope = (h.force[q + 2] - h.force[q + 1]) / (h.time[q + 2] - h.time[q + 1]);
        w.start = std::clamp(h.time[q + 1] - h.force[q + 1] / slope, h.time[q], h.time[q + 1]);
      }
    }

    std::size_t last = i0, next = n;
    for (std::size_t i = i0 + 1; i < n; ++i)
    {
      if (in_contact(i))
      {
        if (i > last + 2 &&
            h.time[i] - h.time[last] > options.separation_fraction * (h.time[last] - w.start))
        {
          next = i;
          break;
        }
        last = i;
      }
    }
    w.separation  = h.time[last];
    w.open_at_end = last + 1 == n;
    if (last + 1 < n)
    {
      if (by_gap)
      {
        const double d0 = h.indentation[last], d1 = h.indentation[last + 1];
        w.separation = h.time[last] + (h.time[last + 1] - h.time[last]) * d0 / (d0 - d1);
      }
      else
        w.separation = h.time[last + 1];
    }

    w.first = i0;
    while (w.first > 0 && h.time[w.first - 1] >= w.start)
      --w.first;
    w.peak_force = 0.0;
    for (std::size_t i = i0; i <= last; ++i)
      w.peak_force = std::max(w.peak_force, h.force[i]);
    if (!(w.peak_force > 0.0))
      throw FitError(fmt::format("force history: no contact force while the indentation is > 0 "
                                 "({} s to {} s)",
                                 w.start,
                                 w.separation));
    for (std::size_t i = w.first > 0 ? w.first - 1 : 0; i < std::min(last + 1, n - 1); ++i)
      w.impulse += 0.5 * (h.force[i] + h.force[i + 1]) * (h.time[i + 1] - h.time[i]);
    const double end = w.separation + options.tail_fraction * (w.separation - w.start);
    w.last           = last;
    while (w.last + 1 < next && h.time[w.last + 1] <= end)
      ++w.last;
    return w;
  }
} // namespace kimp::fit::detail
