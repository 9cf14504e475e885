// The time series of a results file: rows buffered in memory and appended to extendible HDF5
// datasets at flush(); a TimeSeriesSet shares one step/time clock between its quantities.
#include <algorithm>
#include <fmt/format.h>

#include "io/results_file.h"
#include "io/results_hdf5.h"

namespace kimp::io
{
  using detail::append_rows;
  using detail::check;
  using detail::create_extendible;

  void detail::TimeSeriesState::flush()
  {
    const std::size_t n = steps.size();
    if (n == 0)
      return;
    if (!file->open())
      throw ResultsError(
        fmt::format("results file '{}': time series '{}' written after the file was closed",
                    file->name,
                    path));
    if (writes_clock)
    {
      append_rows(step_set,
                  H5T_NATIVE_INT64,
                  steps.data(),
                  written,
                  n,
                  1,
                  false,
                  file->name,
                  path + "/step");
      append_rows(time_set,
                  H5T_NATIVE_DOUBLE,
                  times.data(),
                  written,
                  n,
                  1,
                  false,
                  file->name,
                  path + "/time");
    }
    append_rows(value_set,
                H5T_NATIVE_DOUBLE,
                values.data(),
                written,
                n,
                width,
                matrix,
                file->name,
                path + "/value");
    written += n;
    steps.clear();
    times.clear();
    values.clear();
  }

  detail::TimeSeriesState::~TimeSeriesState()
  {
    try
    {
      if (file->open())
        flush();
    }
    catch (const std::exception &error)
    {
      if (file->deferred_error.empty())
        file->deferred_error = error.what();
    }
    if (file->open())
      for (const hid_t id : {step_set, time_set, value_set})
        if (id >= 0)
          H5Dclose(id);
  }

  TimeSeries::TimeSeries(std::shared_ptr<detail::TimeSeriesState> state)
    : state_(std::move(state))
  {
  }
  TimeSeries::TimeSeries(TimeSeries &&) noexcept            = default;
  TimeSeries &TimeSeries::operator=(TimeSeries &&) noexcept = default;
  TimeSeries::~TimeSeries()                                 = default;

  void TimeSeries::append(std::int64_t step, double time, const double *values)
  {
    auto &s = *state_;
    s.steps.push_back(step);
    s.times.push_back(time);
    s.values.insert(s.values.end(), values, values + s.width);
    if (s.steps.size() >= s.buffer_rows)
      s.flush();
  }

  void TimeSeries::append(std::int64_t step, double time, const std::vector<double> &values)
  {
    if (values.size() != state_->width)
      throw ResultsError(fmt::format("time series '{}': row of {} values appended, expected {}",
                                     state_->path,
                                     values.size(),
                                     state_->width));
    append(step, time, values.data());
  }

  void TimeSeries::append(std::int64_t step, double time, double value)
  {
    if (state_->width != 1)
      throw ResultsError(fmt::format("time series '{}': one value appended, expected {}",
                                     state_->path,
                                     state_->width));
    append(step, time, &value);
  }

  std::size_t TimeSeries::width() const
  {
    return state_->width;
  }

  std::size_t TimeSeries::size() const
  {
    return state_->written + state_->steps.size();
  }

  void TimeSeries::flush()
  {
    state_->flush();
  }

  std::shared_ptr<detail::TimeSeriesState> ResultsGroup::make_series(ResultsGroup    &g,
                                                                     std::size_t      width,
                                                                     std::string_view units,
                                                                     std::size_t      buffer_rows,
                                                                     std::size_t      expected_rows,
                                                                     const ResultsGroup *clock)
  {
    if (width == 0)
      throw ResultsError(fmt::format("time series '{}': width must be >= 1", g.path()));
    auto state         = std::make_shared<detail::TimeSeriesState>();
    state->file        = file_;
    state->path        = g.path();
    state->width       = width;
    state->matrix      = width > 1;
    state->buffer_rows = std::max<std::size_t>(buffer_rows, 1);
    // One chunk holds the series' expected length, or else the buffered rows: a whole series
    // is one chunk of its exact size, with no padding to a round number of rows. Chunks stay
    // below 1 MiB beyond 4096 rows (HDF5's chunk cache).
    constexpr std::size_t chunk_bytes = std::size_t(1) << 20;
    const std::size_t     chunk =
      std::min<std::size_t>(expected_rows > 0 ? expected_rows : state->buffer_rows,
                            std::max<std::size_t>(4096, chunk_bytes / (sizeof(double) * width)));
    if (clock == nullptr)
    {
      state->step_set = create_extendible(g.id_,
                                          g.path(),
                                          "step",
                                          H5T_STD_I64LE,
                                          1,
                                          false,
                                          chunk,
                                          "1",
                                          file_->name);
      state->time_set = create_extendible(g.id_,
                                          g.path(),
                                          "time",
                                          H5T_IEEE_F64LE,
                                          1,
                                          false,
                                          chunk,
                                          "s",
                                          file_->name);
    }
    else
    {
      state->writes_clock = false;
      for (const char *name : {"step", "time"})
        check(H5Lcreate_hard(clock->id_, name, g.id_, name, H5P_DEFAULT, H5P_DEFAULT),
              file_->name,
              fmt::format("linking '{}/{}' to '{}/{}'", g.path(), name, clock->path(), name));
    }
    state->value_set = create_extendible(g.id_,
                                         g.path(),
                                         "value",
                                         H5T_IEEE_F64LE,
                                         width,
                                         state->matrix,
                                         chunk,
                                         units,
                                         file_->name);
    file_->series.push_back(state);
    return state;
  }

  TimeSeries ResultsGroup::time_series(std::string_view name,
                                       std::size_t      width,
                                       std::string_view units,
                                       std::size_t      buffer_rows)
  {
    ResultsGroup g = group(name);
    return TimeSeries(make_series(g, width, units, buffer_rows, 0, nullptr));
  }

  TimeSeriesSet ResultsGroup::time_series_set(const std::vector<SeriesSpec> &specs,
                                              std::size_t                    buffer_rows,
                                              std::size_t                    expected_rows)
  {
    if (specs.empty())
      throw ResultsError(fmt::format("time series set below '{}': no quantities", path_));
    TimeSeriesSet set;
    ResultsGroup  clock = group(specs.front().name);
    for (std::size_t i = 0; i < specs.size(); ++i)
    {
      ResultsGroup g = group(specs[i].name);
      set.states_.push_back(make_series(g,
                                        specs[i].width,
                                        specs[i].units,
                                        buffer_rows,
                                        expected_rows,
                                        i == 0 ? nullptr : &clock));
      set.row_width_ += specs[i].width;
    }
    return set;
  }

  void TimeSeriesSet::append(std::int64_t step, double time, const std::vector<double> &values)
  {
    if (values.size() != row_width_)
      throw ResultsError(fmt::format("time series set '{}': row of {} values appended, expected {}",
                                     states_.front()->path,
                                     values.size(),
                                     row_width_));
    const double *row = values.data();
    for (const auto &state : states_)
    {
      state->steps.push_back(step);
      state->times.push_back(time);
      state->values.insert(state->values.end(), row, row + state->width);
      row += state->width;
    }
    if (states_.front()->steps.size() >= states_.front()->buffer_rows)
      flush();
  }

  std::size_t TimeSeriesSet::size() const
  {
    return states_.empty() ? 0 : states_.front()->written + states_.front()->steps.size();
  }

  void TimeSeriesSet::flush()
  {
    for (const auto &state : states_)
      state->flush();
  }
} // namespace kimp::io
