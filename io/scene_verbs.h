// The verbs a scene struct's visit() calls, declared once for every Io (SceneReader,
// DefaultsPrinter, JsonWriter, SchemaWriter). A key with a single value reaches the Io as one call,
// value(key, member); a section as open_section(key, doc) and finish() around its keys.
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
#include <variant>
#include <vector>

#include "io/scene_source.h"

namespace kimp::io
{
  /// What a verb declares besides the member: the key, its meaning and, for a quantity, its
  /// display unit (e.g. "MN/m") and admissible range (SI bounds).
  struct Key
  {
    std::string_view key;
    std::string_view doc;
    std::string_view unit;
    const Range     &range;
  };

  /// The member behind a key of one value, by kind: a quantity (a double, an optional one or a
  /// list, SI), a flag, a text, a YAML value kept as text, an integer in [min, max], or the index
  /// of a choice among its options.
  struct Member
  {
    struct Text
    {
      std::string *value;
    };
    struct Yaml
    {
      std::string *text;
    };
    struct Integer
    {
      long long *value;
      long long  min;
      long long  max;
    };
    struct Choice
    {
      std::size_t                    *index;
      const std::vector<std::string> *options;
    };
    using Ref = std::variant<double *,
                             std::optional<double> *,
                             std::vector<double> *,
                             bool *,
                             Text,
                             Yaml,
                             Integer,
                             Choice>;
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

    /// The range of a key declared without one.
    inline const Range &unbounded()
    {
      static const Range range;
      return range;
    }
  } // namespace detail

  /**
   * The verbs of every Io. A key of one value goes to the Io's `value(const Key &, Member::Ref)`;
   * a section to `std::optional<Io> open_section(key, doc)`, the keys of visit_keys on it, then
   * its finish(); lists, optional sections and maps are the Io's own templates.
   */
  template <class Derived>
  class IoVerbs
  {
  public:
    /// Quantity with a unit, stored in SI; `unit` is the display unit (e.g. "MN/m"). A value
    /// written in a file outside `range` is refused by the reader (a default is not checked).
    /// `Q` is double, or std::optional<double>: absent keeps the default, `null` clears it;
    /// `range` applies when set.
    template <class Q>
    std::enable_if_t<std::is_same_v<Q, double> || std::is_same_v<Q, std::optional<double>>>
    quantity(std::string_view key,
             Q               &value,
             std::string_view unit,
             std::string_view doc,
             const Range     &range = detail::unbounded())
    {
      self().value(Key{key, doc, unit, range}, &value);
    }

    /// List of quantities; `range` applies to every item (failures at "key[i]").
    void quantity_list(std::string_view     key,
                       std::vector<double> &values,
                       std::string_view     unit,
                       std::string_view     doc,
                       const Range         &range = detail::unbounded())
    {
      self().value(Key{key, doc, unit, range}, &values);
    }

    void flag(std::string_view key, bool &value, std::string_view doc)
    {
      self().value(Key{key, doc, {}, detail::unbounded()}, &value);
    }

    void text(std::string_view key, std::string &value, std::string_view doc)
    {
      self().value(Key{key, doc, {}, detail::unbounded()}, Member::Text{&value});
    }

    /**
     * A text holding a quantity or one of the words the key admits ("auto", "" = not set, ...),
     * kept as written for a caller that interprets the words: a time step "auto" or "1e-4 s", an
     * impact stiffness whose unit N/m^n depends on the law's exponent. A text written in a file
     * that reads as a number with a unit is held to `range` (SI bounds) by the reader like a
     * quantity, and refused when subnormal, so that no key typed as text escapes the range check;
     * the words and the dimension are rules of validate(). `unit` is the display unit of the
     * range and the listing ("s", "N/m^n").
     */
    void quantity_text(std::string_view key,
                       std::string     &value,
                       std::string_view unit,
                       std::string_view doc,
                       const Range     &range)
    {
      self().value(Key{key, doc, unit, range}, Member::Text{&value});
    }

    /**
     * Any YAML value (scalar, list or map) kept as one line of flow-style YAML text, for a caller
     * that interprets it itself (e.g. a sweep's list of values or {from, to, step}); `null` gives
     * "~". The reader records the lines of its items as "key[i]" and "key.sub".
     */
    void raw(std::string_view key, std::string &yaml_text, std::string_view doc)
    {
      self().value(Key{key, doc, {}, detail::unbounded()}, Member::Yaml{&yaml_text});
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
      self().value(Key{key, doc, {}, detail::unbounded()}, Member::Integer{&v, min, max});
      value = static_cast<Int>(v);
    }

    /// One of `options`.
    void choice(std::string_view                key,
                std::string                    &value,
                const std::vector<std::string> &options,
                std::string_view                doc)
    {
      std::size_t index = index_of(options, [&](const std::string &o) { return o == value; });
      self().value(Key{key, doc, {}, detail::unbounded()}, Member::Choice{&index, &options});
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
      self().value(Key{key, doc, {}, detail::unbounded()}, Member::Choice{&index, &names});
      value = table.at(index).second;
    }

    /// Ends a section opened by open_section(); an Io with nothing to check or close there keeps
    /// this one.
    void finish() {}

    /// A section whose keys are those of visit(io, value).
    template <class T>
    void section(std::string_view key, T &value, std::string_view doc)
    {
      section(key, value, doc, detail::VisitKeys{});
    }

    /// A section whose keys `visit_keys(io, value)` declares: for a section whose keys live in
    /// several structs (e.g. an engine's options beside the scene's own).
    template <class T, class VisitKeys>
    void section(std::string_view key, T &value, std::string_view doc, VisitKeys visit_keys)
    {
      if (std::optional<Derived> sub = self().open_section(key, doc))
      {
        visit_keys(*sub, value);
        sub->finish();
      }
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
