// HDF5 results file -> JSON (io/results_json.h): a generic walk of groups, attributes and
// datasets with the HDF5 C API, so the report needs no knowledge of each command's layout here.
#include "io/results_json.h"

#include <hdf5.h>
#include <string>
#include <vector>

#include "io/hdf5_handle.h"
#include "io/results_file.h"

namespace kimp::io
{
  namespace
  {
    using detail::Hdf5Handle;

    std::string read_text(hid_t object, hid_t type, bool attribute)
    {
      if (H5Tis_variable_str(type) > 0)
      {
        Hdf5Handle   memory(detail::utf8_string_type(), H5Tclose);
        char        *text   = nullptr;
        const herr_t status = attribute ?
                                H5Aread(object, memory.get(), &text) :
                                H5Dread(object, memory.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text);
        std::string  result = (status >= 0 && text != nullptr) ? std::string(text) : std::string();
        if (text != nullptr)
          H5free_memory(text);
        return result;
      }
      const std::size_t size = H5Tget_size(type);
      std::string       buffer(size, '\0');
      Hdf5Handle        memory(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(memory.get(), size);
      const herr_t status =
        attribute ? H5Aread(object, memory.get(), buffer.data()) :
                    H5Dread(object, memory.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data());
      if (status < 0)
        return {};
      return buffer.substr(0, buffer.find('\0'));
    }

    std::vector<hsize_t> shape_of(hid_t space)
    {
      const int            rank = H5Sget_simple_extent_ndims(space);
      std::vector<hsize_t> dims(rank > 0 ? rank : 0);
      if (rank > 0)
        H5Sget_simple_extent_dims(space, dims.data(), nullptr);
      return dims;
    }

    /// Attribute value: numbers (scalar or 1-D), strings (scalar or 1-D variable length).
    nlohmann::json read_attribute(hid_t object, const char *name)
    {
      Hdf5Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
      if (attribute.get() < 0)
        return nullptr;
      Hdf5Handle                 type(H5Aget_type(attribute.get()), H5Tclose);
      Hdf5Handle                 space(H5Aget_space(attribute.get()), H5Sclose);
      const std::vector<hsize_t> dims = shape_of(space.get());
      hsize_t                    n    = 1;
      for (hsize_t d : dims)
        n *= d;
      const H5T_class_t kind = H5Tget_class(type.get());
      if (kind == H5T_STRING)
      {
        if (dims.empty())
          return read_text(attribute.get(), type.get(), true);
        if (H5Tis_variable_str(type.get()) > 0)
        {
          std::vector<char *> texts(n, nullptr);
          Hdf5Handle          memory(detail::utf8_string_type(), H5Tclose);
          nlohmann::json      list = nlohmann::json::array();
          if (H5Aread(attribute.get(), memory.get(), texts.data()) >= 0)
            for (char *t : texts)
              list.push_back(t != nullptr ? std::string(t) : std::string());
          H5Dvlen_reclaim(memory.get(), space.get(), H5P_DEFAULT, texts.data());
          return list;
        }
        return nullptr;
      }
      if (kind == H5T_INTEGER || kind == H5T_FLOAT)
      {
        std::vector<double> values(n);
        if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, values.data()) < 0)
          return nullptr;
        if (dims.empty())
          return values.at(0);
        return values;
      }
      return nullptr;
    }

    nlohmann::json attributes_of(hid_t object)
    {
      nlohmann::json attributes = nlohmann::json::object();
      H5O_info_t     info;
#if H5_VERSION_GE(1, 12, 0)
      H5Oget_info3(object, &info, H5O_INFO_NUM_ATTRS);
#else
      H5Oget_info2(object, &info, H5O_INFO_NUM_ATTRS);
#endif
      for (hsize_t i = 0; i < info.num_attrs; ++i)
      {
        char name[256];
        if (H5Aget_name_by_idx(object,
                               ".",
                               H5_INDEX_NAME,
                               H5_ITER_INC,
                               i,
                               name,
                               sizeof(name),
                               H5P_DEFAULT) < 0)
          continue;
        attributes[name] = read_attribute(object, name);
      }
      return attributes;
    }

    nlohmann::json read_dataset(hid_t dataset, std::size_t max_rows)
    {
      Hdf5Handle                 type(H5Dget_type(dataset), H5Tclose);
      Hdf5Handle                 space(H5Dget_space(dataset), H5Sclose);
      const std::vector<hsize_t> dims = shape_of(space.get());
      nlohmann::json             entry;
      entry["shape"]          = dims;
      const nlohmann::json at = attributes_of(dataset);
      entry["units"]          = at.contains("units") ? at["units"] : nlohmann::json("1");
      const H5T_class_t kind  = H5Tget_class(type.get());
      hsize_t           n     = 1;
      for (hsize_t d : dims)
        n *= d;
      if (kind == H5T_STRING)
      {
        if (dims.empty())
          entry["data"] = read_text(dataset, type.get(), false);
        else if (H5Tis_variable_str(type.get()) > 0 && dims.size() == 1)
        {
          std::vector<char *> texts(n, nullptr);
          Hdf5Handle          memory(detail::utf8_string_type(), H5Tclose);
          nlohmann::json      list = nlohmann::json::array();
          if (H5Dread(dataset, memory.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, texts.data()) >= 0)
            for (char *t : texts)
              list.push_back(t != nullptr ? std::string(t) : std::string());
          H5Dvlen_reclaim(memory.get(), space.get(), H5P_DEFAULT, texts.data());
          entry["data"] = list;
        }
        return entry;
      }
      if (kind != H5T_INTEGER && kind != H5T_FLOAT)
        return entry;
      std::vector<double> values(n);
      if (n > 0 &&
          H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
        return entry;
      if (dims.empty())
      {
        entry["data"] = values.at(0);
        return entry;
      }
      const std::size_t rows  = dims[0];
      const std::size_t width = rows > 0 ? n / rows : 0;
      const std::size_t stride =
        rows > max_rows && max_rows > 0 ? (rows + max_rows - 1) / max_rows : 1;
      entry["stride"]     = stride;
      nlohmann::json data = nlohmann::json::array();
      for (std::size_t r = 0; r < rows; r += stride)
      {
        // Keep the last row so a decimated series still ends at the end of the run.
        const std::size_t row = (r + stride >= rows) ? rows - 1 : r;
        if (dims.size() == 1)
          data.push_back(values[row]);
        else
          data.push_back(
            std::vector<double>(values.begin() + row * width, values.begin() + (row + 1) * width));
        if (row == rows - 1)
          break;
      }
      entry["data"] = std::move(data);
      return entry;
    }

    struct Walk
    {
      nlohmann::json *groups;
      nlohmann::json *datasets;
      std::size_t     max_rows;
    };

    herr_t visit(hid_t root, const char *name, const H5O_info_t *info, void *data)
    {
      auto             &walk = *static_cast<Walk *>(data);
      const std::string path = std::string(name) == "." ? "/" : "/" + std::string(name);
      if (info->type == H5O_TYPE_GROUP)
      {
        Hdf5Handle group(H5Gopen2(root, name, H5P_DEFAULT), H5Gclose);
        if (group.get() >= 0)
          (*walk.groups)[path] = attributes_of(group.get());
      }
      else if (info->type == H5O_TYPE_DATASET)
      {
        Hdf5Handle dataset(H5Dopen2(root, name, H5P_DEFAULT), H5Dclose);
        if (dataset.get() >= 0)
          (*walk.datasets)[path] = read_dataset(dataset.get(), walk.max_rows);
      }
      return 0;
    }
  } // namespace

  nlohmann::json results_to_json(const std::filesystem::path &path, std::size_t max_rows)
  {
    // A damaged file is one ResultsError below, not HDF5's error stack on stderr.
    detail::silence_hdf5_errors();
    Hdf5Handle file(H5Fopen(path.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (file.get() < 0)
      throw ResultsError(path.string() + ": cannot open as an HDF5 results file");
    nlohmann::json groups   = nlohmann::json::object();
    nlohmann::json datasets = nlohmann::json::object();
    Walk           walk{&groups, &datasets, max_rows};
#if H5_VERSION_GE(1, 12, 0)
    H5Ovisit3(file.get(), H5_INDEX_NAME, H5_ITER_INC, visit, &walk, H5O_INFO_BASIC);
#else
    H5Ovisit2(file.get(), H5_INDEX_NAME, H5_ITER_INC, visit, &walk, H5O_INFO_BASIC);
#endif
    return {{"groups", std::move(groups)}, {"datasets", std::move(datasets)}};
  }
} // namespace kimp::io
