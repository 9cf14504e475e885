// One HDF5 results file per command, H5MD-style layout of docs/architecture.md "Results files"
// (schema 1.0): /meta (attributes), /input/{scene,resolved}, one group per case with a `status`
// attribute, time series /<case>/<quantity>/{step,time,value}; every dataset carries a `units`
// attribute.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace kimp::io
{
  /// Failure to create, write or rename a results file; names the file and the object.
  class ResultsError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /// Schema version written to /meta/schema_version: major = incompatible, minor = additive.
  inline constexpr int results_schema_major = 1;
  inline constexpr int results_schema_minor = 0;

  /// One column of a small table (a group with one dataset per column).
  struct TableColumn
  {
    std::string         name;
    std::string         units; ///< "1" for dimensionless
    std::vector<double> values;
  };

  namespace detail
  {
    struct ResultsFileState;
    struct TimeSeriesState;
  } // namespace detail

  /**
   * A time series group {step int64[n], time float64[n] (units "s"), value float64[n] or
   * [n][width]} in chunked, extendible datasets. Rows are buffered and written at flush(), when
   * the buffer is full, at destruction and at ResultsFile::commit().
   */
  class TimeSeries
  {
  public:
    TimeSeries(TimeSeries &&) noexcept;
    TimeSeries &operator=(TimeSeries &&) noexcept;
    ~TimeSeries();

    /// Append one row: `values` has width() entries (one for a scalar series); time in s.
    void append(std::int64_t step, double time, const double *values);
    void append(std::int64_t step, double time, const std::vector<double> &values);
    void append(std::int64_t step, double time, double value);

    /// Values per row (1 for a scalar series).
    std::size_t width() const;
    /// Rows appended so far (written or buffered).
    std::size_t size() const;
    /// Write buffered rows to the file.
    void flush();

  private:
    friend class ResultsGroup;
    explicit TimeSeries(std::shared_ptr<detail::TimeSeriesState> state);
    std::shared_ptr<detail::TimeSeriesState> state_;
  };

  /// One quantity of a TimeSeriesSet: group name, values per row, units of the values.
  struct SeriesSpec
  {
    std::string name;
    std::size_t width = 1;
    std::string units;
  };

  /**
   * Quantities sampled at the same steps: one group per quantity with {step, time, value}, where
   * step and time are written once and hard-linked into every group (docs/architecture.md "Results
   * files").
   */
  class TimeSeriesSet
  {
  public:
    /// Append one row: `values` holds every quantity's width() values, concatenated in the
    /// order of the specs (row_width() in all); time in s.
    void append(std::int64_t step, double time, const std::vector<double> &values);

    std::size_t row_width() const { return row_width_; }
    std::size_t size() const;
    void        flush();

  private:
    friend class ResultsGroup;
    std::vector<std::shared_ptr<detail::TimeSeriesState>> states_;
    std::size_t                                           row_width_ = 0;
  };

  /// An open HDF5 group of a ResultsFile. Names are snake_case; paths may contain '/'.
  class ResultsGroup
  {
  public:
    ResultsGroup(ResultsGroup &&) noexcept;
    ResultsGroup &operator=(ResultsGroup &&) noexcept;
    ~ResultsGroup();

    /// Full HDF5 path of this group ("/" for the root).
    const std::string &path() const { return path_; }

    /// Open `name` below this group, creating it and missing parents.
    ResultsGroup group(std::string_view name);
    /// group(name) with attribute status = "running"; set "ok" or "failed: ..." with set_status.
    ResultsGroup case_group(std::string_view name);
    /// Attribute `status` of this group ("ok" | "failed: <reason>" | "running").
    void set_status(std::string_view status);

    /// 1-D float64 dataset.
    void write(std::string_view name, const std::vector<double> &values, std::string_view units);
    /// 1-D int64 dataset.
    void
    write(std::string_view name, const std::vector<std::int64_t> &values, std::string_view units);
    /// 2-D float64 dataset [n_rows][n_cols] from row-major values.
    void write_matrix(std::string_view           name,
                      const std::vector<double> &row_major,
                      std::size_t                n_rows,
                      std::size_t                n_cols,
                      std::string_view           units);
    /// Scalar float64 dataset.
    void write_scalar(std::string_view name, double value, std::string_view units);
    /// Scalar UTF-8 string dataset (units "1").
    void write_text(std::string_view name, std::string_view text);
    /// 1-D dataset of UTF-8 strings (units "1"), e.g. the case ids or statuses of a table.
    void write(std::string_view name, const std::vector<std::string> &values);

    /// Whole time series at once: steps[n], times[n] (s), values row-major [n][width]
    /// (width 1 gives value[n]).
    void write_time_series(std::string_view                 name,
                           const std::vector<std::int64_t> &steps,
                           const std::vector<double>       &times,
                           const std::vector<double>       &values,
                           std::size_t                      width,
                           std::string_view                 units);
    /// Incrementally written time series (see TimeSeries); width 1 gives value[n].
    TimeSeries time_series(std::string_view name,
                           std::size_t      width,
                           std::string_view units,
                           std::size_t      buffer_rows = 4096);

    /// Quantities sampled together below this group (see TimeSeriesSet); names must differ.
    /// `expected_rows` (0: unknown), when the caller knows the series' length: chunks of that
    /// length (at most 1 MiB beyond 4096 rows), so that the file holds no padding rows.
    TimeSeriesSet time_series_set(const std::vector<SeriesSpec> &specs,
                                  std::size_t                    buffer_rows   = 4096,
                                  std::size_t                    expected_rows = 0);

    /// Small table: group `name` with one dataset per column (equal lengths) and an attribute
    /// `columns` listing their order.
    void write_table(std::string_view name, const std::vector<TableColumn> &columns);

    void set_attribute(std::string_view name, std::string_view value);
    void set_attribute(std::string_view name, const char *value);
    void set_attribute(std::string_view name, double value);
    void set_attribute(std::string_view name, const std::vector<int> &values);
    template <class Int>
    std::enable_if_t<std::is_integral_v<Int> && !std::is_same_v<Int, bool>>
    set_attribute(std::string_view name, Int value)
    {
      set_integer_attribute(name, static_cast<std::int64_t>(value));
    }

  private:
    friend class ResultsFile;
    ResultsGroup(std::shared_ptr<detail::ResultsFileState> file, std::int64_t id, std::string path);
    void set_integer_attribute(std::string_view name, std::int64_t value);
    /// Series state with value dataset in `g`, and step/time datasets unless `clock` is given
    /// (then hard links to the step/time of group `clock`).
    std::shared_ptr<detail::TimeSeriesState> make_series(ResultsGroup       &g,
                                                         std::size_t         width,
                                                         std::string_view    units,
                                                         std::size_t         buffer_rows,
                                                         std::size_t         expected_rows,
                                                         const ResultsGroup *clock);

    std::shared_ptr<detail::ResultsFileState> file_;
    std::int64_t                              id_ = -1;
    std::string                               path_;
  };

  /**
   * RAII results file. The constructor creates `<final>.tmp-<pid>` and writes /meta and /input;
   * commit() flushes, closes and renames it to `final_path`. Destroying an uncommitted file
   * deletes the temporary file, so a failed run leaves nothing under the final name.
   * HDF5's automatic error printing is switched off (process-wide): errors become ResultsError.
   */
  class ResultsFile
  {
  public:
    /**
     * @param[in] final_path    name the file gets at commit()
     * @param[in] scene_text    the scene file verbatim (/input/scene)
     * @param[in] resolved_json resolved parameters as JSON text (/input/resolved)
     */
    ResultsFile(std::filesystem::path final_path,
                std::string_view      scene_text,
                std::string_view      resolved_json);
    ResultsFile(ResultsFile &&) noexcept;
    ResultsFile &operator=(ResultsFile &&) = delete;
    ResultsFile(const ResultsFile &)       = delete;
    ~ResultsFile();

    const std::filesystem::path &final_path() const { return final_path_; }
    const std::filesystem::path &temporary_path() const { return temporary_path_; }
    bool                         committed() const { return committed_; }

    /// The root group "/".
    ResultsGroup root();

    /// Flush every open TimeSeries, close the file and rename it to final_path().
    void commit();

  private:
    std::filesystem::path                     final_path_;
    std::filesystem::path                     temporary_path_;
    std::shared_ptr<detail::ResultsFileState> state_;
    bool                                      committed_ = false;
  };
} // namespace kimp::io
