// kimp::testing::ScopedHandle: an integer handle of a C API (a file descriptor, an HDF5 id) that
// is closed when its owner ends.
#pragma once

namespace kimp::testing
{
  /**
   * Owns the handle `id` (valid when >= 0) and passes it to `Close` at the end of its life;
   * neither copied nor moved. Converts to the handle for the calls of its C API.
   */
  template <class Id, auto Close>
  class ScopedHandle
  {
  public:
    explicit ScopedHandle(const Id id)
      : id_(id)
    {
    }
    ~ScopedHandle() { reset(); }
    ScopedHandle(const ScopedHandle &)            = delete;
    ScopedHandle &operator=(const ScopedHandle &) = delete;

    /// Closes the handle now (when valid); it is invalid (-1) from then on.
    void reset()
    {
      if (id_ >= 0)
        Close(id_);
      id_ = -1;
    }

    operator Id() const { return id_; }

  private:
    Id id_;
  };
} // namespace kimp::testing
