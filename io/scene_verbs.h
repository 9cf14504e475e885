// The verbs a scene struct's visit() calls, shared by every Io (SceneReader, DefaultsPrinter,
// JsonWriter, SchemaWriter): each verb is declared here once and forwards to the one member of
// the Io that does its work (quantity_value, integer_value, choice_index, section).
#pragma once

#include <algorithm>
#include <climits>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "io/scene_source.h"

namespace kimp::io
{
  /// What a quantity verb declares besides the member: key, display unit (e.g. "MN/m"), meaning
  /// and admissible range (SI bounds).
  struct QuantityKey
  {
    std::string_view key;
    std::string_view unit;
    std::string_view doc;
    const Range     &range;
  };

  namespace detail
  {
    /// The keys of a section: its struct's visit(), found by argument-dependent lookup.
    struct VisitKeys
    {
      template <class Io, class T>
      void operator()(Io &io, T &value) const
      {
        visit(io, value);
      }
    };

    /// One value of a map_of(): a std::string is kept as YAML text (raw()), any other T is a
    /// section visited through its visit().
    template <class Io, class T>
    void visit_map_value(Io &io, const std::string &name, T &value, std::string_view doc)
    {
      if constexpr (std::is_same_v<T, std::string>)
        io.raw(name, value, doc);
      else
        io.section(name, value, doc);
    }
  } // namespace detail

  /**
   * Verbs shared by every Io. Quantities (a double, an optional one or a list) go to the Io's
   * `quantity_value(const QuantityKey &, T &)`, integer types to `integer_value`, enum and string
   * choices to `choice_index`, a section to `section(key, value, doc, visit_keys)`.
   */
  template <class Derived>
  class IoVerbs
  {
  public:
    /// Quantity with a unit, stored in SI; `unit` is the display unit (e.g. "MN/m"). A value
    /// written in a file outside `range` is refused by the reader (a default is not checked).
    void quantity(std::string_view key,
                  double          &value,
                  std::string_view unit,
                  std::string_view doc,
                  const Range     &range = {})
    {
      self().quantity_value(QuantityKey{key, unit, doc, range}, value);
    }

    /// Optional quantity: absent keeps the default, `null` clears it; `range` applies when set.
    void quantity(std::string_view       key,
                  std::optional<double> &value,
                  std::string_view       unit,
                  std::string_view       doc,
                  const Range           &range = {})
    {
      self().quantity_value(QuantityKey{key, unit, doc, range}, value);
    }

    /// List of quantities; `range` applies to every item (failures at "key[i]").
    void quantity_list(std::string_view     key,
                       std::vector<double> &values,
                       std::string_view     unit,
                       std::string_view     doc,
                       const Range         &range = {})
    {
      self().quantity_value(QuantityKey{key, unit, doc, range}, values);
    }

    /// Integer `key` in [min, max] and in the range of Int (so an unsigned key is >= 0).
    template <class Int>
    std::enable_if_t<std::is_integral_v<Int> && !std::is_same_v<Int, bool>>
    integer(std::string_view key,
            Int             &value,
            std::string_view doc,
            long long        min = LLONG_MIN,
            long long        max = LLONG_MAX)
    {
      min = std::max<long long>(min, static_cast<long long>(std::numeric_limits<Int>::lowest()));
      if constexpr (std::is_signed_v<Int> || sizeof(Int) < sizeof(long long))
        max = std::min<long long>(max, static_cast<long long>(std::numeric_limits<Int>::max()));
      long long v = static_cast<long long>(value);
      self().integer_value(key, v, doc, min, max);
      value = static_cast<Int>(v);
    }

    /// One of `options`.
    void choice(std::string_view                key,
                std::string                    &value,
                const std::vector<std::string> &options,
                std::string_view                doc)
    {
      std::size_t index = index_of(options, [&](const std::string &o) { return o == value; });
      self().choice_index(key, index, options, doc);
      value = options.at(index);
    }

    /// An enum class through its string table, e.g. {{"linear", Kind::linear}, ...}.
    template <class E>
    std::enable_if_t<std::is_enum_v<E>> choice(std::string_view                              key,
                                               E                                            &value,
                                               const std::vector<std::pair<std::string, E>> &table,
                                               std::string_view                              doc)
    {
      std::vector<std::string> names;
      for (const auto &entry : table)
        names.push_back(entry.first);
      std::size_t index = index_of(table, [&](const auto &entry) { return entry.second == value; });
      self().choice_index(key, index, names, doc);
      value = table.at(index).second;
    }

    /// A section whose keys are those of visit(io, value).
    template <class T>
    void section(std::string_view key, T &value, std::string_view doc)
    {
      self().section(key, value, doc, detail::VisitKeys{});
    }

  private:
    Derived &self() { return static_cast<Derived &>(*this); }

    template <class Container, class Predicate>
    static std::size_t index_of(const Container &container, Predicate predicate)
    {
      for (std::size_t i = 0; i < container.size(); ++i)
        if (predicate(container[i]))
          return i;
      throw std::logic_error("scene default is not one of its own choices");
    }
  };
} // namespace kimp::io
