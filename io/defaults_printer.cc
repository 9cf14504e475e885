// The annotated default scene of `--print-defaults`; see defaults_printer.h.
#include "io/defaults_printer.h"

#include <fmt/format.h>

#include "io/units.h"

namespace kimp::io
{
  using detail::integer_range_text;
  using detail::join;

  namespace
  {
    std::string yaml_quote(std::string_view text)
    {
      std::string quoted = "\"";
      for (const char c : text)
      {
        switch (c)
        {
          case '"':
            quoted += "\\\"";
            break;
          case '\\':
            quoted += "\\\\";
            break;
          case '\n':
            quoted += "\\n";
            break;
          case '\t':
            quoted += "\\t";
            break;
          default:
            quoted += c;
        }
      }
      return quoted + "\"";
    }

    std::string unit_comment(std::string_view unit)
    {
      return unit.empty() ? std::string("dimensionless") : std::string(unit);
    }

    /// Unit and range of a quantity's comment: "MN/m", "MN/m, > 0".
    std::string unit_range_comment(std::string_view unit, const Range &range)
    {
      return range.bounded() ? unit_comment(unit) + ", " + range.text(unit) : unit_comment(unit);
    }
  } // namespace

  DefaultsPrinter::DefaultsPrinter(std::ostream &out)
    : out_(&out)
  {
  }

  DefaultsPrinter DefaultsPrinter::child(std::string lead, std::string first_lead) const
  {
    DefaultsPrinter sub(*out_);
    sub.lead_       = std::move(lead);
    sub.first_lead_ = std::move(first_lead);
    return sub;
  }

  void DefaultsPrinter::line(std::string_view key,
                             std::string_view value,
                             std::string_view comment,
                             std::string_view extra_lead)
  {
    const std::string lead = first_lead_.empty() ? lead_ : first_lead_;
    first_lead_.clear();
    *out_ << lead << extra_lead << key << ':';
    if (!value.empty())
      *out_ << ' ' << value;
    *out_ << "  # " << comment << '\n';
  }

  void DefaultsPrinter::quantity_value(const QuantityKey &key, double &value)
  {
    line(key.key,
         yaml_quote(format_quantity(value, key.unit)),
         fmt::format("{} [{}]", key.doc, unit_range_comment(key.unit, key.range)));
  }

  void DefaultsPrinter::quantity_value(const QuantityKey &key, std::optional<double> &value)
  {
    line(key.key,
         value ? yaml_quote(format_quantity(*value, key.unit)) : std::string("null"),
         fmt::format("{} [{}] (optional: null = not set)",
                     key.doc,
                     unit_range_comment(key.unit, key.range)));
  }

  void DefaultsPrinter::quantity_value(const QuantityKey &key, std::vector<double> &values)
  {
    std::vector<std::string> items;
    for (const double v : values)
      items.push_back(yaml_quote(format_quantity(v, key.unit)));
    line(key.key,
         "[" + join(items, ", ") + "]",
         fmt::format("{} [{}, list{}]",
                     key.doc,
                     unit_comment(key.unit),
                     key.range.bounded() ? ", each " + key.range.text(key.unit) : std::string()));
  }

  void DefaultsPrinter::flag(std::string_view key, bool &value, std::string_view doc)
  {
    line(key, value ? "true" : "false", fmt::format("{} (true or false)", doc));
  }

  void DefaultsPrinter::text(std::string_view key, std::string &value, std::string_view doc)
  {
    line(key, yaml_quote(value), doc);
  }

  void DefaultsPrinter::raw(std::string_view key, std::string &yaml_text, std::string_view doc)
  {
    const std::string value = yaml_text.empty() ? std::string("null") : yaml_text;
    if (!doc.empty())
    {
      line(key, value, doc);
      return;
    }
    *out_ << (first_lead_.empty() ? lead_ : first_lead_) << key << ": " << value << '\n';
    first_lead_.clear();
  }

  void DefaultsPrinter::integer_value(std::string_view key,
                                      long long       &value,
                                      std::string_view doc,
                                      long long        min,
                                      long long        max)
  {
    line(key, std::to_string(value), fmt::format("{} ({})", doc, integer_range_text(min, max)));
  }

  void DefaultsPrinter::choice_index(std::string_view                key,
                                     std::size_t                    &index,
                                     const std::vector<std::string> &options,
                                     std::string_view                doc)
  {
    line(key,
         yaml_quote(options.at(index)),
         fmt::format("{} (one of: {})", doc, join(options, ", ")));
  }
} // namespace kimp::io
