// PEER AT2 reader (see at2_reader.h): the NPTS/DT line, the unit the header states (g =
// 9.80665 m/s², cm/s², m/s², in/s², ...) → m/s², the values; and read_ground_motion(), which
// tells AT2 from two-column text (two_column_reader.cc). The text layer both share is
// record_text.h. Format variants: docs/physics.md "Ground-motion records".
#include "io/at2_reader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <vector>

#include "base/format.h"
#include "io/record_text.h"
#include "io/units.h"

namespace kimp::io
{
  using namespace detail;

  namespace
  {
    std::string token_at(std::string_view s, std::size_t pos)
    {
      std::size_t end = pos;
      while (end < s.size() && !is_blank(s[end]))
        ++end;
      return std::string(s.substr(pos, end - pos));
    }

    bool can_start_number(char c)
    {
      return is_digit(c) || c == '.' || c == '+' || c == '-';
    }

    /// Position of `word` as a whole word, case-insensitive, or npos.
    std::size_t find_word(std::string_view s, std::string_view word)
    {
      for (std::size_t p = 0; p + word.size() <= s.size(); ++p)
      {
        bool match = true;
        for (std::size_t k = 0; k < word.size() && match; ++k)
          match = std::toupper(static_cast<unsigned char>(s[p + k])) == word[k];
        if (match && (p == 0 || !is_word_char(s[p - 1])) &&
            (p + word.size() == s.size() || !is_word_char(s[p + word.size()])))
          return p;
      }
      return std::string_view::npos;
    }

    bool is_npts_dt_line(std::string_view s)
    {
      return find_word(s, "NPTS") != std::string_view::npos &&
             find_word(s, "DT") != std::string_view::npos;
    }

    /// The value token after a keyword: blanks, an optional '=' or ':', blanks, then up to the
    /// next blank or comma.
    std::string value_after(std::string_view s, std::size_t keyword_end)
    {
      std::size_t p = keyword_end;
      while (p < s.size() && is_blank(s[p]))
        ++p;
      if (p < s.size() && (s[p] == '=' || s[p] == ':'))
        ++p;
      while (p < s.size() && is_blank(s[p]))
        ++p;
      std::size_t end = p;
      while (end < s.size() && !is_blank(s[end]) && s[end] != ',')
        ++end;
      return std::string(s.substr(p, end - p));
    }

    struct Header
    {
      std::size_t npts = 0;
      double      dt   = 0.0;
    };

    Header parse_npts_dt(const Line &line, const std::string &source)
    {
      const std::string_view s      = line.text;
      const std::size_t      p_npts = find_word(s, "NPTS");
      const std::size_t      p_dt   = find_word(s, "DT");
      std::string            npts_text, dt_text;

      std::size_t first = 0;
      while (first < s.size() && is_blank(s[first]))
        ++first;
      if (first < s.size() && can_start_number(s[first]))
      {
        // Numbers-first form "4000 0.0100 NPTS, DT": values in the order of the keywords.
        std::istringstream values{std::string(s.substr(0, std::min(p_npts, p_dt)))};
        std::string        a, b;
        values >> a >> b;
        for (std::string *t : {&a, &b})
          if (!t->empty() && t->back() == ',')
            t->pop_back();
        npts_text = p_npts < p_dt ? a : b;
        dt_text   = p_npts < p_dt ? b : a;
      }
      else
      {
        npts_text = value_after(s, p_npts + 4);
        dt_text   = value_after(s, p_dt + 2);
      }

      Header      header;
      const auto  context = "NPTS/DT line '" + base::excerpt(s) + "'";
      std::size_t npts    = 0;
      const auto  npts_result =
        std::from_chars(npts_text.data(), npts_text.data() + npts_text.size(), npts);
      if (npts_text.empty() || npts_result.ec != std::errc() ||
          npts_result.ptr != npts_text.data() + npts_text.size() || npts == 0)
        fail(source,
             line.number,
             "NPTS = \"" + base::excerpt(npts_text) + "\" in " + context +
               " (expected a positive integer)");
      header.npts = npts;

      // DT may touch its unit ("DT=.01SEC"): accept a numeric prefix followed by SEC/S only.
      double            dt  = 0.0;
      const std::size_t end = dt_text.empty() ? std::string::npos : scan_real(dt_text, 0, dt);
      std::string       unit;
      if (end != std::string::npos)
        for (std::size_t k = end; k < dt_text.size(); ++k)
          unit += static_cast<char>(std::toupper(static_cast<unsigned char>(dt_text[k])));
      // A subnormal DT (1e-320 s) passes "> 0" but would make an endless run.
      if (end == std::string::npos || !(unit.empty() || unit == "SEC" || unit == "S") ||
          !(dt > 0.0) || !std::isnormal(dt))
        fail(source,
             line.number,
             "DT = \"" + base::excerpt(dt_text) + "\" in " + context +
               " (expected a positive time step in seconds)");
      if (dt < min_record_dt || dt > max_record_dt)
        fail(source,
             line.number,
             "DT = " + format_number(dt) + " s in " + context +
               " (expected a sampling interval in [" + format_number(min_record_dt) + " s, " +
               format_number(max_record_dt) +
               " s]: outside it implausible for a ground-motion record)");
      header.dt = dt;
      return header;
    }

    struct UnitName
    {
      const char *name;  // as normalised by normalise_unit()
      double      value; // m/s² per unit
    };

    /// Acceleration units a PEER header may state, after normalise_unit().
    const UnitName at2_units[] = {{"G", standard_gravity},
                                  {"CM/S/S", 0.01},
                                  {"CM/S2", 0.01},
                                  {"GAL", 0.01},
                                  {"MM/S/S", 0.001},
                                  {"MM/S2", 0.001},
                                  {"M/S/S", 1.0},
                                  {"M/S2", 1.0},
                                  {"IN/S/S", 0.0254},
                                  {"IN/S2", 0.0254},
                                  {"FT/S/S", 0.3048},
                                  {"FT/S2", 0.3048}};

    const char *const at2_unit_expectation =
      "expected G, CM/S/S (CM/SEC/SEC, CM/S^2, GAL), MM/S/S, M/S/S, IN/S/S or FT/S/S";

    /// Upper case, "SEC" -> "S", "^" and "**" removed: "cm/sec^2" -> "CM/S2".
    std::string normalise_unit(std::string_view text)
    {
      std::string u;
      for (const char c : text)
        if (c != '^' && c != '*')
          u += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      for (std::size_t p = u.find("SEC"); p != std::string::npos; p = u.find("SEC", p))
        u.replace(p, 3, "S");
      return u;
    }

    /**
     * The SI value of one unit of the series, from the header lines before the NPTS/DT line: the
     * PEER line "<QUANTITY> TIME SERIES IN UNITS OF <UNIT>". A velocity or displacement series,
     * a missing "UNITS OF" statement and a unit that is not an acceleration unit are refused, so
     * that a file is never read in a unit it does not state.
     */
    double
    header_unit(const std::vector<Line> &lines, std::size_t n_header, const std::string &source)
    {
      for (std::size_t i = 0; i < n_header; ++i)
      {
        const std::string_view s           = lines[i].text;
        const bool             series_line = find_word(s, "UNITS") != std::string_view::npos ||
                                 find_word(s, "SERIES") != std::string_view::npos ||
                                 find_word(s, "HISTORY") != std::string_view::npos;
        if (!series_line)
          continue;
        for (const char *kind : {"VELOCITY", "DISPLACEMENT"})
          if (find_word(s, kind) != std::string_view::npos)
            fail(source,
                 lines[i].number,
                 std::string("a ") + (kind[0] == 'V' ? "velocity" : "displacement") +
                   " series: header line '" + base::excerpt(s) +
                   "' (expected an ACCELERATION time series; kimp reads accelerations only)");
      }
      for (std::size_t i = 0; i < n_header; ++i)
      {
        const std::string_view s     = lines[i].text;
        const std::size_t      units = find_word(s, "UNITS");
        if (units == std::string_view::npos)
          continue;
        std::size_t p = units + 5;
        while (p < s.size() && is_blank(s[p]))
          ++p;
        const std::size_t of = find_word(s.substr(p), "OF");
        if (of == 0)
          p += 2;
        while (p < s.size() && (is_blank(s[p]) || s[p] == ':' || s[p] == '='))
          ++p;
        std::size_t end = p;
        while (end < s.size() && !is_blank(s[end]) && s[end] != ',' && s[end] != ';')
          ++end;
        std::string_view token = s.substr(p, end - p);
        while (!token.empty() && (token.back() == '.' || token.back() == ')'))
          token.remove_suffix(1);
        const std::string unit = normalise_unit(token);
        for (const UnitName &known : at2_units)
          if (unit == known.name)
            return known.value;
        fail(source,
             lines[i].number,
             "unknown unit \"" + base::excerpt(token) + "\" in header line '" + base::excerpt(s) +
               "' (" + at2_unit_expectation + "; kimp never assumes a unit)");
      }
      fail(source,
           lines[n_header].number,
           "no 'UNITS OF ...' statement in the " +
             (n_header == 0 ? std::string("header (no line before the NPTS/DT line)") :
                              "header lines 1-" + std::to_string(n_header)) +
             " (expected a line such as 'ACCELERATION TIME SERIES IN UNITS OF G'; kimp never "
             "assumes a unit)");
    }
  } // namespace

  GroundMotionFileError::GroundMotionFileError(const std::string &file,
                                               std::size_t        line,
                                               const std::string &message)
    : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " +
                         message)
    , file_(file)
    , line_(line)
  {
  }

  AccelerationRecord parse_at2(std::string_view content, const std::string &source)
  {
    check_text(content, source);
    const SplitText split = split_lines(content);

    std::size_t header_index = split.lines.size();
    for (std::size_t i = 0; i < std::min(split.lines.size(), at2_max_header_lines); ++i)
      if (is_npts_dt_line(split.lines[i].text))
      {
        header_index = i;
        break;
      }
    if (header_index == split.lines.size())
    {
      if (split.lines.size() < 4)
        fail(source,
             split.lines.size(),
             "truncated: the file ends after " + std::to_string(split.lines.size()) +
               " line(s), before any NPTS/DT line (" + at2_expectation + ")");
      fail(source,
           std::min(split.lines.size(), at2_max_header_lines),
           "no NPTS/DT line in lines 1-" +
             std::to_string(std::min(split.lines.size(), at2_max_header_lines)) + " (" +
             at2_expectation + ")");
    }
    const Header header = parse_npts_dt(split.lines[header_index], source);
    const double unit   = header_unit(split.lines, header_index, source);

    AccelerationRecord motion;
    motion.dt   = header.dt;
    motion.name = stem_of(source);
    motion.acceleration.reserve(std::min(header.npts, content.size() / 2));
    for (std::size_t i = header_index + 1; i < split.lines.size(); ++i)
    {
      const Line &line = split.lines[i];
      std::size_t p    = 0;
      while (true)
      {
        while (p < line.text.size() && is_blank(line.text[p]))
          ++p;
        if (p >= line.text.size())
          break;
        double            value = 0.0;
        const std::size_t end   = scan_real(line.text, p, value);
        if (end == std::string_view::npos || (end < line.text.size() && !is_blank(line.text[end]) &&
                                              !can_start_number(line.text[end])))
          fail(source,
               line.number,
               "non-numeric token \"" + base::excerpt(token_at(line.text, p)) + "\" at column " +
                 std::to_string(p + 1) +
                 " (expected numbers in Fortran E format such as -.1234567E-02)");
        if (motion.acceleration.size() == header.npts)
          fail(source,
               line.number,
               "more values than NPTS = " + std::to_string(header.npts) + ": value " +
                 std::to_string(header.npts + 1) +
                 " is on this line (expected exactly NPTS "
                 "values after the NPTS/DT line)");
        if (!std::isfinite(value * unit))
          fail(source,
               line.number,
               "value " + token_at(line.text, p) + " at column " + std::to_string(p + 1) +
                 " overflows when converted to m/s^2 (expected a finite acceleration)");
        motion.acceleration.push_back(value * unit);
        p = end;
      }
    }
    if (motion.acceleration.size() < header.npts)
      fail(source,
           split.lines.size(),
           "fewer values than NPTS: the file ends after " +
             std::to_string(motion.acceleration.size()) +
             " of NPTS = " + std::to_string(header.npts) + " values (expected " +
             std::to_string(header.npts - motion.acceleration.size()) + " more; truncated?" +
             (split.ends_with_newline ? "" : " the last line has no newline") + ")");
    return motion;
  }

  AccelerationRecord read_at2(const std::filesystem::path &file)
  {
    return parse_at2(read_file(file), file.string());
  }

  AccelerationRecord read_ground_motion(const std::filesystem::path &file,
                                        std::optional<double>        two_column_unit)
  {
    const std::string content = read_file(file);
    const std::string source  = file.string();
    check_text(content, source);
    const SplitText split = split_lines(content);
    for (std::size_t i = 0; i < std::min(split.lines.size(), at2_max_header_lines); ++i)
      if (is_npts_dt_line(split.lines[i].text))
      {
        // An AT2 file is read in the unit its header states: a unit for two-column text that
        // says otherwise is a mistake, not something to ignore silently.
        if (two_column_unit)
        {
          const double stated = header_unit(split.lines, i, source);
          if (std::abs(stated - *two_column_unit) > 1e-9 * stated)
            fail(source,
                 split.lines[i].number,
                 fmt::format("a PEER AT2 file whose header states its unit (1 unit = {:.6g} "
                             "m/s^2), but the scene's record_unit gives 1 unit = {:.6g} m/s^2 "
                             "(expected no record_unit: it is for two-column text; an AT2 file "
                             "is read in the unit of its header)",
                             stated,
                             *two_column_unit));
        }
        return parse_at2(content, source);
      }

    for (const Line &line : split.lines)
    {
      std::string bad;
      bool        ok   = true;
      const auto  nums = split_numbers(strip_comment(line.text), bad, ok);
      if (ok && nums.empty())
        continue;
      if (!ok || nums.size() != 2)
        fail(source,
             line.number,
             "neither a PEER AT2 file (no NPTS/DT line in lines 1-" +
               std::to_string(at2_max_header_lines) +
               ") nor two-column text (this first data line does not hold exactly 2 "
               "numbers) (expected one of the two formats)");
      if (!two_column_unit)
        fail(source,
             line.number,
             "two-column time/acceleration text does not state its unit (expected the unit "
             "of the acceleration column from the scene, ground_motion.record_unit such as "
             "\"g\", \"m/s^2\" or \"cm/s^2\")");
      return parse_two_column(content, source, *two_column_unit);
    }
    fail(source, split.lines.size(), "no data lines (expected AT2 or two-column text)");
  }
} // namespace kimp::io
