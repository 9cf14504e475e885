// FEM impact results: /fem/<case> written through ResultsGroup, read back with the HDF5 C API.
#include "io/fem_results.h"

#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <hdf5.h>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "io/hdf5_handle.h"

namespace kimp::io
{
  namespace
  {
    struct SeriesField
    {
      const char         *name;
      std::vector<double> FemCase::*member;
      const char                   *units;
    };

    // Order of writing; contact_force is the required one whose time axis the others share.
    const std::vector<SeriesField> &series_fields()
    {
      static const std::vector<SeriesField> fields = {
        {"contact_force", &FemCase::contact_force, "N/m"},
        {"smoothed_contact_force", &FemCase::smoothed_contact_force, "N/m"},
        {"indentation", &FemCase::indentation, "m"},
        {"slab_displacement", &FemCase::slab_displacement, "m"},
        {"slab_velocity", &FemCase::slab_velocity, "m/s"},
        {"wall_displacement", &FemCase::wall_displacement, "m"}};
      return fields;
    }

    struct ScalarField
    {
      const char *name;
      double FemCase::*member;
      const char      *units;
    };

    const std::vector<ScalarField> &scalar_fields()
    {
      static const std::vector<ScalarField> fields = {{"wall_height", &FemCase::wall_height, "m"},
                                                      {"slab_mass", &FemCase::slab_mass, "kg/m"},
                                                      {"impact_velocity",
                                                       &FemCase::impact_velocity,
                                                       "m/s"}};
      return fields;
    }

    /// A field of FemSummary: a real value or a count, with its units.
    struct SummaryField
    {
      const char           *name;
      const char           *units;
      std::optional<double> FemSummary::*real        = nullptr;
      std::optional<std::int64_t> FemSummary::*count = nullptr;
    };

    /// The fields of FemSummary in the order of the struct.
    const std::vector<SummaryField> &summary_fields()
    {
      using S                                       = FemSummary;
      static const std::vector<SummaryField> fields = {
        {"peak_force", "N/m", &S::peak_force},
        {"peak_force_raw", "N/m", &S::peak_force_raw},
        {"contact_start", "s", &S::contact_start},
        {"contact_duration", "s", &S::contact_duration},
        {"impulse", "N*s/m", &S::impulse},
        {"rebound_velocity", "m/s", &S::rebound_velocity},
        {"apparent_cor", "1", &S::apparent_cor},
        {"energy_error", "1", &S::energy_error},
        {"smoothing_window", "s", &S::smoothing_window},
        {"max_penetration", "m", &S::max_penetration},
        {"mean_penetration", "m", &S::mean_penetration},
        {"initial_gap", "m", &S::initial_gap},
        {"penalty_stiffness", "N/m/m", &S::penalty_stiffness},
        {"mesh_level", "1", nullptr, &S::mesh_level},
        {"penalty_factor", "1", &S::penalty_factor},
        {"contact_subcycles", "1", nullptr, &S::contact_subcycles},
        {"n_dofs", "1", nullptr, &S::n_dofs},
        {"n_cells", "1", nullptr, &S::n_cells},
        {"n_steps", "1", nullptr, &S::n_steps},
        {"n_newton", "1", nullptr, &S::n_newton},
        {"n_step_halvings", "1", nullptr, &S::n_step_halvings},
        {"n_linear_solves", "1", nullptr, &S::n_linear_solves},
        {"linear_solver_seconds", "s", &S::linear_solver_seconds},
        {"linear_setup_seconds", "s", &S::linear_setup_seconds},
        {"n_ranks", "1", nullptr, &S::n_ranks},
        {"dt", "s", &S::dt},
        {"dt_stable", "s", &S::dt_stable},
        {"wall_time", "s", &S::wall_time},
        {"plastic_dissipation", "J/m", &S::plastic_dissipation},
        {"damage_dissipation", "J/m", &S::damage_dissipation},
        {"contact_dissipation", "J/m", &S::contact_dissipation},
        {"residual_energy", "J/m", &S::residual_energy},
        {"dissipation_cor", "1", &S::dissipation_cor},
        {"permanent_indentation", "m", &S::permanent_indentation},
        {"wall_residual_displacement", "m", &S::wall_residual_displacement},
        {"stored_energy_share", "1", &S::stored_energy_share},
        {"radiated_energy", "J/m", &S::radiated_energy},
        {"slab_damping_dissipation", "J/m", &S::slab_damping_dissipation},
        {"boundary_spring_energy", "J/m", &S::boundary_spring_energy},
        {"plastic_dissipation_slab", "J/m", &S::plastic_dissipation_slab},
        {"plastic_dissipation_wall", "J/m", &S::plastic_dissipation_wall},
        {"plastic_dissipation_soil", "J/m", &S::plastic_dissipation_soil},
        {"damage_dissipation_slab", "J/m", &S::damage_dissipation_slab},
        {"damage_dissipation_wall", "J/m", &S::damage_dissipation_wall},
        {"damage_dissipation_soil", "J/m", &S::damage_dissipation_soil},
        {"first_peak_force", "N/m", &S::first_peak_force},
        {"first_peak_time", "s", &S::first_peak_time},
        {"first_peak_impulse", "N*s/m", &S::first_peak_impulse},
        {"max_slab_displacement", "m", &S::max_slab_displacement},
        {"max_wall_displacement", "m", &S::max_wall_displacement},
        {"energy_equivalent_resistance", "N/m", &S::energy_equivalent_resistance},
        {"time_to_stop", "s", &S::time_to_stop},
        {"time_to_95_travel", "s", &S::time_to_95_travel},
        {"max_bar_strain_ratio", "1", &S::max_bar_strain_ratio},
        {"max_bar_strain_height", "m", &S::max_bar_strain_height},
        {"max_bar_gauge_strain_ratio", "1", &S::max_bar_gauge_strain_ratio},
        {"max_bar_gauge_strain_height", "m", &S::max_bar_gauge_strain_height},
        {"bar_gauge_length", "m", &S::bar_gauge_length},
        {"impulse_momentum_ratio", "1", &S::impulse_momentum_ratio},
        {"geostatic_weight", "N/m", &S::geostatic_weight},
        {"geostatic_residual", "1", &S::geostatic_residual},
        {"geostatic_iterations", "1", nullptr, &S::geostatic_iterations},
        {"geostatic_plastic_dissipation", "J/m", &S::geostatic_plastic_dissipation},
        {"geostatic_wall_displacement", "m", &S::geostatic_wall_displacement},
        {"interface_normal_force", "N/m", &S::interface_normal_force},
        {"friction_dissipation", "J/m", &S::friction_dissipation}};
      return fields;
    }

    const SummaryField *summary_field(const std::string &key)
    {
      for (const SummaryField &field : summary_fields())
        if (key == field.name)
          return &field;
      return nullptr;
    }

    using Handle = detail::Hdf5Handle;

    /// Reading context: the file name for every message.
    class Reader
    {
    public:
      explicit Reader(std::string file)
        : file_(std::move(file))
      {
      }

      [[noreturn]] void fail(const std::string &object, const std::string &problem) const
      {
        throw ResultsError(fmt::format("FEM results file '{}': {}: {}", file_, object, problem));
      }

      bool exists(hid_t location, const std::string &path) const
      {
        return H5Lexists(location, path.c_str(), H5P_DEFAULT) > 0;
      }

      hid_t open_group(hid_t location, const std::string &path) const
      {
        if (!exists(location, path))
          fail(path, "group missing");
        const hid_t group = H5Gopen2(location, path.c_str(), H5P_DEFAULT);
        if (group < 0)
          fail(path, "cannot open group");
        return group;
      }

      std::string string_attribute(hid_t object, const char *name, const std::string &where) const
      {
        if (H5Aexists(object, name) <= 0)
          fail(where, fmt::format("attribute '{}' missing", name));
        const Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
        const Handle type(H5Aget_type(attribute.get()), H5Tclose);
        if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) <= 0)
          fail(where, fmt::format("attribute '{}' is not a variable-length string", name));
        const Handle memory_type(detail::utf8_string_type(), H5Tclose);
        char        *text = nullptr;
        if (H5Aread(attribute.get(), memory_type.get(), &text) < 0 || text == nullptr)
          fail(where, fmt::format("cannot read attribute '{}'", name));
        std::string result(text);
        H5free_memory(text);
        return result;
      }

      /// Whole float64 dataset (scalar or 1-D) with its units attribute checked.
      std::vector<double> doubles(hid_t              location,
                                  const std::string &path,
                                  const std::string &where,
                                  const std::string &expected_units) const
      {
        if (!exists(location, path))
          fail(where, "dataset missing");
        const Handle dataset(H5Dopen2(location, path.c_str(), H5P_DEFAULT), H5Dclose);
        if (dataset.get() < 0)
          fail(where, "cannot open dataset");
        const Handle space(H5Dget_space(dataset.get()), H5Sclose);
        const int    rank = H5Sget_simple_extent_ndims(space.get());
        if (rank > 1)
          fail(where, fmt::format("rank {} dataset, expected a scalar or 1-D one", rank));
        const hssize_t n = H5Sget_simple_extent_npoints(space.get());
        if (n < 0)
          fail(where, "cannot read the dataset size");
        std::vector<double> values(static_cast<std::size_t>(n));
        if (n > 0 && H5Dread(dataset.get(),
                             H5T_NATIVE_DOUBLE,
                             H5S_ALL,
                             H5S_ALL,
                             H5P_DEFAULT,
                             values.data()) < 0)
          fail(where, "cannot read the values");
        const std::string units = string_attribute(dataset.get(), "units", where);
        if (!expected_units.empty() && units != expected_units)
          fail(where, fmt::format("units '{}', expected '{}'", units, expected_units));
        return values;
      }

      double scalar(hid_t              location,
                    const std::string &path,
                    const std::string &where,
                    const std::string &expected_units) const
      {
        const std::vector<double> values = doubles(location, path, where, expected_units);
        if (values.size() != 1)
          fail(where, fmt::format("{} values, expected one", values.size()));
        return values.front();
      }

      std::string text(hid_t location, const std::string &path, const std::string &where) const
      {
        const Handle dataset(H5Dopen2(location, path.c_str(), H5P_DEFAULT), H5Dclose);
        if (dataset.get() < 0)
          fail(where, "cannot open dataset");
        const Handle type(H5Dget_type(dataset.get()), H5Tclose);
        if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) <= 0)
          fail(where, "not a variable-length string dataset");
        const Handle memory_type(detail::utf8_string_type(), H5Tclose);
        char        *value = nullptr;
        if (H5Dread(dataset.get(), memory_type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &value) < 0 ||
            value == nullptr)
          fail(where, "cannot read the string");
        std::string result(value);
        H5free_memory(value);
        return result;
      }

      /// Names of the links of a group in increasing name order.
      std::vector<std::string> children(hid_t group, const std::string &where) const
      {
        H5G_info_t info{};
        if (H5Gget_info(group, &info) < 0)
          fail(where, "cannot list the group");
        std::vector<std::string> names;
        for (hsize_t i = 0; i < info.nlinks; ++i)
        {
          const ssize_t length =
            H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
          if (length < 0)
            fail(where, "cannot read a link name");
          std::string name(static_cast<std::size_t>(length) + 1, '\0');
          H5Lget_name_by_idx(group,
                             ".",
                             H5_INDEX_NAME,
                             H5_ITER_INC,
                             i,
                             name.data(),
                             name.size(),
                             H5P_DEFAULT);
          name.resize(static_cast<std::size_t>(length));
          names.push_back(std::move(name));
        }
        return names;
      }

      const std::string &file() const { return file_; }

    private:
      std::string file_;
    };

    void check_schema(const Reader &reader, hid_t file)
    {
      const Handle meta(reader.open_group(file, "/meta"), H5Gclose);
      if (H5Aexists(meta.get(), "schema_version") <= 0)
        reader.fail("/meta", "attribute 'schema_version' missing");
      const Handle attribute(H5Aopen(meta.get(), "schema_version", H5P_DEFAULT), H5Aclose);
      const Handle space(H5Aget_space(attribute.get()), H5Sclose);
      if (H5Sget_simple_extent_npoints(space.get()) != 2)
        reader.fail("/meta", "attribute 'schema_version' must hold two integers");
      int version[2] = {-1, -1};
      if (H5Aread(attribute.get(), H5T_NATIVE_INT, version) < 0)
        reader.fail("/meta", "cannot read attribute 'schema_version'");
      if (version[0] != results_schema_major)
        reader.fail("/meta",
                    fmt::format("schema_version {}.{} (this kimp reads major version {})",
                                version[0],
                                version[1],
                                results_schema_major));
    }

    FemCase read_case(const Reader &reader, hid_t fem, const std::string &name)
    {
      const std::string path = "/fem/" + name;
      const Handle      group(reader.open_group(fem, name), H5Gclose);
      FemCase           result;
      result.name   = name;
      result.status = reader.string_attribute(group.get(), "status", path);

      if (reader.exists(group.get(), "labels"))
      {
        const Handle labels(reader.open_group(group.get(), "labels"), H5Gclose);
        for (const std::string &key : reader.children(labels.get(), path + "/labels"))
          result.labels[key] = reader.text(labels.get(), key, path + "/labels/" + key);
      }
      if (result.status != "ok")
        return result;

      for (const ScalarField &field : scalar_fields())
        result.*field.member =
          reader.scalar(group.get(), field.name, path + "/" + field.name, field.units);

      bool have_time = false;
      for (const SeriesField &field : series_fields())
      {
        const std::string series = path + "/" + field.name;
        if (!reader.exists(group.get(), field.name))
        {
          if (std::string(field.name) == "contact_force")
            reader.fail(series, "time series missing (required)");
          continue;
        }
        const Handle              g(reader.open_group(group.get(), field.name), H5Gclose);
        const std::vector<double> time = reader.doubles(g.get(), "time", series + "/time", "s");
        std::vector<double>       value =
          reader.doubles(g.get(), "value", series + "/value", field.units);
        if (value.size() != time.size())
          reader.fail(series, fmt::format("{} values for {} times", value.size(), time.size()));
        if (!have_time)
        {
          result.time = time;
          have_time   = true;
        }
        else if (time != result.time)
          reader.fail(series + "/time", "differs from the time axis of contact_force");
        result.*field.member = std::move(value);
      }

      if (reader.exists(group.get(), "summary"))
      {
        const Handle summary(reader.open_group(group.get(), "summary"), H5Gclose);
        for (const std::string &key : reader.children(summary.get(), path + "/summary"))
        {
          const std::string where = path + "/summary/" + key;
          result.summary.set(key, reader.scalar(summary.get(), key, where, ""));
          const Handle        dataset(H5Dopen2(summary.get(), key.c_str(), H5P_DEFAULT), H5Dclose);
          const std::string   units = reader.string_attribute(dataset.get(), "units", where);
          const SummaryField *field = summary_field(key == "wall_seconds" ? "wall_time" : key);
          if (field == nullptr || units != field->units)
            result.summary_units[key] = units;
        }
      }
      return result;
    }
  } // namespace

  std::map<std::string, double> FemSummary::entries() const
  {
    std::map<std::string, double> result = extra;
    for (const SummaryField &field : summary_fields())
      if (field.real && this->*field.real)
        result[field.name] = *(this->*field.real);
      else if (field.count && this->*field.count)
        result[field.name] = static_cast<double>(*(this->*field.count));
    return result;
  }

  void FemSummary::set(const std::string &key, double value)
  {
    // Files written before the key was named like every command's wall time.
    const SummaryField *field = summary_field(key == "wall_seconds" ? "wall_time" : key);
    if (field == nullptr)
      extra[key] = value;
    else if (field->real)
      this->*field->real = value;
    else if (std::isfinite(value) && std::abs(value) < 9.0e15)
      this->*field->count = std::llround(value);
    else
      throw std::invalid_argument(fmt::format("FEM summary: {} = {} is not a count", key, value));
  }

  nlohmann::ordered_json FemSummary::json() const
  {
    nlohmann::ordered_json result = nlohmann::ordered_json::object();
    for (const SummaryField &field : summary_fields())
      if (field.real && this->*field.real)
        result[field.name] = *(this->*field.real);
      else if (field.count && this->*field.count)
        result[field.name] = *(this->*field.count);
    for (const auto &[key, value] : extra)
      result[key] = value;
    return result;
  }

  std::string fem_summary_units(const FemCase &fem_case, const std::string &key)
  {
    if (const auto given = fem_case.summary_units.find(key); given != fem_case.summary_units.end())
      return given->second;
    if (const SummaryField *field = summary_field(key))
      return field->units;
    throw ResultsError(fmt::format("FEM case '{}': summary key '{}' has no known units (give "
                                   "them in FemCase::summary_units)",
                                   fem_case.name,
                                   key));
  }

  void write_fem_case(ResultsGroup &fem_root, const FemCase &fem_case)
  {
    if (fem_case.name.empty() || fem_case.name.find('/') != std::string::npos)
      throw std::invalid_argument(
        fmt::format("FEM case: name = '{}' (must be non-empty, without '/')", fem_case.name));
    const std::size_t n = fem_case.time.size();
    for (const SeriesField &field : series_fields())
    {
      const std::size_t size = (fem_case.*field.member).size();
      if (size != 0 && size != n)
        throw std::invalid_argument(fmt::format("FEM case '{}': {} has {} samples, time has {}",
                                                fem_case.name,
                                                field.name,
                                                size,
                                                n));
    }
    // Resolve every summary unit before anything is written, so a bad key leaves no half case.
    std::map<std::string, std::string>  summary_units;
    const std::map<std::string, double> summary = fem_case.summary.entries();
    for (const auto &[key, value] : summary)
      summary_units[key] = fem_summary_units(fem_case, key);

    if (fem_case.status == "ok" && fem_case.contact_force.empty())
      throw std::invalid_argument(
        fmt::format("FEM case '{}': contact_force is empty (required)", fem_case.name));

    ResultsGroup group = fem_root.case_group(fem_case.name);
    if (!fem_case.labels.empty())
    {
      ResultsGroup labels = group.group("labels");
      for (const auto &[key, text] : fem_case.labels)
        labels.write_text(key, text);
    }
    if (fem_case.status == "ok")
    {
      for (const ScalarField &field : scalar_fields())
        group.write_scalar(field.name, fem_case.*field.member, field.units);

      std::vector<std::int64_t> steps(n);
      for (std::size_t i = 0; i < n; ++i)
        steps[i] = static_cast<std::int64_t>(i);
      for (const SeriesField &field : series_fields())
        if (!(fem_case.*field.member).empty())
          group.write_time_series(field.name,
                                  steps,
                                  fem_case.time,
                                  fem_case.*field.member,
                                  1,
                                  field.units);

      if (!summary.empty())
      {
        ResultsGroup summary_group = group.group("summary");
        for (const auto &[key, value] : summary)
          summary_group.write_scalar(key, value, summary_units.at(key));
      }
    }
    group.set_status(fem_case.status);
  }

  std::vector<FemCase> read_fem_cases(const std::filesystem::path &file)
  {
    const Reader reader(file.string());
    if (!std::filesystem::exists(file))
      reader.fail("/", "no such file");
    detail::silence_hdf5_errors();
    const Handle h5(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (h5.get() < 0)
      reader.fail("/", "not a readable HDF5 file");
    check_schema(reader, h5.get());
    const Handle         fem(reader.open_group(h5.get(), "/fem"), H5Gclose);
    std::vector<FemCase> cases;
    for (const std::string &name : reader.children(fem.get(), "/fem"))
      cases.push_back(read_case(reader, fem.get(), name));
    return cases;
  }
} // namespace kimp::io
