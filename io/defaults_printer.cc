// The annotated default scene of `--print-defaults`; see defaults_printer.h.
#include "io/defaults_printer.h"

#include <fmt/format.h>
#include <variant>

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

  namespace
  {
    /// The value as written in the listing and the comment after it.
    struct Listing
    {
      std::string value;
      std::string comment;
    };

    Listing listing(const Key &key, const double *value)
    {
      return {yaml_quote(format_quantity(*value, key.unit)),
              fmt::format("{} [{}]", key.doc, unit_range_comment(key.unit, key.range))};
    }

    Listing listing(const Key &key, const std::optional<double> *value)
    {
      return {*value ? yaml_quote(format_quantity(**value, key.unit)) : std::string("null"),
              fmt::format("{} [{}] (optional: null = not set)",
                          key.doc,
                          unit_range_comment(key.unit, key.range))};
    }

    Listing listing(const Key &key, const std::vector<double> *values)
    {
      std::vector<std::string> items;
      for (const double v : *values)
        items.push_back(yaml_quote(format_quantity(v, key.unit)));
      return {"[" + join(items, ", ") + "]",
              fmt::format("{} [{}, list{}]",
                          key.doc,
                          unit_comment(key.unit),
                          key.range.bounded() ? ", each " + key.range.text(key.unit) :
                                                std::string())};
    }

    Listing listing(const Key &key, const bool *value)
    {
      return {*value ? "true" : "false", fmt::format("{} (true or false)", key.doc)};
    }

    Listing listing(const Key &key, Member::Text member)
    {
      // A quantity typed as text (IoVerbs::quantity_text) lists its unit and range.
      return {yaml_quote(*member.value),
              key.range.bounded() ?
                fmt::format("{} [{}]", key.doc, unit_range_comment(key.unit, key.range)) :
                std::string(key.doc)};
    }

    /// The YAML text as written (flow style), `null` when empty; no comment when `doc` is empty
    /// (the values of a map, which its own comment describes).
    Listing listing(const Key &key, Member::Yaml member)
    {
      return {member.text->empty() ? std::string("null") : *member.text, std::string(key.doc)};
    }

    Listing listing(const Key &key, Member::Integer member)
    {
      return {std::to_string(*member.value),
              fmt::format("{} ({})", key.doc, integer_range_text(member.min, member.max))};
    }

    Listing listing(const Key &key, Member::Choice member)
    {
      return {yaml_quote(member.options->at(*member.index)),
              fmt::format("{} (one of: {})", key.doc, join(*member.options, ", "))};
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
    if (!comment.empty())
      *out_ << "  # " << comment;
    *out_ << '\n';
  }

  void DefaultsPrinter::value(const Key &key, Member::Ref member)
  {
    const Listing l = std::visit([&](auto m) { return listing(key, m); }, member);
    line(key.key, l.value, l.comment);
  }

  std::optional<DefaultsPrinter> DefaultsPrinter::open_section(std::string_view key,
                                                               std::string_view doc)
  {
    line(key, "", doc);
    return child(lead_ + "  ", "");
  }
} // namespace kimp::io
