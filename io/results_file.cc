// HDF5 results file (C API, used serially): its groups, datasets and attributes, and the file's
// life (built in memory, written to a temporary file at commit, renamed); layout in
// results_file.h and docs/architecture.md "Results files". The time series are in
// results_series.cc, the HDF5 writing helpers in results_hdf5.h.
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
#include "io/output_dir.h"
#include "io/results_hdf5.h"

namespace kimp::io
{
  static_assert(std::is_same_v<hid_t, std::int64_t>, "kimp stores HDF5 ids as int64_t");

  using detail::check;
  using detail::Closer;
  using detail::join_path;
  using detail::utf8_string_type;
  using detail::write_dataset;
  using detail::write_numeric_attribute;
  using detail::write_string_attribute;

  namespace
  {
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
      const int write_error = write_all_and_sync(state_->fd, image.data(), image.size());
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
