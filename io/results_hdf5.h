// The HDF5 side of the results file (private to io/): the state a ResultsFile shares with its
// groups and time series, and the writing of attributes and datasets, each failure turned into
// one ResultsError naming the file, the object and HDF5's reason.
#pragma once

#include <algorithm>
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

  /// Descriptions of the HDF5 error stack, outermost first.
  inline herr_t collect_error(unsigned int /*n*/, const H5E_error2_t *error, void *data)
  {
    auto *descriptions = static_cast<std::vector<std::string> *>(data);
    if (error->desc != nullptr && error->desc[0] != '\0')
      descriptions->emplace_back(error->desc);
    return 0;
  }

  /// One line from HDF5's error stack: the outermost and the innermost description (the
  /// whole stack runs to a dozen lines that say the same thing); clears the stack.
  inline std::string hdf5_error_text()
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

  inline std::string join_path(const std::string &parent, std::string_view name)
  {
    return parent == "/" ? "/" + std::string(name) : parent + "/" + std::string(name);
  }

  inline void delete_attribute_if_present(hid_t object, const std::string &name)
  {
    if (H5Aexists(object, name.c_str()) > 0)
      H5Adelete(object, name.c_str());
  }

  inline void write_string_attribute(hid_t              object,
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


  /// Create a dataset of `rank` dims, write `data` and its `units` attribute.

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

  /// The transfer properties of every dataset write: a 64 KiB type-conversion buffer instead of
  /// HDF5's default 1 MiB, which it allocates zeroed (fresh pages) for each write that converts
  /// (strings, labels, integers); larger writes are converted in pieces, to the same bytes.
  inline hid_t transfer_properties()
  {
    static const hid_t properties = []
    {
      const hid_t id = H5Pcreate(H5P_DATASET_XFER);
      if (id >= 0)
        H5Pset_buffer(id, std::size_t(64) << 10, nullptr, nullptr);
      return id;
    }();
    return properties >= 0 ? properties : H5P_DEFAULT;
  }

  /// Create a dataset of `rank` dims, write `data` and its `units` attribute.
  inline void write_dataset(hid_t                       group,
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
    check(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, transfer_properties(), data),
          file,
          "writing dataset '" + path + "'");
    write_string_attribute(dataset.get(), "units", units.empty() ? "1" : units, file, path);
  }

  /// Chunked dataset [0][width...] extendible along the first dimension.

  /// Chunked dataset [0][width...] extendible along the first dimension.
  inline hid_t create_extendible(hid_t              group,
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
    const hid_t dataset =
      check(H5Dcreate2(group, name, type, space.get(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
            file,
            "creating dataset '" + path + "/" + name + "'");
    write_string_attribute(dataset, "units", units.empty() ? "1" : units, file, path + "/" + name);
    return dataset;
  }

  /// Write rows [first_row, first_row + n_rows) of an extendible dataset, extending it.
  inline void append_rows(hid_t              dataset,
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
    check(H5Dwrite(dataset,
                   memory_type,
                   memory_space.get(),
                   file_space.get(),
                   transfer_properties(),
                   data),
          file,
          "writing " + what);
  }
} // namespace kimp::io::detail
