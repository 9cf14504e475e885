// kimp::testing::Hdf5Reader: read-only access to an HDF5 file with the HDF5 C API, independent of
// kimp::io's own reader so that the tests check io's writer against a second implementation.
#pragma once

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <hdf5.h>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/scoped_handle.h"

namespace kimp::testing
{
  /**
   * An HDF5 file opened read-only. Opening never throws (ok() says whether it worked); a read
   * that fails throws std::runtime_error naming the object, so that the test fails there.
   * Strings are read as variable-length UTF-8 (what kimp::io writes; HDF5 does not convert
   * between character sets, so another encoding is an error too).
   */
  class Hdf5Reader
  {
  public:
    explicit Hdf5Reader(const std::filesystem::path &file)
      : file_(file.string())
      , id_(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT))
    {
    }

    /// Whether the file could be opened.
    bool ok() const { return id_ >= 0; }

    /// The HDF5 file id, for checks the reader does not offer.
    hid_t id() const { return id_; }

    /// Whether the link `path` exists (its parent groups must exist).
    bool exists(const std::string &path) const
    {
      return H5Lexists(id_, path.c_str(), H5P_DEFAULT) > 0;
    }

    /// The extent of `dataset` (empty for a scalar).
    std::vector<hsize_t> dims(const std::string &dataset) const
    {
      const hid_t          d     = open_dataset(dataset);
      const hid_t          space = H5Dget_space(d);
      const int            rank  = H5Sget_simple_extent_ndims(space);
      std::vector<hsize_t> result(static_cast<std::size_t>(std::max(rank, 0)));
      H5Sget_simple_extent_dims(space, result.data(), nullptr);
      H5Sclose(space);
      H5Dclose(d);
      return result;
    }

    /// Every value of `dataset`, converted by HDF5 to `memory_type` (e.g. H5T_NATIVE_DOUBLE).
    template <class T>
    std::vector<T> read(const std::string &dataset, hid_t memory_type) const
    {
      std::size_t n = 1;
      for (const hsize_t extent : dims(dataset))
        n *= extent;
      std::vector<T> values(n);
      const hid_t    d      = open_dataset(dataset);
      const herr_t   status = H5Dread(d, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
      H5Dclose(d);
      if (status < 0)
        throw std::runtime_error(file_ + ": cannot read " + dataset);
      return values;
    }

    /// Every value of `dataset` as double.
    std::vector<double> doubles(const std::string &dataset) const
    {
      return read<double>(dataset, H5T_NATIVE_DOUBLE);
    }

    /// The scalar string dataset `dataset`.
    std::string text(const std::string &dataset) const
    {
      const hid_t  d       = open_dataset(dataset);
      const hid_t  type    = string_type();
      char        *pointer = nullptr;
      const herr_t status  = H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &pointer);
      std::string  result  = pointer != nullptr ? pointer : "";
      H5free_memory(pointer);
      H5Tclose(type);
      H5Dclose(d);
      if (status < 0)
        throw std::runtime_error(file_ + ": cannot read " + dataset + " as text");
      return result;
    }

    /// The string attribute `name` of the object at `path`, or "<missing>" if it has none.
    std::string attribute(const std::string &path, const std::string &name) const
    {
      if (H5Aexists_by_name(id_, path.c_str(), name.c_str(), H5P_DEFAULT) <= 0)
        return "<missing>";
      const hid_t  a = H5Aopen_by_name(id_, path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
      const hid_t  type    = string_type();
      char        *pointer = nullptr;
      const herr_t status  = H5Aread(a, type, &pointer);
      std::string  result  = pointer != nullptr ? pointer : "";
      H5free_memory(pointer);
      H5Tclose(type);
      H5Aclose(a);
      if (status < 0)
        throw std::runtime_error(file_ + ": cannot read " + path + " @" + name + " as text");
      return result;
    }

    /// The `units` attribute of the object at `path`, or "<missing>".
    std::string units(const std::string &path) const { return attribute(path, "units"); }

    /// Every value of the numeric attribute `name` of the object at `path`.
    template <class T>
    std::vector<T>
    numeric_attribute(const std::string &path, const std::string &name, hid_t memory_type) const
    {
      const hid_t a = H5Aopen_by_name(id_, path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
      if (a < 0)
        throw std::runtime_error(file_ + ": no attribute " + path + " @" + name);
      const hid_t    space = H5Aget_space(a);
      const auto     n     = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
      std::vector<T> values(n);
      const herr_t   status = H5Aread(a, memory_type, values.data());
      H5Sclose(space);
      H5Aclose(a);
      if (status < 0)
        throw std::runtime_error(file_ + ": cannot read " + path + " @" + name);
      return values;
    }

    /// The absolute path of every dataset in the file, found by visiting all links.
    std::vector<std::string> datasets() const
    {
      std::vector<std::string> names;
      H5Ovisit2(
        id_,
        H5_INDEX_NAME,
        H5_ITER_NATIVE,
        [](hid_t, const char *name, const H5O_info_t *info, void *data) -> herr_t
        {
          if (info->type == H5O_TYPE_DATASET)
            static_cast<std::vector<std::string> *>(data)->push_back(std::string("/") + name);
          return 0;
        },
        &names,
        H5O_INFO_BASIC);
      return names;
    }

  private:
    hid_t open_dataset(const std::string &dataset) const
    {
      const hid_t d = H5Dopen2(id_, dataset.c_str(), H5P_DEFAULT);
      if (d < 0)
        throw std::runtime_error(file_ + ": no dataset " + dataset);
      return d;
    }

    static hid_t string_type()
    {
      const hid_t type = H5Tcopy(H5T_C_S1);
      H5Tset_size(type, H5T_VARIABLE);
      H5Tset_cset(type, H5T_CSET_UTF8);
      return type;
    }

    std::string                   file_;
    ScopedHandle<hid_t, H5Fclose> id_;
  };
} // namespace kimp::testing
