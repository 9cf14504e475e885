// Unit parser: "number unit" -> SI value and dimension (exponents of kg, m, s).
#include "io/units.h"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <string>

#include "base/format.h"

namespace kimp::io
{
  namespace
  {
    constexpr double exponent_tolerance = 1e-9;

    struct UnitSymbol
    {
      std::string_view symbol;
      double           factor;
      Dimension        dimension;
    };

    constexpr Dimension dimensionless{0, 0, 0};
    constexpr Dimension length{0, 1, 0};
    constexpr Dimension time_dim{0, 0, 1};
    constexpr Dimension mass{1, 0, 0};
    constexpr Dimension force{1, 1, -2};
    constexpr Dimension pressure{1, -1, -2};
    constexpr Dimension acceleration{0, 1, -2};

    constexpr std::array<UnitSymbol, 18> symbols{{
      {"m", 1.0, length},
      {"cm", 1e-2, length},
      {"mm", 1e-3, length},
      {"km", 1e3, length},
      {"s", 1.0, time_dim},
      {"ms", 1e-3, time_dim},
      {"kg", 1.0, mass},
      {"t", 1e3, mass},
      {"N", 1.0, force},
      {"kN", 1e3, force},
      {"MN", 1e6, force},
      {"Pa", 1.0, pressure},
      {"kPa", 1e3, pressure},
      {"MPa", 1e6, pressure},
      {"GPa", 1e9, pressure},
      {"g", standard_gravity, acceleration},
      {"%", 1e-2, dimensionless},
      {"1", 1.0, dimensionless},
    }};

    std::string known_symbols()
    {
      std::string list;
      for (const auto &s : symbols)
      {
        if (!list.empty())
          list += ", ";
        list += s.symbol;
      }
      return list;
    }

    std::string_view trim(std::string_view text)
    {
      const auto is_space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
      while (!text.empty() && is_space(text.front()))
        text.remove_prefix(1);
      while (!text.empty() && is_space(text.back()))
        text.remove_suffix(1);
      return text;
    }

    struct ParsedUnit
    {
      Quantity unit;
      bool     uses_gravity = false;
    };

    double parse_exponent(std::string_view text, std::string_view unit)
    {
      text               = trim(text);
      bool plain_decimal = !text.empty();
      for (const char c : text)
        if (!(std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == '-'))
          plain_decimal = false;
      double value            = 0.0;
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
      if (!plain_decimal || error != std::errc() || end != text.data() + text.size())
        throw UnitError(fmt::format("bad exponent '^{}' in unit '{}' (expected a decimal number "
                                    "such as ^2, ^-1 or ^1.5)",
                                    base::excerpt(text),
                                    base::excerpt(unit)));
      return value;
    }

    ParsedUnit parse_unit_detailed(std::string_view unit_text)
    {
      const std::string_view unit = trim(unit_text);
      ParsedUnit             parsed;
      parsed.unit.value = 1.0;
      if (unit.empty())
        return parsed;

      std::size_t pos  = 0;
      double      sign = 1.0; // +1 multiplies, -1 divides by the next factor
      while (true)
      {
        while (pos < unit.size() && unit[pos] == ' ')
          ++pos;
        std::size_t begin = pos;
        while (pos < unit.size() && unit[pos] != '*' && unit[pos] != '/' && unit[pos] != '^' &&
               unit[pos] != ' ')
          ++pos;
        const std::string_view symbol = unit.substr(begin, pos - begin);
        while (pos < unit.size() && unit[pos] == ' ')
          ++pos;
        double exponent = 1.0;
        if (pos < unit.size() && unit[pos] == '^')
        {
          begin = ++pos;
          while (pos < unit.size() && unit[pos] != '*' && unit[pos] != '/')
            ++pos;
          exponent = parse_exponent(unit.substr(begin, pos - begin), unit);
        }
        if (symbol.empty())
          throw UnitError(fmt::format("malformed unit '{}' (expected symbols joined by '*' or "
                                      "'/', each with an optional ^exponent, like 'kN/mm^1.5')",
                                      base::excerpt(unit)));
        const UnitSymbol *match = nullptr;
        for (const auto &s : symbols)
          if (s.symbol == symbol)
            match = &s;
        if (match == nullptr)
        {
          const bool looks_like_grams =
            symbol == "gram" || symbol == "grams" || (symbol.size() == 2 && symbol[1] == 'g');
          throw UnitError(
            fmt::format("unknown unit '{}' in '{}' (known: {}{})",
                        base::excerpt(symbol),
                        base::excerpt(unit),
                        known_symbols(),
                        looks_like_grams ? "; grams are not supported, use kg or t" : ""));
        }
        if (match->symbol == "g")
          parsed.uses_gravity = true;
        const double e = sign * exponent;
        // Exact division for plain quotients keeps "2500 kN/mm" printing as 2500.
        if (e == 1.0)
          parsed.unit.value *= match->factor;
        else if (e == -1.0)
          parsed.unit.value /= match->factor;
        else
          parsed.unit.value *= std::pow(match->factor, e);
        parsed.unit.dimension.mass += e * match->dimension.mass;
        parsed.unit.dimension.length += e * match->dimension.length;
        parsed.unit.dimension.time += e * match->dimension.time;

        if (pos >= unit.size())
          break;
        if (unit[pos] != '*' && unit[pos] != '/')
          throw UnitError(fmt::format("malformed unit '{}' near '{}' (expected '*' or '/' "
                                      "between unit symbols)",
                                      base::excerpt(unit),
                                      base::excerpt(unit.substr(pos))));
        sign = unit[pos] == '*' ? 1.0 : -1.0;
        ++pos;
      }
      return parsed;
    }

    struct ParsedQuantity
    {
      Quantity         quantity;
      std::string_view unit_text;
      ParsedUnit       unit;
    };

    ParsedQuantity parse_quantity_detailed(std::string_view raw)
    {
      const std::string_view text = trim(raw);
      if (text.empty())
        throw UnitError("empty quantity (expected a number with a unit, like '2500 kN/mm')");
      std::string_view number = text;
      if (number.front() == '+')
        number.remove_prefix(1);
      double value = 0.0;
      const auto [end, error] =
        std::from_chars(number.data(), number.data() + number.size(), value);
      if (error == std::errc::result_out_of_range)
        throw UnitError(
          fmt::format("'{}' is not a finite number (out of range)", base::excerpt(text)));
      if (error != std::errc() || end == number.data())
        throw UnitError(fmt::format("'{}' does not start with a number (expected a number with a "
                                    "unit, like '2500 kN/mm')",
                                    base::excerpt(text)));
      if (!std::isfinite(value))
        throw UnitError(fmt::format("'{}' is not a finite number", base::excerpt(text)));
      ParsedQuantity parsed;
      parsed.unit_text      = trim(number.substr(static_cast<std::size_t>(end - number.data())));
      parsed.unit           = parse_unit_detailed(parsed.unit_text);
      parsed.quantity.value = value * parsed.unit.unit.value;
      parsed.quantity.dimension = parsed.unit.unit.dimension;
      if (!std::isfinite(parsed.quantity.value))
        throw UnitError(fmt::format("'{}' overflows when converted to SI", base::excerpt(text)));
      return parsed;
    }

    std::string with_article(const std::string &noun)
    {
      const bool vowel =
        !noun.empty() && std::string_view("aeiou").find(noun.front()) != std::string_view::npos;
      return (vowel ? "an " : "a ") + noun;
    }

    std::string format_exponent(double e)
    {
      return e == 1.0 ? std::string() : fmt::format("^{}", e);
    }

    std::string describe_expected(const Dimension &dimension, std::string_view expected_unit)
    {
      const std::string name = dimension_name(dimension);
      if (dimension.dimensionless())
        return expected_unit.empty() ? std::string("expected a dimensionless number like '0.05'") :
                                       fmt::format("expected a dimensionless number with '{}', "
                                                   "like '5 {}'",
                                                   expected_unit,
                                                   expected_unit);
      return fmt::format("expected {} in units like '{}' ({})",
                         name.empty() ? std::string("a quantity") : with_article(name),
                         expected_unit,
                         to_string(dimension));
    }
  } // namespace

  bool Dimension::operator==(const Dimension &other) const
  {
    return std::abs(mass - other.mass) < exponent_tolerance &&
           std::abs(length - other.length) < exponent_tolerance &&
           std::abs(time - other.time) < exponent_tolerance;
  }

  std::string to_string(const Dimension &dimension)
  {
    std::string text;
    const auto  add = [&text](std::string_view symbol, double e)
    {
      if (std::abs(e) < exponent_tolerance)
        return;
      if (!text.empty())
        text += ' ';
      text += symbol;
      text += format_exponent(e);
    };
    add("kg", dimension.mass);
    add("m", dimension.length);
    add("s", dimension.time);
    return text.empty() ? std::string("1") : text;
  }

  std::string dimension_name(const Dimension &dimension)
  {
    struct Named
    {
      Dimension        dimension;
      std::string_view name;
    };
    static constexpr std::array<Named, 15> names{{
      {dimensionless, "dimensionless number"},
      {length, "length"},
      {time_dim, "time"},
      {mass, "mass"},
      {force, "force"},
      {pressure, "stress or stiffness per length"},
      {acceleration, "acceleration"},
      {{0, 1, -1}, "velocity"},
      {{1, 0, -2}, "stiffness"},
      {{1, 0, -1}, "damping coefficient"},
      {{1, -1, -1}, "damping coefficient per length"},
      {{1, -3, 0}, "density"},
      {{1, -1, 0}, "mass per length"},
      {{1, 2, -2}, "energy"},
      {{0, 0, -1}, "frequency"},
    }};
    for (const auto &n : names)
      if (n.dimension == dimension)
        return std::string(n.name);
    return {};
  }

  Quantity parse_unit(std::string_view unit)
  {
    return parse_unit_detailed(unit).unit;
  }

  Quantity parse_quantity(std::string_view text)
  {
    return parse_quantity_detailed(text).quantity;
  }

  double parse_quantity_as(std::string_view text, std::string_view expected_unit)
  {
    const Quantity expected = parse_unit(expected_unit);
    ParsedQuantity parsed;
    try
    {
      parsed = parse_quantity_detailed(text);
    }
    catch (const UnitError &error)
    {
      throw UnitError(
        fmt::format("{}; {}", error.what(), describe_expected(expected.dimension, expected_unit)));
    }
    const bool percent_expected = trim(expected_unit) == "%";
    if (parsed.unit_text.empty() && percent_expected)
      // A bare number could be a fraction (0.05) or a percentage (5): never guessed.
      throw UnitError(fmt::format("'{}' has no unit: a ratio given in % needs the percent sign "
                                  "(write '{:g} %' for the fraction {}, or '{} %')",
                                  base::excerpt(trim(text)),
                                  parsed.quantity.value * 100.0,
                                  base::excerpt(trim(text)),
                                  base::excerpt(trim(text))));
    if (parsed.unit_text.empty() && !expected.dimension.dimensionless())
      throw UnitError(fmt::format("'{}' has no unit: {}",
                                  base::excerpt(trim(text)),
                                  describe_expected(expected.dimension, expected_unit)));
    if (parsed.quantity.dimension != expected.dimension)
    {
      const std::string got_name = dimension_name(parsed.quantity.dimension);
      std::string       hint;
      if (parsed.unit.uses_gravity && std::abs(expected.dimension.mass) > exponent_tolerance)
        hint = " ('g' is standard gravity 9.80665 m/s^2; grams are not supported, use kg or t)";
      throw UnitError(fmt::format("'{}' has the wrong dimension: {}, got {}{}{}",
                                  base::excerpt(trim(text)),
                                  describe_expected(expected.dimension, expected_unit),
                                  got_name.empty() ? std::string() : with_article(got_name) + " ",
                                  "(" + to_string(parsed.quantity.dimension) + ")",
                                  hint));
    }
    return parsed.quantity.value;
  }

  std::string format_quantity(double value_in_si, std::string_view display_unit)
  {
    const Quantity unit      = parse_unit(display_unit);
    const double   value     = value_in_si / unit.value;
    const auto     unit_text = trim(display_unit);
    // 15 significant digits hide the last-bit noise of si/factor (0.15 m -> "15 cm").
    if (unit_text.empty())
      return fmt::format("{:.15g}", value);
    return fmt::format("{:.15g} {}", value, unit_text);
  }
} // namespace kimp::io
