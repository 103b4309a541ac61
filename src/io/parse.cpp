#include "io/parse.h"

#include <charconv>
#include <climits>
#include <cmath>

namespace polycube::io::detail {

namespace {
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
}  // namespace

std::string quote(std::string_view text, std::size_t max_len) {
  std::string s = "'";
  const std::size_t n = std::min(text.size(), max_len);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    s.push_back(c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?');
  }
  if (text.size() > max_len) s += "...";
  s.push_back('\'');
  return s;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

bool parse_double(std::string_view tok, double& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  if (tok.empty()) return false;
  const char* end = tok.data() + tok.size();
  const auto [ptr, ec] = std::from_chars(tok.data(), end, out);
  return ec == std::errc() && ptr == end && std::isfinite(out);
}

bool parse_int64(std::string_view tok, long long& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  if (tok.empty()) return false;
  const char* end = tok.data() + tok.size();
  const auto [ptr, ec] = std::from_chars(tok.data(), end, out);
  return ec == std::errc() && ptr == end;
}

// --- Scanner ----------------------------------------------------------------------------------

Scanner::Scanner(std::string_view data, std::string name, char comment)
    : data_(data), name_(std::move(name)), comment_(comment) {}

void Scanner::skip_space(bool cross_lines) {
  while (pos_ < data_.size()) {
    const char c = data_[pos_];
    if (is_space(c)) {
      ++pos_;
    } else if (c == '\n') {
      if (!cross_lines) return;
      ++pos_;
      ++line_;
    } else if (comment_ != '\0' && c == comment_) {
      while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
    } else {
      return;
    }
  }
}

std::string_view Scanner::next() {
  skip_space(true);
  tok_line_ = line_;
  const std::size_t start = pos_;
  while (pos_ < data_.size() && !is_space(data_[pos_]) && data_[pos_] != '\n' &&
         (comment_ == '\0' || data_[pos_] != comment_))
    ++pos_;
  return data_.substr(start, pos_ - start);
}

std::string_view Scanner::next_on_line() {
  skip_space(false);
  if (pos_ >= data_.size() || data_[pos_] == '\n') return {};
  return next();
}

std::string_view Scanner::token(const char* what) {
  std::string_view t = next();
  if (t.empty()) fail(std::string("unexpected end of file (expected ") + what + ")");
  return t;
}

std::string_view Scanner::line_token(const char* what) {
  std::string_view t = next_on_line();
  if (t.empty()) {
    tok_line_ = line_;
    fail(std::string("line ends early (expected ") + what + ")");
  }
  return t;
}

bool Scanner::at_end() {
  skip_space(true);
  tok_line_ = line_;
  return pos_ >= data_.size();
}

void Scanner::skip_line() {
  while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
  if (pos_ < data_.size()) {
    ++pos_;
    ++line_;
  }
}

std::string_view Scanner::rest_of_line() {
  skip_space(false);
  tok_line_ = line_;
  const std::size_t start = pos_;
  while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
  std::size_t end = pos_;
  while (end > start && is_space(data_[end - 1])) --end;
  if (pos_ < data_.size()) {
    ++pos_;
    ++line_;
  }
  return data_.substr(start, end - start);
}

double Scanner::real(const char* what) { return real(token(what), what); }

double Scanner::real(std::string_view tok, const char* what) const {
  double v = 0.0;
  if (parse_double(tok, v)) return v;
  // Say why: NaN/Inf and overflow get their own words, everything else is garbage.
  double raw = 0.0;
  std::string_view t = tok;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), raw);
  if (ptr == t.data() + t.size() && !t.empty()) {
    if (ec == std::errc::result_out_of_range) fail(std::string(what) + " out of range: " + quote(tok));
    if (ec == std::errc()) fail(std::string(what) + " is not finite: " + quote(tok));
  }
  fail(std::string("expected a number (") + what + "), found " + quote(tok));
}

long long Scanner::integer(const char* what) { return integer(token(what), what); }

long long Scanner::integer(std::string_view tok, const char* what) const {
  long long v = 0;
  if (!parse_int64(tok, v)) fail(std::string("expected an integer (") + what + "), found " + quote(tok));
  return v;
}

int Scanner::count(const char* what, std::size_t min_bytes) {
  return check_count(integer(what), what, min_bytes);
}

int Scanner::check_count(long long n, const char* what, std::size_t min_bytes) const {
  if (n < 0) fail(std::string("negative ") + what + " " + std::to_string(n));
  const std::size_t room = remaining() / std::max<std::size_t>(min_bytes, 1) + 1;
  if (n > INT_MAX || static_cast<unsigned long long>(n) > room)
    fail("declared " + std::to_string(n) + " " + what + ", more than the rest of the file (" +
         std::to_string(remaining()) + " bytes) can hold");
  return static_cast<int>(n);
}

int Scanner::index(long long n_vertices, int base) {
  return check_index(integer("vertex index"), n_vertices, base);
}

int Scanner::check_index(long long value, long long n_vertices, int base) const {
  if (value < base || value - base >= n_vertices)
    fail("vertex index " + std::to_string(value) + " out of range (" +
         (n_vertices == 0 ? std::string("no vertices")
                          : std::to_string(base) + ".." + std::to_string(n_vertices - 1 + base)) +
         ")");
  return static_cast<int>(value - base);
}

void Scanner::fail(const std::string& what) const { throw core::InputError(name_, tok_line_, what); }

// --- ByteReader -------------------------------------------------------------------------------

void ByteReader::need(std::size_t n, const char* what) const {
  if (n > remaining())
    fail(std::string("truncated binary data (expected ") + what + " at byte " + std::to_string(pos_) +
         ", file has " + std::to_string(data_.size()) + " bytes)");
}

void ByteReader::fail(const std::string& what) const { throw core::InputError(name_, 0, what); }

// --- TextWriter -------------------------------------------------------------------------------

TextWriter& TextWriter::operator<<(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out_.append(buf, static_cast<std::size_t>(r.ptr - buf));
  return *this;
}

TextWriter& TextWriter::operator<<(float v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out_.append(buf, static_cast<std::size_t>(r.ptr - buf));
  return *this;
}

TextWriter& TextWriter::operator<<(long long v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  out_.append(buf, static_cast<std::size_t>(r.ptr - buf));
  return *this;
}

}  // namespace polycube::io::detail
