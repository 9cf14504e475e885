// Plain two-column "time acceleration" text (see at2_reader.h): '#' comments, blank, comma or
// semicolon separators, uniform times from 0 within two_column_time_tolerance·dt.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/format.h"
#include "io/at2_reader.h"
#include "io/record_text.h"

namespace kimp::io
{
  using namespace detail;

  AccelerationRecord
  parse_two_column(std::string_view content, const std::string &source, double acceleration_unit)
  {
    if (!(std::isfinite(acceleration_unit) && acceleration_unit > 0.0))
      throw std::invalid_argument(
        source + ": two-column acceleration unit = " + format_number(acceleration_unit) +
        " m/s^2 (must be finite and > 0)");
    check_text(content, source);
    const SplitText split = split_lines(content);

    std::vector<double>      times, values;
    std::vector<std::size_t> line_numbers;
    for (const Line &line : split.lines)
    {
      std::string bad;
      bool        ok   = true;
      const auto  nums = split_numbers(strip_comment(line.text), bad, ok);
      if (!ok)
        fail(source,
             line.number,
             "non-numeric token \"" + base::excerpt(bad) +
               "\" (expected 'time acceleration' numbers; comment other lines with '#')");
      if (nums.empty())
        continue;
      if (nums.size() != 2)
        fail(source,
             line.number,
             std::to_string(nums.size()) +
               " numbers on the line (expected 2: 'time acceleration')");
      if (!std::isfinite(nums[1] * acceleration_unit))
        fail(source,
             line.number,
             "acceleration " + format_number(nums[1]) +
               " overflows when converted to m/s^2 (expected a finite acceleration)");
      times.push_back(nums[0]);
      values.push_back(nums[1] * acceleration_unit);
      line_numbers.push_back(line.number);
    }
    if (times.size() < 2)
      fail(source,
           split.lines.size(),
           std::to_string(times.size()) +
             " data row(s) (expected at least 2 'time acceleration' rows)");
    for (std::size_t i = 1; i < times.size(); ++i)
      if (!(times[i] > times[i - 1]))
        fail(source,
             line_numbers[i],
             "time " + format_number(times[i]) + " s after " + format_number(times[i - 1]) +
               " s (expected strictly increasing times)");

    const double dt = (times.back() - times.front()) / static_cast<double>(times.size() - 1);
    if (!std::isnormal(dt))
      fail(source,
           line_numbers.back(),
           "time step " + format_number(dt) +
             " s (expected a positive normal number: times spanning more than 1e-300 s)");
    if (dt < min_record_dt || dt > max_record_dt)
      fail(source,
           line_numbers.back(),
           "time step " + format_number(dt) + " s (expected a sampling interval in [" +
             format_number(min_record_dt) + " s, " + format_number(max_record_dt) +
             " s]: outside it implausible for a ground-motion record)");
    const double tolerance = two_column_time_tolerance * dt;
    if (std::abs(times.front()) > tolerance)
      fail(source,
           line_numbers.front(),
           "first time " + format_number(times.front()) +
             " s (expected 0: samples are taken from t = 0)");
    for (std::size_t i = 0; i < times.size(); ++i)
    {
      const double deviation = times[i] - static_cast<double>(i) * dt;
      if (std::abs(deviation) > tolerance)
        fail(source,
             line_numbers[i],
             "time " + format_number(times[i]) + " s is " + format_number(deviation) +
               " s off the uniform grid i*dt with dt = " + format_number(dt) +
               " s (expected uniform sampling within " + format_number(two_column_time_tolerance) +
               "*dt)");
    }

    AccelerationRecord motion;
    motion.dt           = dt;
    motion.acceleration = std::move(values);
    motion.name         = stem_of(source);
    return motion;
  }

  AccelerationRecord read_two_column(const std::filesystem::path &file, double acceleration_unit)
  {
    return parse_two_column(read_file(file), file.string(), acceleration_unit);
  }
} // namespace kimp::io
