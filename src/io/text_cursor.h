// A cursor over the text of an OBJ, OFF, ascii PLY or ascii STL file: words and numbers
// separated by blanks, line ends and # comments, keeping the 1-based line for messages.
// Numbers are read in place with std::from_chars: no copies, no allocation.
#pragma once

#include "meander/mesh.h"

#include <cstdint>
#include <string_view>

namespace meander::io {

// A line ends at LF, CRLF or a lone CR (classic Mac OS text); a CR followed by a LF is
// a blank before the LF. `end` is the end of the text.
inline bool is_line_end(const char* q, const char* end) {
  return *q == '\n' || (*q == '\r' && (q + 1 == end || q[1] != '\n'));
}

// The first line end in [q, last), or last; `end` is the end of the text. Without
// `carriage_returns` the range holds no CR, and only line feeds are looked for.
const char* find_line_end(const char* q, const char* last, const char* end, bool carriage_returns = true);

class TextCursor {
public:
  // `name` stands for the file in messages and `text` starts on line `first_line`.
  // A UTF-8 byte order mark is skipped.
  TextCursor(std::string_view text, std::string_view name, int64_t first_line = 1);

  int64_t line() const { return line_; }
  bool at_end() const { return p_ == end_; }
  size_t bytes_left() const { return size_t(end_ - p_); }

  // Skips spaces, tabs and the carriage returns of CRLF, staying on the line.
  void skip_blanks() {
    while (p_ != end_ && is_blank(*p_) && !is_line_end(p_)) ++p_;
  }
  // Skips blanks, line ends and comments: to the next word or the end of the text.
  void skip_space();
  // Whether the line holds no more words (skips blanks first).
  bool at_line_end() {
    skip_blanks();
    return p_ == end_ || is_line_end(p_) || *p_ == '#';
  }
  // Moves past the end of the current line.
  void next_line();

  // The next word on this line, up to a blank or line end; empty at the line end.
  std::string_view word();
  // Skips space; if the next word is `keyword` (ASCII case-insensitive), moves past it
  // and returns true, else stays before it.
  bool accept(std::string_view keyword);
  // The same, failing with "expected 'keyword', found 'word'" when it is not there.
  void expect(std::string_view keyword);

  // The next word on this line read as a number. Failures name `what`: "missing vertex
  // coordinate", "bad vertex coordinate 'abc'", "non-finite vertex coordinate 'nan'".
  float real(std::string_view what);
  int64_t integer(std::string_view what) { return integer(what, ' '); }
  // An integer that may be followed, in the same word, by `separator` and text that is
  // not read (the "/vt/vn" after an OBJ vertex index).
  int64_t integer(std::string_view what, char separator);
  // A number of any kind (non-finite allowed), whose value is not needed.
  void skip_number(std::string_view what);

  // Throws InputError("name:line: message"). At the end of a file that ends with a line
  // end, the line is the last one, not the empty one after it.
  [[noreturn]] void fail(std::string_view message) const;

  static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

private:
  bool is_line_end(const char* q) const { return io::is_line_end(q, end_); }
  // The first line end at or after q, or the end of the text.
  const char* find_line_end(const char* q) const { return io::find_line_end(q, end_, end_); }
  bool at_word_end(const char* q) const { return q == end_ || is_blank(*q) || *q == '\n' || *q == '#'; }
  // The word starting at the cursor, for messages.
  std::string_view word_here() const;
  // Where the number at the cursor starts: past a '+', which from_chars does not take.
  const char* number_start(std::string_view what) {
    if (at_line_end()) fail_missing(what);
    const bool plus = *p_ == '+' && p_ + 1 != end_ && (unsigned(p_[1] - '0') < 10 || p_[1] == '.');
    return p_ + plus;
  }
  [[noreturn]] void fail_missing(std::string_view what) const;
  [[noreturn]] void fail_bad(std::string_view what) const;

  const char* begin_;
  const char* p_;
  const char* end_;
  int64_t line_ = 1;
  std::string_view name_;
};

// The three coordinates of a vertex, on the cursor's line.
inline Vec3 read_point(TextCursor& in) {
  const float x = in.real("vertex coordinate");
  const float y = in.real("vertex coordinate");
  const float z = in.real("vertex coordinate");
  return {x, y, z};
}

} // namespace meander::io
