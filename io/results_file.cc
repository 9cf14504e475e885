// HDF5 results file (C API, used serially); layout in results_file.h and docs/architecture.md
// "Results files"
#include "io/results_file.h"

#include <array>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <fmt/format.h>
#include <hdf5.h>
#include <optional>
#include <system_error>
#include <unistd.h>

#include "base/version.h"
#include "io/hdf5_handle.h"
#include "io/output_dir.h"

namespace kimp::io
{
  static_assert(std::is_same_v<hid_t, std::int64_t>, "kimp stores HDF5 ids as int64_t");

  namespace detail
  {
    struct ResultsFileState
    {
      hid_t                                       file = -1;
      int                                         fd   = -1; ///< the temporary file on disk
      std::string                                 name;      ///< final file name, for messages
      std::vector<std::weak_ptr<TimeSeriesState>> series;
      std::string                                 deferred_error;
      std::optional<TemporaryFile>                temporary; ///< removed by a SIGTERM handler

      bool open() const { return file >= 0; }
    };

    struct TimeSeriesState
    {
      std::shared_ptr<ResultsFileState> file;
      std::string                       path;
      hid_t                             step_set  = -1;
      hid_t                             time_set  = -1;
      hid_t                             value_set = -1;
      std::size_t                       width     = 1;
      bool                              matrix    = false; ///< value is [n][width]
      bool        writes_clock = true; ///< false: step/time are hard links to another series'
      std::size_t written      = 0;
      std::size_t buffer_rows  = 4096;
      std::vector<std::int64_t> steps;
      std::vector<double>       times;
      std::vector<double>       values;

      void flush();
      ~TimeSeriesState();
    };
  } // namespace detail

  namespace
  {
    /// Descriptions of the HDF5 error stack, outermost first.
    herr_t collect_error(unsigned int /*n*/, const H5E_error2_t *error, void *data)
    {
      auto *descriptions = static_cast<std::vector<std::string> *>(data);
      if (error->desc != nullptr && error->desc[0] != '\0')
        descriptions->emplace_back(error->desc);
      return 0;
    }

    /// One line from HDF5's error stack: the outermost and the innermost description (the
    /// whole stack runs to a dozen lines that say the same thing).
    std::string hdf5_error_text()
    {
      std::vector<std::string> descriptions;
      H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_error, &descriptions);
      H5Eclear2(H5E_DEFAULT);
      if (descriptions.empty())
        return "no HDF5 error detail";
      std::string text = descriptions.front();
      if (descriptions.size() > 1 && descriptions.back() != descriptions.front())
        text += ": " + descriptions.back();
      for (char &c : text)
        if (c == '\n' || c == '\r')
          c = ' ';
      return text;
    }

    template <class T>
    T check(T result, const std::string &file, const std::string &what)
    {
      if (result < 0)
        throw ResultsError(
          fmt::format("results file '{}': {} failed: {}", file, what, hdf5_error_text()));
      return result;
    }

    using Closer = detail::Hdf5Handle;
    using detail::utf8_string_type;

    std::string join_path(const std::string &parent, std::string_view name)
    {
      return parent == "/" ? "/" + std::string(name) : parent + "/" + std::string(name);
    }

    void delete_attribute_if_present(hid_t object, const std::string &name)
    {
      if (H5Aexists(object, name.c_str()) > 0)
        H5Adelete(object, name.c_str());
    }

    void write_string_attribute(hid_t              object,
                                const std::string &name,
                                std::string_view   value,
                                const std::string &file,
                                const std::string &where)
    {
      delete_attribute_if_present(object, name);
      const Closer      type(utf8_string_type(), H5Tclose);
      const Closer      space(H5Screate(H5S_SCALAR), H5Sclose);
      const std::string what = fmt::format("attribute '{}' of '{}'", name, where);
      const Closer      attribute(
        check(H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
              file,
              "creating " + what),
        H5Aclose);
      const std::string text(value);
      const char       *pointer = text.c_str();
      check(H5Awrite(attribute.get(), type.get(), &pointer), file, "writing " + what);
    }

    template <class T>
    void write_numeric_attribute(hid_t              object,
                                 const std::string &name,
                                 hid_t              file_type,
                                 hid_t              memory_type,
                                 const T           *values,
                                 hsize_t            n,
                                 bool               scalar,
                                 const std::string &file,
                                 const std::string &where)
    {
      delete_attribute_if_present(object, name);
      const Closer space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr),
                         H5Sclose);
      const std::string what = fmt::format("attribute '{}' of '{}'", name, where);
      const Closer      attribute(
        check(H5Acreate2(object, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
              file,
              "creating " + what),
        H5Aclose);
      check(H5Awrite(attribute.get(), memory_type, values), file, "writing " + what);
    }

    /// Create a dataset of `rank` dims, write `data` and its `units` attribute.
    void write_dataset(hid_t                       group,
                       const std::string          &group_path,
                       std::string_view            name,
                       hid_t                       file_type,
                       hid_t                       memory_type,
                       const void                 *data,
                       const std::vector<hsize_t> &dims,
                       std::string_view            units,
                       const std::string          &file)
    {
      const std::string path = join_path(group_path, name);
      const Closer      space(dims.empty() ?
                           H5Screate(H5S_SCALAR) :
                           H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                         H5Sclose);
      const Closer dataset(check(H5Dcreate2(group,
                                            std::string(name).c_str(),
                                            file_type,
                                            space.get(),
                                            H5P_DEFAULT,
                                            H5P_DEFAULT,
                                            H5P_DEFAULT),
                                 file,
                                 "creating dataset '" + path + "'"),
                           H5Dclose);
      check(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
            file,
            "writing dataset '" + path + "'");
      write_string_attribute(dataset.get(), "units", units.empty() ? "1" : units, file, path);
    }

    /// Chunked dataset [0][width...] extendible along the first dimension.
    hid_t create_extendible(hid_t              group,
                            const std::string &path,
                            const char        *name,
                            hid_t              type,
                            std::size_t        width,
                            bool               matrix,
                            std::size_t        chunk_rows,
                            std::string_view   units,
                            const std::string &file)
    {
      const int     rank = matrix ? 2 : 1;
      const hsize_t dims[2]{0, width};
      const hsize_t max_dims[2]{H5S_UNLIMITED, width};
      const hsize_t chunk[2]{std::max<hsize_t>(1, chunk_rows), width};
      const Closer  space(H5Screate_simple(rank, dims, max_dims), H5Sclose);
      const Closer  properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
      check(H5Pset_chunk(properties.get(), rank, chunk), file, "chunking '" + path + "'");
      const hid_t dataset = check(
        H5Dcreate2(group, name, type, space.get(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
        file,
        "creating dataset '" + path + "/" + name + "'");
      write_string_attribute(dataset,
                             "units",
                             units.empty() ? "1" : units,
                             file,
                             path + "/" + name);
      return dataset;
    }

    void append_rows(hid_t              dataset,
                     hid_t              memory_type,
                     const void        *data,
                     std::size_t        first_row,
                     std::size_t        n_rows,
                     std::size_t        width,
                     bool               matrix,
                     const std::string &file,
                     const std::string &what)
    {
      const int     rank = matrix ? 2 : 1;
      const hsize_t new_dims[2]{first_row + n_rows, width};
      check(H5Dset_extent(dataset, new_dims), file, "extending " + what);
      const Closer  file_space(H5Dget_space(dataset), H5Sclose);
      const hsize_t start[2]{first_row, 0};
      const hsize_t count[2]{n_rows, width};
      check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
            file,
            "selecting rows of " + what);
      const Closer memory_space(H5Screate_simple(rank, count, nullptr), H5Sclose);
      check(H5Dwrite(dataset, memory_type, memory_space.get(), file_space.get(), H5P_DEFAULT, data),
            file,
            "writing " + what);
    }

    std::string utc_now()
    {
      const std::time_t now = std::time(nullptr);
      std::tm           utc{};
      gmtime_r(&now, &utc);
      std::array<char, 32> text{};
      std::strftime(text.data(), text.size(), "%Y-%m-%dT%H:%M:%SZ", &utc);
      return text.data();
    }
  } // namespace

  // ---------------------------------------------------------------------------------------------

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

  // ---------------------------------------------------------------------------------------------

  ResultsGroup::ResultsGroup(std::shared_ptr<detail::ResultsFileState> file,
                             std::int64_t                              id,
                             std::string                               path)
    : file_(std::move(file))
    , id_(id)
    , path_(std::move(path))
  {
  }

  ResultsGroup::ResultsGroup(ResultsGroup &&other) noexcept
    : file_(std::move(other.file_))
    , id_(other.id_)
    , path_(std::move(other.path_))
  {
    other.id_ = -1;
  }

  ResultsGroup &ResultsGroup::operator=(ResultsGroup &&other) noexcept
  {
    if (this != &other)
    {
      if (id_ >= 0 && file_ && file_->open())
        H5Gclose(id_);
      file_     = std::move(other.file_);
      id_       = other.id_;
      path_     = std::move(other.path_);
      other.id_ = -1;
    }
    return *this;
  }

  ResultsGroup::~ResultsGroup()
  {
    if (id_ >= 0 && file_ && file_->open())
      H5Gclose(id_);
  }

  ResultsGroup ResultsGroup::group(std::string_view name)
  {
    if (name.empty())
      throw ResultsError(
        fmt::format("results file '{}': empty group name below '{}'", file_->name, path_));
    hid_t       current = H5Oopen(id_, ".", H5P_DEFAULT);
    std::string path    = path_;
    std::size_t begin   = 0;
    while (begin <= name.size())
    {
      const std::size_t end       = std::min(name.find('/', begin), name.size());
      const std::string component = std::string(name.substr(begin, end - begin));
      begin                       = end + 1;
      if (component.empty())
        continue;
      path = join_path(path, component);
      const Closer parent(current, H5Oclose);
      const htri_t exists = H5Lexists(parent.get(), component.c_str(), H5P_DEFAULT);
      current =
        exists > 0 ?
          H5Gopen2(parent.get(), component.c_str(), H5P_DEFAULT) :
          H5Gcreate2(parent.get(), component.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      check(current, file_->name, "opening group '" + path + "'");
    }
    return ResultsGroup(file_, current, path);
  }

  ResultsGroup ResultsGroup::case_group(std::string_view name)
  {
    ResultsGroup g = group(name);
    g.set_status("running");
    return g;
  }

  void ResultsGroup::set_status(std::string_view status)
  {
    set_attribute("status", status);
  }

  void ResultsGroup::write(std::string_view           name,
                           const std::vector<double> &values,
                           std::string_view           units)
  {
    write_dataset(id_,
                  path_,
                  name,
                  H5T_IEEE_F64LE,
                  H5T_NATIVE_DOUBLE,
                  values.data(),
                  {values.size()},
                  units,
                  file_->name);
  }

  void ResultsGroup::write(std::string_view                 name,
                           const std::vector<std::int64_t> &values,
                           std::string_view                 units)
  {
    write_dataset(id_,
                  path_,
                  name,
                  H5T_STD_I64LE,
                  H5T_NATIVE_INT64,
                  values.data(),
                  {values.size()},
                  units,
                  file_->name);
  }

  void ResultsGroup::write_matrix(std::string_view           name,
                                  const std::vector<double> &row_major,
                                  std::size_t                n_rows,
                                  std::size_t                n_cols,
                                  std::string_view           units)
  {
    if (row_major.size() != n_rows * n_cols)
      throw ResultsError(fmt::format("dataset '{}': {} values given for a {} x {} matrix",
                                     join_path(path_, name),
                                     row_major.size(),
                                     n_rows,
                                     n_cols));
    write_dataset(id_,
                  path_,
                  name,
                  H5T_IEEE_F64LE,
                  H5T_NATIVE_DOUBLE,
                  row_major.data(),
                  {n_rows, n_cols},
                  units,
                  file_->name);
  }

  void ResultsGroup::write_scalar(std::string_view name, double value, std::string_view units)
  {
    write_dataset(id_,
                  path_,
                  name,
                  H5T_IEEE_F64LE,
                  H5T_NATIVE_DOUBLE,
                  &value,
                  {},
                  units,
                  file_->name);
  }

  void ResultsGroup::write(std::string_view name, const std::vector<std::string> &values)
  {
    const Closer              type(utf8_string_type(), H5Tclose);
    std::vector<const char *> pointers;
    pointers.reserve(values.size());
    for (const std::string &v : values)
      pointers.push_back(v.c_str());
    write_dataset(id_,
                  path_,
                  name,
                  type.get(),
                  type.get(),
                  pointers.data(),
                  {values.size()},
                  "1",
                  file_->name);
  }

  void ResultsGroup::write_text(std::string_view name, std::string_view text)
  {
    const Closer      type(utf8_string_type(), H5Tclose);
    const std::string copy(text);
    const char       *pointer = copy.c_str();
    write_dataset(id_, path_, name, type.get(), type.get(), &pointer, {}, "1", file_->name);
  }

  void ResultsGroup::write_time_series(std::string_view                 name,
                                       const std::vector<std::int64_t> &steps,
                                       const std::vector<double>       &times,
                                       const std::vector<double>       &values,
                                       std::size_t                      width,
                                       std::string_view                 units)
  {
    if (times.size() != steps.size() || values.size() != steps.size() * width)
      throw ResultsError(fmt::format("time series '{}': {} steps, {} times and {} values "
                                     "(expected {} values for width {})",
                                     join_path(path_, name),
                                     steps.size(),
                                     times.size(),
                                     values.size(),
                                     steps.size() * width,
                                     width));
    TimeSeries series = time_series(name, width, units, std::max<std::size_t>(steps.size(), 1));
    for (std::size_t i = 0; i < steps.size(); ++i)
      series.append(steps[i], times[i], values.data() + i * width);
    series.flush();
  }

  std::shared_ptr<detail::TimeSeriesState> ResultsGroup::make_series(ResultsGroup    &g,
                                                                     std::size_t      width,
                                                                     std::string_view units,
                                                                     std::size_t      buffer_rows,
                                                                     const ResultsGroup *clock)
  {
    if (width == 0)
      throw ResultsError(fmt::format("time series '{}': width must be >= 1", g.path()));
    auto state              = std::make_shared<detail::TimeSeriesState>();
    state->file             = file_;
    state->path             = g.path();
    state->width            = width;
    state->matrix           = width > 1;
    state->buffer_rows      = std::max<std::size_t>(buffer_rows, 1);
    const std::size_t chunk = std::min<std::size_t>(state->buffer_rows, 4096);
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
    return TimeSeries(make_series(g, width, units, buffer_rows, nullptr));
  }

  TimeSeriesSet ResultsGroup::time_series_set(const std::vector<SeriesSpec> &specs,
                                              std::size_t                    buffer_rows)
  {
    if (specs.empty())
      throw ResultsError(fmt::format("time series set below '{}': no quantities", path_));
    TimeSeriesSet set;
    ResultsGroup  clock = group(specs.front().name);
    for (std::size_t i = 0; i < specs.size(); ++i)
    {
      ResultsGroup g = group(specs[i].name);
      set.states_.push_back(
        make_series(g, specs[i].width, specs[i].units, buffer_rows, i == 0 ? nullptr : &clock));
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

  void ResultsGroup::write_table(std::string_view name, const std::vector<TableColumn> &columns)
  {
    ResultsGroup             table = group(name);
    std::vector<std::string> names;
    for (const auto &column : columns)
    {
      if (column.values.size() != columns.front().values.size())
        throw ResultsError(fmt::format("table '{}': column '{}' has {} rows, column '{}' has {}",
                                       table.path(),
                                       column.name,
                                       column.values.size(),
                                       columns.front().name,
                                       columns.front().values.size()));
      table.write(column.name, column.values, column.units);
      names.push_back(column.name);
    }
    std::string list;
    for (const auto &n : names)
      list += (list.empty() ? "" : ",") + n;
    table.set_attribute("columns", list);
  }

  void ResultsGroup::set_attribute(std::string_view name, std::string_view value)
  {
    write_string_attribute(id_, std::string(name), value, file_->name, path_);
  }

  void ResultsGroup::set_attribute(std::string_view name, const char *value)
  {
    set_attribute(name, std::string_view(value));
  }

  void ResultsGroup::set_attribute(std::string_view name, double value)
  {
    write_numeric_attribute(id_,
                            std::string(name),
                            H5T_IEEE_F64LE,
                            H5T_NATIVE_DOUBLE,
                            &value,
                            1,
                            true,
                            file_->name,
                            path_);
  }

  void ResultsGroup::set_attribute(std::string_view name, const std::vector<int> &values)
  {
    write_numeric_attribute(id_,
                            std::string(name),
                            H5T_STD_I32LE,
                            H5T_NATIVE_INT,
                            values.data(),
                            values.size(),
                            false,
                            file_->name,
                            path_);
  }

  void ResultsGroup::set_integer_attribute(std::string_view name, std::int64_t value)
  {
    write_numeric_attribute(id_,
                            std::string(name),
                            H5T_STD_I64LE,
                            H5T_NATIVE_INT64,
                            &value,
                            1,
                            true,
                            file_->name,
                            path_);
  }

  // ---------------------------------------------------------------------------------------------

  namespace
  {
    /// Close the in-memory HDF5 file and the temporary file and delete it; never throws. The
    /// HDF5 file lives in memory (core driver without backing store), so closing it does no I/O
    /// and cannot fail on a full disk: no HDF5 id outlives a failed run.
    void discard(detail::ResultsFileState &state)
    {
      if (state.open())
      {
        H5Fclose(state.file);
        state.file = -1;
        H5Eclear2(H5E_DEFAULT);
      }
      if (state.fd >= 0)
      {
        ::close(state.fd);
        state.fd = -1;
      }
      if (state.temporary)
        state.temporary->discard();
    }

    /// Write `size` bytes to `fd` from its start; returns 0 or the errno of the failure.
    int write_all(int fd, const unsigned char *data, std::size_t size)
    {
      std::size_t done = 0;
      while (done < size)
      {
        const ssize_t n = ::write(fd, data + done, size - done);
        if (n < 0)
        {
          if (errno == EINTR)
            continue;
          return errno;
        }
        done += static_cast<std::size_t>(n);
      }
      return ::fsync(fd) == 0 ? 0 : errno;
    }
  } // namespace

  ResultsFile::ResultsFile(std::filesystem::path final_path,
                           std::string_view      scene_text,
                           std::string_view      resolved_json)
    : final_path_(std::move(final_path))
    , temporary_path_(final_path_.string() + ".tmp-" + std::to_string(::getpid()))
    , state_(std::make_shared<detail::ResultsFileState>())
  {
    detail::silence_hdf5_errors();
    state_->name = final_path_.string();
    state_->temporary.emplace(final_path_);

    // The temporary file is created now, so that an unwritable directory is an error before any
    // computation; its bytes are written at commit().
    state_->fd = ::open(temporary_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (state_->fd < 0)
      throw ResultsError(fmt::format("results file '{}': cannot create '{}': {}",
                                     state_->name,
                                     temporary_path_.string(),
                                     std::strerror(errno)));
    try
    {
      // The file is built in memory (core driver, no backing store) and written by commit():
      // HDF5 then never meets a write error, which it cannot recover from (a file whose flush
      // fails cannot be closed, and HDF5's exit handler crashes on it).
      // STRONG close: closing the file also closes every group or dataset still held by a
      // caller, so the file is complete at commit() and removable on failure.
      const Closer access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
      H5Pset_fclose_degree(access.get(), H5F_CLOSE_STRONG);
      // The driver zeroes each increment as it grows the image, so the increment is resident at
      // once: 1 MiB keeps a small run's process small (16 MiB cost a lumped run 15 MiB of RSS);
      // large files grow by realloc, which moves the pages without copying.
      constexpr std::size_t core_increment = std::size_t(1) << 20; // bytes
      check(H5Pset_fapl_core(access.get(), core_increment, 0), state_->name, "in-memory file");
      state_->file =
        check(H5Fcreate(temporary_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()),
              state_->name,
              "creating temporary file '" + temporary_path_.string() + "'");
      ResultsGroup top  = root();
      ResultsGroup meta = top.group("meta");
      meta.set_attribute("schema_version",
                         std::vector<int>{results_schema_major, results_schema_minor});
      meta.set_attribute("creator", "kimp");
      meta.set_attribute("creator_version", kimp::base::version);
      meta.set_attribute("git_revision", kimp::base::git_revision);
      meta.set_attribute("created_utc", utc_now());
      ResultsGroup input = top.group("input");
      input.write_text("scene", scene_text);
      input.write_text("resolved", resolved_json);
    }
    catch (...)
    {
      discard(*state_);
      throw;
    }
  }

  ResultsFile::ResultsFile(ResultsFile &&other) noexcept
    : final_path_(std::move(other.final_path_))
    , temporary_path_(std::move(other.temporary_path_))
    , state_(std::move(other.state_))
    , committed_(other.committed_)
  {
  }

  ResultsFile::~ResultsFile()
  {
    if (!state_ || committed_)
      return;
    discard(*state_);
  }

  ResultsGroup ResultsFile::root()
  {
    if (!state_ || !state_->open())
      throw ResultsError(
        fmt::format("results file '{}' is already committed or closed", final_path_.string()));
    return ResultsGroup(state_,
                        check(H5Gopen2(state_->file, "/", H5P_DEFAULT), state_->name, "opening /"),
                        "/");
  }

  void ResultsFile::commit()
  {
    if (!state_ || !state_->open())
      throw ResultsError(
        fmt::format("results file '{}' is already committed or closed", final_path_.string()));
    try
    {
      for (const auto &weak : state_->series)
        if (const auto series = weak.lock())
          series->flush();
      if (!state_->deferred_error.empty())
        throw ResultsError(state_->deferred_error);
      check(H5Fflush(state_->file, H5F_SCOPE_GLOBAL), state_->name, "flushing");
      const ssize_t              size = check(H5Fget_file_image(state_->file, nullptr, 0),
                                 state_->name,
                                 "measuring the file image");
      std::vector<unsigned char> image(static_cast<std::size_t>(size));
      check(H5Fget_file_image(state_->file, image.data(), image.size()),
            state_->name,
            "copying the file image");
      const herr_t closed = H5Fclose(state_->file);
      state_->file        = -1;
      check(closed, state_->name, "closing");
      const int write_error = write_all(state_->fd, image.data(), image.size());
      const int close_error = ::close(state_->fd) == 0 ? 0 : errno;
      state_->fd            = -1;
      if (write_error != 0 || close_error != 0)
        throw ResultsError(
          fmt::format("results file '{}': writing {} bytes to '{}' failed: {}",
                      state_->name,
                      image.size(),
                      temporary_path_.string(),
                      std::strerror(write_error != 0 ? write_error : close_error)));
      try
      {
        state_->temporary->commit();
      }
      catch (const OutputError &error)
      {
        throw ResultsError(fmt::format("results file {}", error.what()));
      }
    }
    catch (...)
    {
      discard(*state_);
      throw;
    }
    committed_ = true;
  }
} // namespace kimp::io
