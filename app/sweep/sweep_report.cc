// d_req against d_SRSS (docs/physics.md §2): per contact the SRSS rule asks g_c >= sqrt(d_L² +
// d_R²) with the peaks of the run without contacts; d_req is read off the swept gaps.
#include "app/sweep/sweep_report.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <stdexcept>

#include "io/summary.h"
#include "io/table.h"
#include "io/units.h"

namespace kimp::app
{
  using namespace kimp::io;
  namespace
  {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();

    /// Gaps (and offsets) closer than this are the same swept value, m.
    constexpr double same_length = 1e-9;

    const std::string clearance_suffix = ".clearance [m]";
    const std::string srss_suffix      = ".srss_gap [m]";

    bool ends_with(const std::string &text, const std::string &suffix)
    {
      return text.size() >= suffix.size() &&
             text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
    }

    /// Where a contact's metrics sit in SweepTable::metric_names.
    struct ContactColumns
    {
      std::string name;
      std::size_t clearance = 0;
      std::size_t srss      = 0;
    };
  } // namespace

  std::string to_string(RequiredGapStatus status)
  {
    switch (status)
    {
      case RequiredGapStatus::reached:
        return "reached";
      case RequiredGapStatus::at_smallest_gap:
        return "at_smallest_gap";
      case RequiredGapStatus::not_reached:
        return "not_reached";
      case RequiredGapStatus::no_data:
        break;
    }
    return "no_data";
  }

  RequiredGap required_gap(std::vector<GapSample> samples)
  {
    samples.erase(std::remove_if(samples.begin(),
                                 samples.end(),
                                 [](const GapSample &s) { return !s.ok || !std::isfinite(s.gap); }),
                  samples.end());
    RequiredGap result{nan, RequiredGapStatus::no_data};
    if (samples.empty())
      return result;
    std::sort(samples.begin(),
              samples.end(),
              [](const GapSample &a, const GapSample &b) { return a.gap < b.gap; });
    // Distinct gaps, each with "any impact at this gap".
    std::vector<std::pair<double, bool>> gaps;
    for (const GapSample &s : samples)
      if (!gaps.empty() && s.gap - gaps.back().first <= same_length)
        gaps.back().second = gaps.back().second || s.impact;
      else
        gaps.emplace_back(s.gap, s.impact);
    std::size_t first_safe = 0; // one past the largest gap with an impact
    for (std::size_t i = 0; i < gaps.size(); ++i)
      if (gaps[i].second)
        first_safe = i + 1;
    if (first_safe == gaps.size())
      return {nan, RequiredGapStatus::not_reached};
    return {gaps[first_safe].first,
            first_safe == 0 ? RequiredGapStatus::at_smallest_gap : RequiredGapStatus::reached};
  }

  SrssGap srss_required_gap(const std::vector<ContactGap> &contacts, const double gap)
  {
    if (contacts.empty())
      throw std::invalid_argument("d_SRSS: the case has no contact (expected walls or "
                                  "neighbours)");
    SrssGap result{-std::numeric_limits<double>::infinity(), ""};
    for (const ContactGap &c : contacts)
    {
      const double required = c.srss_gap - (c.clearance - gap);
      if (required > result.gap)
        result = {required, c.name};
    }
    return result;
  }

  double DsrssRow::delta() const
  {
    return d_req.status == RequiredGapStatus::reached ||
               d_req.status == RequiredGapStatus::at_smallest_gap ?
             d_srss - d_req.gap :
             nan;
  }

  namespace
  {
    /// The sweep parameters that do not set the gap (they name a configuration; the gap is the
    /// abscissa), their names and columns added to `dsrss`.
    /// @throws SweepError if no parameter sets `gap_key`.
    std::vector<std::size_t> configuration_parameters(const SweepPlan   &plan,
                                                      const SweepTable  &table,
                                                      const std::string &gap_key,
                                                      DsrssTable        &dsrss)
    {
      std::vector<std::size_t>                kept;
      bool                                    gap_swept = false;
      const std::vector<SweepParameterColumn> columns   = sweep_parameter_columns(plan, table);
      for (std::size_t p = 0; p < plan.parameters().size(); ++p)
      {
        const SweepParameter &parameter = plan.parameters()[p];
        const bool            sets_gap  = parameter.sets(gap_key);
        gap_swept                       = gap_swept || sets_gap;
        if (!sets_gap)
        {
          kept.push_back(p);
          dsrss.parameter_names.push_back(parameter.name);
          dsrss.parameter_columns.push_back(columns.at(p));
        }
      }
      if (!gap_swept)
        throw SweepError(
          fmt::format("{}:{}: report.gap: no parameter sets '{}' (expected the scene "
                      "key path of the swept gap)",
                      plan.file_name(),
                      plan.report() ? plan.report()->line : 1,
                      gap_key));
      return kept;
    }

    /// The metric columns d_SRSS reads: the contacts' clearance and SRSS gap, and n_impacts.
    struct ContactMetrics
    {
      std::vector<ContactColumns> contacts;
      std::size_t                 n_impacts = 0;
    };

    /// @throws SweepError without n_impacts or any contact with both metrics.
    ContactMetrics contact_metrics(const SweepPlan &plan, const SweepTable &table)
    {
      ContactMetrics metrics;
      metrics.n_impacts = table.metric_names.size();
      for (std::size_t m = 0; m < table.metric_names.size(); ++m)
      {
        const std::string &name = table.metric_names[m];
        if (name == "n_impacts")
          metrics.n_impacts = m;
        if (!ends_with(name, srss_suffix))
          continue;
        const std::string contact   = name.substr(0, name.size() - srss_suffix.size());
        const auto        clearance = std::find(table.metric_names.begin(),
                                         table.metric_names.end(),
                                         contact + clearance_suffix);
        if (clearance != table.metric_names.end())
          metrics.contacts.push_back(
            {contact, static_cast<std::size_t>(clearance - table.metric_names.begin()), m});
      }
      if (metrics.contacts.empty() || metrics.n_impacts == table.metric_names.size())
        throw SweepError(plan.file_name() +
                         ": d_SRSS needs the metrics n_impacts, <contact>.clearance [m] and "
                         "<contact>.srss_gap [m] (set integration.companion: true in the scene)");
      return metrics;
    }

    /// One main run (not a companion) of the sweep: its gap sample and SRSS gap.
    struct Sample
    {
      GapSample   gap;
      SrssGap     srss;
      std::size_t row = 0;
    };
    /// The runs of one configuration (and one set of clearance offsets) over the swept gaps.
    struct Group
    {
      DsrssRow            row;
      std::vector<Sample> samples;
    };
    /// The groups of the ok runs, and per configuration the number of failed runs.
    struct Groups
    {
      std::vector<Group>                              groups;
      std::map<std::vector<std::string>, std::size_t> failed_of;
    };

    Groups group_runs(const SweepPlan                &plan,
                      const SweepTable               &table,
                      const std::string              &gap_key,
                      const std::vector<std::size_t> &kept,
                      const ContactMetrics           &metrics)
    {
      Groups                                           grouped;
      std::vector<Group>                              &groups    = grouped.groups;
      std::map<std::vector<std::string>, std::size_t> &failed_of = grouped.failed_of;
      std::map<std::pair<std::vector<std::string>, std::string>, std::size_t> index_of;
      const std::vector<ContactColumns> &contacts         = metrics.contacts;
      const std::size_t                  n_impacts_column = metrics.n_impacts;
      for (std::size_t r = 0; r < table.rows.size(); ++r)
      {
        const SweepTableRow &row = table.rows[r];
        if (!row.companion.empty())
          continue;
        std::vector<std::string> values;
        for (const std::size_t p : kept)
          values.push_back(row.values.at(p));
        if (row.status != "ok")
        {
          ++failed_of[values];
          continue;
        }
        if (row.index >= plan.n_cases())
          throw SweepError(fmt::format("{}: row {} beyond the plan's {} cases",
                                       plan.file_name(),
                                       row.index,
                                       plan.n_cases()));
        const std::optional<std::string> gap_text =
          get_yaml_value(plan.case_at(row.index).scene_text, gap_key);
        if (!gap_text)
          throw SweepError(plan.file_name() + ": report.gap: case " + row.id +
                           " has no value at '" + gap_key + "'");
        const double gap = parse_quantity_as(*gap_text, "m");

        std::vector<ContactGap> present;
        std::string             offsets; // the group key part: contact=offset in µm
        double                  max_offset = -std::numeric_limits<double>::infinity();
        for (const ContactColumns &c : contacts)
        {
          const double clearance = row.metrics.at(c.clearance);
          const double srss      = row.metrics.at(c.srss);
          if (!std::isfinite(clearance) || !std::isfinite(srss))
            continue; // contact absent in this configuration
          present.push_back({c.name, clearance, srss});
          const double offset = clearance - gap;
          max_offset          = std::max(max_offset, offset);
          offsets += fmt::format("{}={};", c.name, std::llround(offset * 1e6));
        }
        if (present.empty())
          continue;
        const auto key = std::make_pair(values, offsets);
        auto       it  = index_of.find(key);
        if (it == index_of.end())
        {
          it = index_of.emplace(key, groups.size()).first;
          Group group;
          group.row.values           = values;
          group.row.clearance_offset = max_offset;
          groups.push_back(std::move(group));
        }
        Sample sample;
        sample.gap  = {gap, row.metrics.at(n_impacts_column) > 0.0, true};
        sample.srss = srss_required_gap(present, gap);
        sample.row  = r;
        groups[it->second].samples.push_back(sample);
      }
      return grouped;
    }

    /// The table row of one group: the required gap, d_SRSS of its smallest gap and the spread.
    DsrssRow group_row(Group                                                 &group,
                       const std::map<std::vector<std::string>, std::size_t> &failed_of)
    {
      DsrssRow              &out = group.row;
      std::vector<GapSample> gaps;
      for (const Sample &s : group.samples)
        gaps.push_back(s.gap);
      out.d_req         = required_gap(gaps);
      out.n_cases       = group.samples.size();
      const auto failed = failed_of.find(out.values);
      if (failed != failed_of.end())
      {
        // Failed cases have no metrics, hence no offsets: they count for every group of their
        // parameter values.
        out.n_failed = failed->second;
        out.n_cases += failed->second;
      }
      std::vector<double> distinct;
      double              srss_min = std::numeric_limits<double>::infinity();
      double              srss_max = -srss_min;
      const Sample       *smallest = &group.samples.front();
      for (const Sample &s : group.samples)
      {
        distinct.push_back(s.gap.gap);
        srss_min = std::min(srss_min, s.srss.gap);
        srss_max = std::max(srss_max, s.srss.gap);
        if (s.gap.gap < smallest->gap.gap)
          smallest = &s;
      }
      std::sort(distinct.begin(), distinct.end());
      out.n_gaps = static_cast<std::size_t>(
        std::unique(distinct.begin(),
                    distinct.end(),
                    [](double a, double b) { return std::abs(a - b) <= same_length; }) -
        distinct.begin());
      out.gap_min       = distinct.front();
      out.gap_max       = distinct.back();
      out.d_srss        = smallest->srss.gap;
      out.governing     = smallest->srss.governing;
      out.d_srss_spread = srss_max - srss_min;
      return std::move(out);
    }
  } // namespace

  DsrssTable dsrss_table(const SweepPlan &plan, const SweepTable &table, const std::string &gap_key)
  {
    DsrssTable                     dsrss;
    const std::vector<std::size_t> kept    = configuration_parameters(plan, table, gap_key, dsrss);
    const ContactMetrics           metrics = contact_metrics(plan, table);
    Groups                         grouped = group_runs(plan, table, gap_key, kept, metrics);
    for (Group &group : grouped.groups)
      dsrss.rows.push_back(group_row(group, grouped.failed_of));
    return dsrss;
  }

  void write_dsrss_table(const DsrssTable &dsrss, const std::filesystem::path &file)
  {
    Table csv;
    for (const SweepParameterColumn &p : dsrss.parameter_columns)
      if (p.numeric)
        csv.number(p.name, p.unit);
      else
        csv.text(p.name);
    csv.number("clearance_offset", "m")
      .integer("n_gaps")
      .integer("n_cases")
      .integer("n_failed")
      .number("gap_min", "m")
      .number("gap_max", "m")
      .number("d_req", "m")
      .text("d_req_status")
      .number("d_srss", "m")
      .text("governing_contact")
      .number("d_srss_spread", "m")
      .number("delta_d", "m");
    for (const DsrssRow &r : dsrss.rows)
    {
      std::vector<Cell> row;
      for (std::size_t p = 0; p < dsrss.parameter_columns.size(); ++p)
        if (dsrss.parameter_columns[p].numeric)
          row.emplace_back(dsrss.parameter_columns[p].number(r.values.at(p)));
        else
          row.emplace_back(r.values.at(p));
      row.insert(row.end(),
                 {r.clearance_offset,
                  static_cast<std::int64_t>(r.n_gaps),
                  static_cast<std::int64_t>(r.n_cases),
                  static_cast<std::int64_t>(r.n_failed),
                  r.gap_min,
                  r.gap_max,
                  r.d_req.gap,
                  to_string(r.d_req.status),
                  r.d_srss,
                  r.governing,
                  r.d_srss_spread,
                  r.delta()});
      csv.add_row(std::move(row));
    }
    csv.write_csv(file);
  }
} // namespace kimp::app
