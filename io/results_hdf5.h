// The HDF5 side of the results file (private to io/): the state a ResultsFile shares with its
// groups and time series, and the writing of attributes and datasets, each failure turned into
// one ResultsError naming the file, the object and HDF5's reason.
#pragma once

#include <cstddef>
#include <cstdint>
#include <fmt/format.h>
#include <hdf5.h>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/hdf5_handle.h"
#include "io/output_dir.h"
#include "io/results_file.h"

namespace kimp::io::detail
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

  /// One line from HDF5's error stack: the outermost and the innermost description (the
  /// whole stack runs to a dozen lines that say the same thing); clears the stack.
  std::string hdf5_error_text();

  /// `result`, or a ResultsError "results file '<file>': <what> failed: <HDF5's reason>" if < 0.
  template <class T>
  T check(T result, const std::string &file, const std::string &what)
  {
    if (result < 0)
      throw ResultsError(
        fmt::format("results file '{}': {} failed: {}", file, what, hdf5_error_text()));
    return result;
  }

  using Closer = Hdf5Handle;

  std::string join_path(const std::string &parent, std::string_view name);

  void delete_attribute_if_present(hid_t object, const std::string &name);

  void write_string_attribute(hid_t              object,
                              const std::string &name,
                              std::string_view   value,
                              const std::string &file,
                              const std::string &where);

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
    const Closer space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose);
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
                     const std::string          &file);

  /// Chunked dataset [0][width...] extendible along the first dimension.
  hid_t create_extendible(hid_t              group,
                          const std::string &path,
                          const char        *name,
                          hid_t              type,
                          std::size_t        width,
                          bool               matrix,
                          std::size_t        chunk_rows,
                          std::string_view   units,
                          const std::string &file);

  /// Write rows [first_row, first_row + n_rows) of an extendible dataset, extending it.
  void append_rows(hid_t              dataset,
                   hid_t              memory_type,
                   const void        *data,
                   std::size_t        first_row,
                   std::size_t        n_rows,
                   std::size_t        width,
                   bool               matrix,
                   const std::string &file,
                   const std::string &what);
} // namespace kimp::io::detail
