#include "io/text_cursor.h"

#include "io/reader_support.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>

namespace meander::io {

namespace {

// The digits that start the eight bytes at q, when fewer than eight: their count, and
// their value in `value`, without a branch per digit (indices are most of an OBJ or OFF
// file). -1 when all eight are digits.
int leading_digits(const char* q, int64_t& value) {
  if constexpr (std::endian::native != std::endian::little) return -1;
  uint64_t bytes;
  std::memcpy(&bytes, q, 8);
  const uint64_t t = bytes ^ 0x3030303030303030u; // a digit becomes its value
  // A byte is no digit where it is 10 or more: adding 0x76 sets its top bit (the top bit
  // masked off first, so that no byte carries into the next).
  const uint64_t not_digit = (t | ((t & 0x7F7F7F7F7F7F7F7Fu) + 0x7676767676767676u)) & 0x8080808080808080u;
  if (not_digit == 0) return -1;
  const int n = std::countr_zero(not_digit) / 8; // little endian: the first byte is lowest
  if (n == 0) return 0;
  // The n digits as the last bytes of eight with zeros before them, then combined in
  // pairs, fours and eights by one multiplication each.
  uint64_t v = t << (8 * (8 - n));
  v = (v * 10 + (v >> 8)) & 0x00FF00FF00FF00FFu;
  v = (v * 100 + (v >> 16)) & 0x0000FFFF0000FFFFu;
  v = (v * 10000 + (v >> 32)) & 0xFFFFFFFFu;
  value = int64_t(v);
  return n;
}

} // namespace

TextCursor::TextCursor(std::string_view text, std::string_view name, int64_t first_line)
    : begin_(text.data()), p_(text.data()), end_(text.data() + text.size()), line_(first_line), name_(name) {
  if (text.starts_with("\xEF\xBB\xBF")) p_ += 3;
}

void TextCursor::skip_space() {
  while (p_ != end_) {
    if (is_line_end(p_)) {
      ++p_;
      ++line_;
    } else if (is_blank(*p_)) {
      ++p_;
    } else if (*p_ == '#') {
      p_ = find_line_end(p_);
    } else {
      return;
    }
  }
}

const char* find_line_end(const char* q, const char* last, const char* end, bool carriage_returns) {
  const void* newline = std::memchr(q, '\n', size_t(last - q));
  const char* line_end = newline ? static_cast<const char*>(newline) : last;
  // A lone CR before the LF ends the line first; the CR of a CRLF is that LF's.
  for (const void* cr; carriage_returns && (cr = std::memchr(q, '\r', size_t(line_end - q))) != nullptr;
       q = static_cast<const char*>(cr) + 1)
    if (is_line_end(static_cast<const char*>(cr), end)) return static_cast<const char*>(cr);
  return line_end;
}

void TextCursor::next_line() {
  // Most calls come right after a line's last number.
  if (p_ != end_ && *p_ == '\n') {
    ++p_;
    ++line_;
    return;
  }
  const char* line_end = find_line_end(p_);
  if (line_end == end_) {
    p_ = end_;
    return;
  }
  p_ = line_end + 1;
  ++line_;
}

std::string_view TextCursor::word() {
  skip_blanks();
  const std::string_view found = word_here();
  p_ += found.size();
  return found;
}

bool TextCursor::accept(std::string_view keyword) {
  skip_space();
  const std::string_view found = word_here();
  const bool same = found.size() == keyword.size() &&
                    std::equal(found.begin(), found.end(), keyword.begin(),
                               [](unsigned char a, unsigned char b) { return std::tolower(a) == std::tolower(b); });
  if (same) p_ += found.size();
  return same;
}

void TextCursor::expect(std::string_view keyword) {
  if (accept(keyword)) return;
  const std::string expected = "expected '" + std::string(keyword) + "'";
  fail(at_end() ? expected + " but the file ends" : expected + ", found " + quoted(word_here()));
}

std::string_view TextCursor::word_here() const {
  const char* q = p_;
  while (q != end_ && !is_blank(*q) && *q != '\n') ++q;
  return {p_, size_t(q - p_)};
}

void TextCursor::fail_missing(std::string_view what) const { fail("missing " + std::string(what)); }

void TextCursor::fail_bad(std::string_view what) const { fail("bad " + std::string(what) + " " + quoted(word_here())); }

float TextCursor::real(std::string_view what) {
  const char* first = number_start(what);
  float value;
  const auto [last, ec] = std::from_chars(first, end_, value);
  if (ec == std::errc() && at_word_end(last) && std::isfinite(value)) {
    p_ = last;
    return value;
  }
  if (ec == std::errc::invalid_argument || !at_word_end(last)) fail_bad(what);
  if (ec == std::errc::result_out_of_range) {
    // from_chars reports underflow and overflow alike; underflow is a valid zero.
    double wide = 0;
    if (std::from_chars(first, end_, wide).ec == std::errc() && std::fabs(wide) < 1) {
      p_ = last;
      return float(wide);
    }
  }
  fail("non-finite " + std::string(what) + " " + quoted(word_here()));
}

int64_t TextCursor::integer(std::string_view what, char separator) {
  // By hand rather than with from_chars, about twice as fast. Up to 18 digits cannot
  // overflow; longer numbers are refused (no mesh has that many vertices).
  const char* q = number_start(what);
  const bool negative = *q == '-';
  q += negative;
  const char* digits = q;
  int64_t value = 0;
  if (const int n = end_ - q >= 8 ? leading_digits(q, value) : -1; n >= 0)
    q += n;
  else
    for (; q != end_ && unsigned(*q - '0') < 10 && q - digits < 18; ++q) value = value * 10 + (*q - '0');
  if (q == digits || (q != end_ && unsigned(*q - '0') < 10)) fail_bad(what);
  if (q != end_ && *q == separator)
    while (!at_word_end(q)) ++q;
  if (!at_word_end(q)) fail_bad(what);
  p_ = q;
  return negative ? -value : value;
}

void TextCursor::skip_number(std::string_view what) {
  const char* first = number_start(what);
  double value;
  const auto [last, ec] = std::from_chars(first, end_, value);
  if (ec == std::errc::invalid_argument || !at_word_end(last)) fail_bad(what);
  p_ = last;
}

void TextCursor::fail(std::string_view message) const {
  const bool after_last_line = p_ == end_ && p_ != begin_ && (p_[-1] == '\n' || p_[-1] == '\r');
  fail_at_line(name_, line_ - after_last_line, message);
}

} // namespace meander::io
