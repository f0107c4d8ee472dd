/// SVG numbers and lengths: the scanner every other micro-parser builds on.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <system_error>

#include "import/svg/svg_detail.h"
#include "import/svg/svg_parse.h"

namespace rescuesim::svg {

namespace detail {

std::string quote(std::string_view s, std::size_t pos, std::size_t max_chars) {
  if (pos >= s.size()) return "the end";
  // appended piece by piece: GCC 12 warns falsely (-Wrestrict) on chained operator+
  std::string out(1, '\'');
  out.append(s.substr(pos, max_chars));
  if (s.size() - pos > max_chars) out.append("...");
  out.push_back('\'');
  return out;
}

namespace {

/// A token for messages, shortened when absurdly long.
std::string token_text(std::string_view token) {
  constexpr std::size_t kMax = 32;
  return token.size() <= kMax ? std::string(token) : std::string(token.substr(0, kMax)) + "...";
}

/// Reads the digits of an exponent, saturating so that a thousand digits cannot overflow.
long exponent_value(std::string_view digits) {
  long e = 0;
  for (char c : digits) e = std::min(e * 10 + (c - '0'), 1000000L);
  return e;
}

}  // namespace

double scan_number(std::string_view s, std::size_t& pos) {
  const std::size_t start = pos;
  std::size_t i = pos;
  const bool negative = i < s.size() && s[i] == '-';
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;

  // spelled-out infinities and NaNs get their own message: they are a common export bug
  if (i < s.size() && (to_lower(s[i]) == 'i' || to_lower(s[i]) == 'n')) {
    std::size_t j = i;
    while (j < s.size() && ((s[j] >= 'a' && s[j] <= 'z') || (s[j] >= 'A' && s[j] <= 'Z'))) ++j;
    std::string word;
    for (char c : s.substr(i, j - i)) word += to_lower(c);
    if (word.rfind("inf", 0) == 0 || word == "nan")
      throw ParseError("expected a finite number, found '" + token_text(s.substr(start, j - start)) + "'", start);
  }

  // mantissa: digits, optional fraction; note where the first significant digit sits so an
  // out-of-range result can be told apart as overflow or underflow
  const std::size_t int_begin = i;
  while (i < s.size() && is_digit(s[i])) ++i;
  const std::size_t int_end = i;
  std::size_t frac_begin = i, frac_end = i;
  if (i < s.size() && s[i] == '.') {
    frac_begin = ++i;
    while (i < s.size() && is_digit(s[i])) ++i;
    frac_end = i;
  }
  if (int_end == int_begin && frac_end == frac_begin)
    throw ParseError("expected a number, found " + quote(s, start), start);

  // exponent only when digits follow, so "1em" is 1 with unit em
  long exponent = 0;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    std::size_t j = i + 1;
    const bool exp_negative = j < s.size() && s[j] == '-';
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) ++j;
    if (j < s.size() && is_digit(s[j])) {
      const std::size_t digits_begin = j;
      while (j < s.size() && is_digit(s[j])) ++j;
      exponent = exponent_value(s.substr(digits_begin, j - digits_begin));
      if (exp_negative) exponent = -exponent;
      i = j;
    }
  }

  // convert with from_chars (locale-independent); it does not accept a leading '+'
  const std::string_view token = s.substr(start, i - start);
  std::string_view text = token;
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value, std::chars_format::general);
  if (result.ec == std::errc::result_out_of_range) {
    // decimal exponent of the leading significant digit: negative means underflow → zero
    long lead = 0;
    std::size_t k = int_begin;
    while (k < int_end && s[k] == '0') ++k;
    if (k < int_end) {
      lead = long(int_end - k) - 1;
    } else {
      std::size_t z = frac_begin;
      while (z < frac_end && s[z] == '0') ++z;
      lead = -long(z - frac_begin) - 1;
    }
    if (lead + exponent < 0) {
      pos = i;
      return negative ? -0.0 : 0.0;
    }
    throw ParseError("number " + token_text(token) + " is out of range", start);
  }
  if (result.ec != std::errc() || result.ptr != text.data() + text.size())
    throw ParseError("expected a number, found '" + token_text(token) + "'", start);
  if (!std::isfinite(value) || std::abs(value) > kMaxMagnitude)
    throw ParseError("number " + token_text(token) + " is out of range (largest magnitude 1e9)", start);
  pos = i;
  return value;
}

}  // namespace detail

double read_number(std::string_view s, std::size_t& pos) {
  // one separating comma, with whitespace on either side
  detail::skip_space(s, pos);
  if (pos < s.size() && s[pos] == ',') {
    ++pos;
    detail::skip_space(s, pos);
  }
  return detail::scan_number(s, pos);
}

bool at_end(std::string_view s, std::size_t pos) {
  for (; pos < s.size(); ++pos)
    if (!detail::is_space(s[pos]) && s[pos] != ',') return false;
  return true;
}

bool Length::physical() const {
  switch (unit) {
    case Unit::mm:
    case Unit::cm:
    case Unit::m:
    case Unit::in:
    case Unit::pt:
    case Unit::pc:
      return true;
    default:
      return false;
  }
}

double Length::metres() const {
  switch (unit) {
    case Unit::mm: return value * 0.001;
    case Unit::cm: return value * 0.01;
    case Unit::m: return value;
    case Unit::in: return value * 0.0254;
    case Unit::pt: return value * 0.0254 / 72.0;
    case Unit::pc: return value * 0.0254 / 6.0;
    default: throw std::logic_error("svg::Length::metres() called on a length without a physical unit");
  }
}

double Length::user_units() const {
  // 96 px per inch; 16 px per em and, as browsers do without font metrics, half that per ex
  switch (unit) {
    case Unit::none:
    case Unit::px: return value;
    case Unit::mm: return value * 96.0 / 25.4;
    case Unit::cm: return value * 96.0 / 2.54;
    case Unit::m: return value * 96.0 / 0.0254;
    case Unit::in: return value * 96.0;
    case Unit::pt: return value * 96.0 / 72.0;
    case Unit::pc: return value * 16.0;
    case Unit::em: return value * 16.0;
    case Unit::ex: return value * 8.0;
    case Unit::percent: return 0.0;
  }
  return value;
}

Length parse_length(std::string_view s) {
  // trim, then number immediately followed by an optional unit
  std::size_t pos = 0;
  detail::skip_space(s, pos);
  std::size_t end = s.size();
  while (end > pos && detail::is_space(s[end - 1])) --end;
  const std::string_view body = s.substr(0, end);
  if (pos == end) throw ParseError("expected a length, found the end", pos);
  Length length;
  length.value = detail::scan_number(body, pos);

  std::string unit;
  for (char c : body.substr(pos)) unit += detail::to_lower(c);
  struct Suffix {
    const char* text;
    Unit unit;
  };
  static const Suffix kSuffixes[] = {{"", Unit::none}, {"px", Unit::px}, {"mm", Unit::mm}, {"cm", Unit::cm},
                                     {"m", Unit::m},   {"in", Unit::in}, {"pt", Unit::pt}, {"pc", Unit::pc},
                                     {"%", Unit::percent}, {"em", Unit::em}, {"ex", Unit::ex}};
  for (const Suffix& suffix : kSuffixes) {
    if (unit == suffix.text) {
      length.unit = suffix.unit;
      return length;
    }
  }
  throw ParseError("expected a length unit (px, mm, cm, m, in, pt, pc, %, em, ex) after the number, found " +
                       detail::quote(body, pos),
                   pos);
}

}  // namespace rescuesim::svg
