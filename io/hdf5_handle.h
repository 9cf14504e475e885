// The HDF5 identifier of kimp::io (private to io/): closed at scope exit by its close function,
// so that no early return or exception leaks an open file, group, dataset, type or space.
#pragma once

#include <hdf5.h>

namespace kimp::io::detail
{
  /// Owns one HDF5 id (a negative id owns nothing) and closes it with `close` at scope exit.
  class Hdf5Handle
  {
  public:
    Hdf5Handle(hid_t id, herr_t (*close)(hid_t))
      : id_(id)
      , close_(close)
    {
    }
    Hdf5Handle(const Hdf5Handle &)            = delete;
    Hdf5Handle &operator=(const Hdf5Handle &) = delete;
    ~Hdf5Handle()
    {
      if (id_ >= 0)
        close_(id_);
    }
    hid_t get() const { return id_; }

  private:
    hid_t id_;
    herr_t (*close_)(hid_t);
  };

  /// Switch off HDF5's automatic printing of its error stack (process-wide): kimp turns every
  /// HDF5 failure into one exception with a one-line message instead.
  inline void silence_hdf5_errors()
  {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }

  /// A variable-length UTF-8 string type (the caller closes it with H5Tclose).
  inline hid_t utf8_string_type()
  {
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    return type;
  }
} // namespace kimp::io::detail
