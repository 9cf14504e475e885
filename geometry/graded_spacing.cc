// Graded 1D node distribution: equal steps of the metric ψ = ∫ ds / h per span, h the lower
// envelope of "cones" q + ln(g)·dist(s, [lo, hi]) capped at h_max (piecewise linear, so ψ and its
// inverse are closed-form logarithms / exponentials per piece).
#include "geometry/graded_spacing.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace kimp::geometry
{
  namespace
  {
    [[noreturn]] void reject(const std::string &name, double value, const std::string &rule)
    {
      std::ostringstream message;
      message.precision(10);
      message << "GradedSpacing: " << name << " = " << value << " (" << rule << ')';
      throw std::invalid_argument(message.str());
    }

    // Tolerance on metric lengths when rounding up to an element count: a span that is an exact
    // multiple of h must not get an extra element from round-off.
    constexpr double metric_round_off = 1e-9;

    // Relative slack on the grading test, for round-off in the node coordinates.
    constexpr double ratio_round_off = 1e-12;

    // Passes that lower the size field at breakpoints with a size jump; each pass can only lower
    // the field, and in practice two or three suffice.
    constexpr int max_cone_passes = 8;

    // Single elements the final greedy repair may add in total.
    constexpr int max_repair_steps = 32;

    // h(s) = min(h_max, size + slope·dist(s, [lo, hi])).
    struct Cone
    {
      double lo, hi, size;
    };

    // Lower envelope of cones, capped at h_max: piecewise linear between knots (every kink of a
    // cone and every crossing of two cone pieces is a knot), constant outside the knots.
    class Envelope
    {
    public:
      Envelope(const std::vector<Cone> &cones, double h_max, double slope)
        : cones_(cones)
        , h_max_(h_max)
        , slope_(slope)
      {
        std::vector<double> knots;
        for (const Cone &c : cones)
        {
          knots.push_back(c.lo);
          knots.push_back(c.hi);
          if (slope > 0.0)
          {
            knots.push_back(c.lo - (h_max - c.size) / slope);
            knots.push_back(c.hi + (h_max - c.size) / slope);
          }
        }
        if (slope > 0.0)
          for (const Cone &a : cones)
            for (const Cone &b : cones)
            {
              // a rising right of a meets b falling left of b; a's flat top meets b's flanks.
              knots.push_back((b.size - a.size + slope * (b.lo + a.hi)) / (2.0 * slope));
              knots.push_back(b.hi + (a.size - b.size) / slope);
              knots.push_back(b.lo - (a.size - b.size) / slope);
            }
        std::sort(knots.begin(), knots.end());
        knots.erase(std::unique(knots.begin(), knots.end()), knots.end());

        s_ = knots;
        h_.resize(s_.size());
        psi_.assign(s_.size(), 0.0);
        for (std::size_t i = 0; i < s_.size(); ++i)
          h_[i] = size(s_[i]);
        for (std::size_t i = 1; i < s_.size(); ++i)
          psi_[i] = psi_[i - 1] + piece_metric(s_[i] - s_[i - 1], h_[i - 1], h_[i]);
      }

      double size(double s) const
      {
        double h = h_max_;
        for (const Cone &c : cones_)
          h = std::min(h, c.size + slope_ * std::max({c.lo - s, s - c.hi, 0.0}));
        return h;
      }

      double metric(double s) const
      {
        if (s <= s_.front())
          return psi_.front() - (s_.front() - s) / h_.front();
        if (s >= s_.back())
          return psi_.back() + (s - s_.back()) / h_.back();
        const std::size_t i = std::upper_bound(s_.begin(), s_.end(), s) - s_.begin() - 1;
        return psi_[i] + piece_metric(s - s_[i], h_[i], size(s));
      }

      double coordinate(double psi) const
      {
        if (psi <= psi_.front())
          return s_.front() - (psi_.front() - psi) * h_.front();
        if (psi >= psi_.back())
          return s_.back() + (psi - psi_.back()) * h_.back();
        const std::size_t i    = std::upper_bound(psi_.begin(), psi_.end(), psi) - psi_.begin() - 1;
        const double      t    = psi - psi_[i];
        const double      beta = (h_[i + 1] - h_[i]) / (s_[i + 1] - s_[i]); // dh/ds on the piece
        // h(ψ) = h_i exp(β (ψ − ψ_i)), s = s_i + (h − h_i)/β; the β → 0 limit is s_i + h_i t.
        if (beta == 0.0)
          return s_[i] + h_[i] * t;
        return s_[i] + h_[i] * std::expm1(beta * t) / beta;
      }

    private:
      std::vector<Cone>   cones_;
      double              h_max_;
      double              slope_;
      std::vector<double> s_, h_, psi_;

      // ∫ ds / h over a piece of length ds where h goes linearly from h0 to h1.
      static double piece_metric(double ds, double h0, double h1)
      {
        if (ds <= 0.0)
          return 0.0;
        const double x = (h1 - h0) / h0;
        if (std::abs(x) < 1e-12)
          return ds / h0;
        return ds * std::log1p(x) / (h1 - h0);
      }
    };

    std::vector<double> span_nodes(const Envelope &field, double a, double b, int n)
    {
      const double psi_a = field.metric(a);
      const double psi_b = field.metric(b);
      const double step  = (psi_b - psi_a) / n;

      std::vector<double> result(n + 1);
      result.front() = a;
      for (int i = 1; i < n; ++i)
        result[i] = field.coordinate(psi_a + i * step);
      result.back() = b;
      return result;
    }

    std::vector<double>
    assemble(const Envelope &field, const std::vector<double> &cuts, const std::vector<int> &counts)
    {
      std::vector<double> all{cuts.front()};
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
      {
        const std::vector<double> span = span_nodes(field, cuts[k], cuts[k + 1], counts[k]);
        all.insert(all.end(), span.begin() + 1, span.end());
      }
      return all;
    }

    std::vector<int> element_counts(const Envelope &field, const std::vector<double> &cuts)
    {
      std::vector<int> counts(cuts.size() - 1);
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
      {
        const double length = field.metric(cuts[k + 1]) - field.metric(cuts[k]);
        counts[k]           = std::max(1, static_cast<int>(std::ceil(length - metric_round_off)));
      }
      return counts;
    }
  } // namespace


  GradedSpacing::GradedSpacing(double fine_begin,
                               double fine_end,
                               double h_fine,
                               double h_max,
                               double grading)
    : fine_begin_(fine_begin)
    , fine_end_(fine_end)
    , h_fine_(h_fine)
    , h_max_(h_max)
    , slope_(std::log(grading))
  {
    if (!std::isfinite(fine_begin) || !std::isfinite(fine_end) || fine_end < fine_begin)
      reject("fine_end",
             fine_end,
             "must be finite and >= fine_begin = " + std::to_string(fine_begin));
    if (!(h_fine > 0.0) || !std::isfinite(h_fine))
      reject("h_fine", h_fine, "must be > 0 and finite");
    if (!(h_max >= h_fine) || !std::isfinite(h_max))
      reject("h_max", h_max, "must be >= h_fine = " + std::to_string(h_fine));
    if (!(grading >= 1.0) || !std::isfinite(grading))
      reject("grading", grading, "must be >= 1 and finite");
  }


  double GradedSpacing::size_at(double s) const
  {
    return Envelope({{fine_begin_, fine_end_, h_fine_}}, h_max_, slope_).size(s);
  }


  double GradedSpacing::metric(double s) const
  {
    return Envelope({{fine_begin_, fine_end_, h_fine_}}, h_max_, slope_).metric(s);
  }


  double GradedSpacing::coordinate(double psi) const
  {
    return Envelope({{fine_begin_, fine_end_, h_fine_}}, h_max_, slope_).coordinate(psi);
  }


  std::vector<double>
  GradedSpacing::nodes(double begin, double end, const std::vector<double> &breakpoints) const
  {
    if (!std::isfinite(begin) || !std::isfinite(end) || !(end > begin))
      reject("end", end, "must be finite and > begin = " + std::to_string(begin));

    std::vector<double> cuts{begin};
    std::vector<double> sorted = breakpoints;
    std::sort(sorted.begin(), sorted.end());
    for (const double b : sorted)
      if (std::isfinite(b) && b > cuts.back() && b < end)
        cuts.push_back(b);
    cuts.push_back(end);

    const double grading   = std::exp(slope_);
    const auto   too_steep = [&](double ratio) { return ratio > grading * (1 + ratio_round_off); };
    std::vector<Cone> cones{{fine_begin_, fine_end_, h_fine_}};

    Envelope            field(cones, h_max_, slope_);
    std::vector<int>    counts = element_counts(field, cuts);
    std::vector<double> result = assemble(field, cuts, counts);

    // Size jumps at breakpoints: let the coarser side grade down to the finer side's size.
    for (int pass = 0; pass < max_cone_passes && too_steep(max_neighbour_ratio(result)); ++pass)
    {
      bool        lowered = false;
      std::size_t node    = 0;
      for (std::size_t k = 1; k + 1 < cuts.size(); ++k)
      {
        node += counts[k - 1];
        const double left  = result[node] - result[node - 1];
        const double right = result[node + 1] - result[node];
        if (too_steep(std::max(left / right, right / left)))
        {
          cones.push_back({cuts[k], cuts[k], std::min(left, right)});
          lowered = true;
        }
      }
      if (!lowered)
        break;
      field  = Envelope(cones, h_max_, slope_);
      counts = element_counts(field, cuts);
      result = assemble(field, cuts, counts);
    }

    // Remaining jumps: add the single element that lowers the largest ratio most (bounded).
    double ratio = max_neighbour_ratio(result);
    for (int step = 0; step < max_repair_steps && cuts.size() > 2 && too_steep(ratio); ++step)
    {
      std::size_t best_span  = counts.size();
      double      best_ratio = ratio;
      for (std::size_t k = 0; k < counts.size(); ++k)
      {
        std::vector<int> trial = counts;
        ++trial[k];
        const double trial_ratio = max_neighbour_ratio(assemble(field, cuts, trial));
        if (trial_ratio < best_ratio)
        {
          best_ratio = trial_ratio;
          best_span  = k;
        }
      }
      if (best_span == counts.size())
        break;
      ++counts[best_span];
      result = assemble(field, cuts, counts);
      ratio  = best_ratio;
    }
    return result;
  }


  double max_neighbour_ratio(const std::vector<double> &nodes)
  {
    double ratio = 1.0;
    for (std::size_t i = 2; i < nodes.size(); ++i)
    {
      const double left  = nodes[i - 1] - nodes[i - 2];
      const double right = nodes[i] - nodes[i - 1];
      ratio              = std::max(ratio, std::max(left / right, right / left));
    }
    return ratio;
  }
} // namespace kimp::geometry
