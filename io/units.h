// Physical quantities written as text with units ("2500 kN/mm", "750 kN/mm^1.5", "0.821 g"),
// converted to SI. A unit is a product of symbols with decimal exponents: value·Π(factor_i^e_i),
// dimension = Π(kg^a m^b s^c). Standard gravity g = 9.80665 m/s² (CGPM 1901); grams are not units.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace kimp::io
{
  /// Standard gravity, m/s² (CGPM 1901): the unit "g" of scene files and the unit of AT2 records.
  inline constexpr double standard_gravity = 9.80665;

  /// Bad quantity text: unknown unit, wrong dimension, missing unit, non-finite or empty value.
  class UnitError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /// Exponents of kg, m and s (decimal: a Hertz-type stiffness in N/m^1.5 is kg·m^-0.5·s^-2).
  struct Dimension
  {
    double mass   = 0.0;
    double length = 0.0;
    double time   = 0.0;

    /// True if every exponent agrees within 1e-9 (exponents are sums of decimal literals).
    bool operator==(const Dimension &other) const;
    bool operator!=(const Dimension &other) const { return !(*this == other); }
    bool dimensionless() const { return *this == Dimension{}; }
  };

  /// Dimension in base units, e.g. "kg m^-0.5 s^-2", or "1" when dimensionless.
  std::string to_string(const Dimension &dimension);

  /// A value in SI base units (kg, m, s) with its dimension.
  struct Quantity
  {
    double    value = 0.0;
    Dimension dimension;
  };

  /**
   * Parse a unit expression such as "kN/mm^1.5", "kN*s/m/m", "%", or "" (dimensionless).
   * Grammar: factor (('*' | '/') factor)*, factor = symbol ['^' decimal exponent]; every '/'
   * divides by the single factor that follows it. Symbols: m cm mm km, s ms, kg t, N kN MN,
   * Pa kPa MPa GPa, g (standard gravity), % (0.01) and 1.
   * @return the SI value of one unit and its dimension.
   * @throws UnitError naming the unknown symbol or the malformed part.
   */
  Quantity parse_unit(std::string_view unit);

  /**
   * Parse "number [unit]" ("2500 kN/mm", "5 %", "2e-5 s", "0.3"). A bare number is dimensionless.
   * @throws UnitError for empty text, a missing or non-finite number, or an unknown unit.
   */
  Quantity parse_quantity(std::string_view text);

  /**
   * Parse `text` and return its SI value, requiring the dimension of `expected_unit`
   * (e.g. "MN/m"). A bare number is accepted only when expected_unit is "" (dimensionless);
   * "%" demands the percent sign so that "5" is never read as 5 %.
   * @throws UnitError whose message says what was expected, e.g.
   *         "expected a stiffness like '2500 MN/m'".
   */
  double parse_quantity_as(std::string_view text, std::string_view expected_unit);

  /**
   * Format an SI value in `display_unit` with 15 significant digits (reads back within 1e-15
   * relative): format_quantity(2.5e9, "kN/mm") == "2500 kN/mm"; format_quantity(0.3, "") == "0.3".
   */
  std::string format_quantity(double value_in_si, std::string_view display_unit);

  /// A readable name for common dimensions ("stiffness", "length", ...), or "" if none.
  std::string dimension_name(const Dimension &dimension);
} // namespace kimp::io
