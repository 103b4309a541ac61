#pragma once
//! \file parse.h
//! \brief Internal helpers shared by the readers and writers of io/ (not installed, not API).
//!
//! - Scanner: a whitespace tokenizer over a whole file held in memory, tracking line numbers,
//!   with number parsing through std::from_chars (rejects NaN, Inf, garbage, overflow) and
//!   checked counts and indices. Every failure throws core::InputError "file:line: what" on one
//!   line (file text quoted in messages is sanitized and shortened).
//! - ByteReader: bounds-checked little/big-endian reads from a binary buffer.
//! - TextWriter: appends numbers to a string with std::to_chars (shortest round-trip form).

#include "core/errors.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

namespace polycube::io::detail {

//! A printable, one-line, shortened copy of file text for use in an error message.
std::string quote(std::string_view text, std::size_t max_len = 24);

//! Case-insensitive ASCII comparison.
bool iequals(std::string_view a, std::string_view b);

//! Parse a whole token as a finite double (a leading '+' is allowed).
//! \return false when the token is not entirely a number, or is NaN, Inf or out of range.
bool parse_double(std::string_view token, double& out);

//! Parse a whole token as a decimal integer (a leading '+' is allowed).
bool parse_int64(std::string_view token, long long& out);

//! Whitespace tokenizer over a file held in memory.
class Scanner {
 public:
  //! \param data the whole file; \param name the file name used in messages;
  //! \param comment a character starting a comment to the end of the line ('\0': none).
  Scanner(std::string_view data, std::string name, char comment = '\0');

  //! Next token (crossing lines), or an empty view at the end of the input.
  std::string_view next();
  //! Next token on the current line, or an empty view when the line (or input) ends.
  std::string_view next_on_line();
  //! Next token on the current line, which must exist. \throw InputError "line ends early".
  std::string_view line_token(const char* what);
  //! Next token, which must exist. \throw InputError "unexpected end of file (expected what)".
  std::string_view token(const char* what);
  //! True when only whitespace and comments are left.
  bool at_end();
  //! Skip the rest of the current line (including its newline).
  void skip_line();
  //! The rest of the current line, without its newline; the scanner moves to the next line.
  std::string_view rest_of_line();

  //! A finite real number. \throw InputError naming \p what on garbage, NaN or Inf.
  double real(const char* what);
  //! Like real(), but the token is already read.
  double real(std::string_view tok, const char* what) const;
  //! An integer. \throw InputError naming \p what.
  long long integer(const char* what);
  long long integer(std::string_view tok, const char* what) const;
  //! An element count in [0, INT_MAX] that the remaining input can hold, each item taking at
  //! least \p min_bytes bytes. Guards every reserve() against absurd declared counts.
  int count(const char* what, std::size_t min_bytes);
  //! Check an already read count the same way.
  int check_count(long long n, const char* what, std::size_t min_bytes) const;
  //! A vertex index, written with base \p base (0 or 1), checked in range; returned 0-based.
  int index(long long n_vertices, int base);
  int check_index(long long value, long long n_vertices, int base) const;

  //! Throw InputError "name:line: what" at the line of the last token read.
  [[noreturn]] void fail(const std::string& what) const;

  [[nodiscard]] long line() const { return tok_line_; }
  [[nodiscard]] const std::string& name() const { return name_; }
  [[nodiscard]] std::size_t offset() const { return pos_; }
  [[nodiscard]] std::size_t remaining() const { return data_.size() - pos_; }
  [[nodiscard]] std::string_view data() const { return data_; }
  //! Move to a position saved with offset() and current_line() (to peek at a token and put it
  //! back), or to the start of a binary body after a text header.
  void seek(std::size_t pos, long line) {
    pos_ = pos;
    line_ = line;
  }
  [[nodiscard]] long current_line() const { return line_; }

 private:
  // Skip spaces, tabs, CR and comments; stop at a newline when !cross_lines.
  void skip_space(bool cross_lines);

  std::string_view data_;
  std::string name_;
  char comment_;
  std::size_t pos_ = 0;
  long line_ = 1;      // line of pos_
  long tok_line_ = 1;  // line of the last token
};

//! Bounds-checked reads from a binary buffer.
class ByteReader {
 public:
  ByteReader(std::string_view data, std::string name, std::size_t pos = 0)
      : data_(data), name_(std::move(name)), pos_(pos) {}

  [[nodiscard]] std::size_t remaining() const { return data_.size() - pos_; }
  [[nodiscard]] std::size_t offset() const { return pos_; }
  //! Throw "name: truncated binary data (expected what at byte N)" unless n bytes are left.
  void need(std::size_t n, const char* what) const;
  void skip(std::size_t n, const char* what) {
    need(n, what);
    pos_ += n;
  }
  //! Read a plain value of type T (host is little-endian); \p swap reverses its bytes.
  template <class T>
  T get(const char* what, bool swap = false) {
    need(sizeof(T), what);
    unsigned char b[sizeof(T)];
    std::memcpy(b, data_.data() + pos_, sizeof(T));
    if (swap)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    pos_ += sizeof(T);
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }
  [[noreturn]] void fail(const std::string& what) const;

 private:
  std::string_view data_;
  std::string name_;
  std::size_t pos_;
};

//! Appends text to a string; numbers through std::to_chars (shortest exact form for doubles).
class TextWriter {
 public:
  explicit TextWriter(std::string& out) : out_(out) {}
  TextWriter& operator<<(std::string_view s) {
    out_.append(s);
    return *this;
  }
  TextWriter& operator<<(char c) {
    out_.push_back(c);
    return *this;
  }
  TextWriter& operator<<(double v);
  TextWriter& operator<<(float v);
  TextWriter& operator<<(long long v);
  TextWriter& operator<<(int v) { return *this << static_cast<long long>(v); }
  TextWriter& operator<<(std::size_t v) { return *this << static_cast<long long>(v); }

 private:
  std::string& out_;
};

//! Append the raw bytes of a plain value (little-endian host).
template <class T>
void put_bytes(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

}  // namespace polycube::io::detail
