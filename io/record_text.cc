// The text layer of the ground-motion readers (declared in io/record_text.h): lines, control
// bytes, Fortran reals and the numeric tokens of a line.
#include "io/record_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace kimp::io::detail
{
  std::string format_number(double value)
  {
    std::ostringstream out;
    out.precision(10);
    out << value;
    return out.str();
  }

  SplitText split_lines(std::string_view content)
  {
    SplitText   split;
    std::size_t begin = 0;
    while (begin < content.size())
    {
      std::size_t end         = content.find_first_of("\r\n", begin);
      const bool  has_newline = end != std::string_view::npos;
      if (!has_newline)
        end = content.size();
      split.lines.push_back({content.substr(begin, end - begin), split.lines.size() + 1});
      split.ends_with_newline = has_newline;
      begin                   = end + 1;
      if (has_newline && content[end] == '\r' && begin < content.size() && content[begin] == '\n')
        ++begin;
    }
    return split;
  }

  void check_text(std::string_view content, const std::string &source)
  {
    if (std::all_of(content.begin(),
                    content.end(),
                    [](char c) { return is_blank(c) || c == '\n'; }))
      fail(source, 1, std::string("empty file (") + at2_expectation + ")");
    std::size_t line = 1, column = 1;
    for (std::size_t k = 0; k < content.size(); ++k)
    {
      const char c    = content[k];
      const auto byte = static_cast<unsigned char>(c);
      if (c == '\r' && k + 1 < content.size() && content[k + 1] == '\n')
        continue;
      if (c == '\n' || c == '\r')
      {
        ++line;
        column = 1;
        continue;
      }
      if ((byte < 0x20 && !is_blank(c)) || byte == 0x7f)
      {
        char hex[8];
        std::snprintf(hex, sizeof hex, "0x%02x", byte);
        fail(source,
             line,
             "binary data: control byte " + std::string(hex) + " at column " +
               std::to_string(column) + " (expected a text file)");
      }
      ++column;
    }
  }

  std::size_t scan_real(std::string_view s, std::size_t pos, double &value)
  {
    std::size_t p = pos;
    if (p < s.size() && (s[p] == '+' || s[p] == '-'))
      ++p;
    std::size_t n_digits = 0;
    bool        has_dot  = false;
    while (p < s.size() && (is_digit(s[p]) || (s[p] == '.' && !has_dot)))
    {
      if (s[p] == '.')
        has_dot = true;
      else
        ++n_digits;
      ++p;
    }
    if (n_digits == 0)
      return std::string_view::npos;
    const std::size_t mantissa_end = p;
    std::string       exponent;
    if (p < s.size() && (s[p] == 'E' || s[p] == 'e' || s[p] == 'D' || s[p] == 'd'))
    {
      std::size_t q = p + 1;
      if (q < s.size() && (s[q] == '+' || s[q] == '-'))
        ++q;
      const std::size_t digits_begin = q;
      while (q < s.size() && is_digit(s[q]))
        ++q;
      if (q == digits_begin)
        return std::string_view::npos;
      exponent = std::string(s.substr(p + 1, q - p - 1));
      p        = q;
    }
    else if (has_dot && p + 4 <= s.size() && (s[p] == '+' || s[p] == '-') && is_digit(s[p + 1]) &&
             is_digit(s[p + 2]) && is_digit(s[p + 3]) &&
             (p + 4 == s.size() || !(is_digit(s[p + 4]) || s[p + 4] == '.')))
    {
      exponent = std::string(s.substr(p, 4));
      p += 4;
    }

    std::string text(s.substr(pos, mantissa_end - pos));
    if (!exponent.empty())
      text += "e" + exponent;
    const char *first = text.data();
    if (*first == '+')
      ++first;
    const auto result = std::from_chars(first, text.data() + text.size(), value);
    if (result.ec != std::errc() || result.ptr != text.data() + text.size() ||
        !std::isfinite(value))
      return std::string_view::npos;
    return p;
  }

  std::string read_file(const std::filesystem::path &file)
  {
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
      fail(file.string(), 0, "is a directory (expected a ground-motion file)");
    std::ifstream in(file, std::ios::binary);
    if (!in)
      fail(file.string(), 0, "cannot open (expected a readable ground-motion file)");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad())
      fail(file.string(), 0, "read error");
    return buffer.str();
  }

  std::vector<double> split_numbers(std::string_view s, std::string &bad, bool &ok)
  {
    std::vector<double> values;
    ok            = true;
    std::size_t p = 0;
    while (true)
    {
      while (p < s.size() && (is_blank(s[p]) || s[p] == ',' || s[p] == ';'))
        ++p;
      if (p >= s.size())
        break;
      std::size_t end = p;
      while (end < s.size() && !is_blank(s[end]) && s[end] != ',' && s[end] != ';')
        ++end;
      const std::string_view token = s.substr(p, end - p);
      double                 value = 0.0;
      if (scan_real(token, 0, value) != token.size())
      {
        bad = std::string(token);
        ok  = false;
        return values;
      }
      values.push_back(value);
      p = end;
    }
    return values;
  }

  std::string_view strip_comment(std::string_view s)
  {
    const std::size_t hash = s.find('#');
    return hash == std::string_view::npos ? s : s.substr(0, hash);
  }

  std::string stem_of(const std::string &source)
  {
    return std::filesystem::path(source).stem().string();
  }
} // namespace kimp::io::detail
