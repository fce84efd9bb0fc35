// Reading ASCII tokens and little-endian binary values of a .msh file, with bounds checks.
#include "msh_scanner.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

#include "emcontact/error.hpp"
#include "emcontact/input/echo.hpp"

namespace emc::mesh::msh {
namespace {

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

/// A token without one leading '+' (from_chars refuses it, C and Gmsh accept it).
const char* after_plus(const std::string& t) {
  return t.size() > 1 && t[0] == '+' && t[1] != '-' ? t.data() + 1 : t.data();
}

}  // namespace

void Scanner::set_section(const std::string& section) {
  section_ = input::echo(section);
}

bool Scanner::at_end() {
  skip_space();
  return pos_ >= text_.size();
}

void Scanner::skip_space() {
  while (pos_ < text_.size() && (is_blank(text_[pos_]) || text_[pos_] == '\n')) ++pos_;
}

void Scanner::skip_blanks() {
  while (pos_ < text_.size() && is_blank(text_[pos_])) ++pos_;
}

std::string Scanner::line() {
  const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
  std::size_t last = end;
  while (last > pos_ && is_blank(text_[last - 1])) --last;
  std::string out = text_.substr(pos_, last - pos_);
  pos_ = std::min(end + 1, text_.size());
  return out;
}

std::string Scanner::token(const char* what) {
  skip_blanks();
  const std::size_t begin = pos_;
  while (pos_ < text_.size() && !is_blank(text_[pos_]) && text_[pos_] != '\n') ++pos_;
  if (pos_ == begin) {
    fail(std::string("expected ") + what + ", found the end of the " +
         (pos_ < text_.size() ? "line" : "file (truncated file?)"));
  }
  return text_.substr(begin, pos_ - begin);
}

std::uint64_t Scanner::little_endian(std::size_t bytes, const char* what) {
  if (text_.size() - pos_ < bytes) {
    fail(std::string("the file ends inside ") + what + " (truncated file?)");
  }
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < bytes; ++i) {
    v |= static_cast<std::uint64_t>(static_cast<unsigned char>(text_[pos_ + i])) << (8 * i);
  }
  pos_ += bytes;
  return v;
}

std::uint64_t Scanner::size(const char* what) {
  if (binary_) return little_endian(8, what);
  const std::string t = token(what);
  std::uint64_t v = 0;
  const char* first = after_plus(t);
  const auto r = std::from_chars(first, t.data() + t.size(), v);
  if (r.ec == std::errc::result_out_of_range)
    fail(std::string(what) + " " + quote(t) + " is too large");
  if (r.ec != std::errc() || r.ptr != t.data() + t.size()) {
    fail(std::string("expected ") + what + " (a non-negative integer), found " + quote(t));
  }
  return v;
}

int Scanner::integer(const char* what) {
  if (binary_) {
    const auto u = static_cast<std::uint32_t>(little_endian(4, what));
    std::int32_t v;
    std::memcpy(&v, &u, sizeof v);
    return v;
  }
  const std::string t = token(what);
  int v = 0;
  const auto r = std::from_chars(after_plus(t), t.data() + t.size(), v);
  if (r.ec == std::errc::result_out_of_range) {
    fail(std::string(what) + " " + quote(t) + " is out of the range of an int");
  }
  if (r.ec != std::errc() || r.ptr != t.data() + t.size()) {
    fail(std::string("expected ") + what + " (an integer), found " + quote(t));
  }
  return v;
}

double Scanner::real(const char* what) {
  if (binary_) {
    const std::uint64_t u = little_endian(8, what);
    double v;
    std::memcpy(&v, &u, sizeof v);
    return v;
  }
  const std::string t = token(what);
  double v = 0.0;
  const auto r = std::from_chars(after_plus(t), t.data() + t.size(), v);
  if (r.ec == std::errc::result_out_of_range) {
    fail(std::string(what) + " " + quote(t) + " is out of the range of a double");
  }
  if (r.ec != std::errc() || r.ptr != t.data() + t.size()) {
    fail(std::string("expected ") + what + " (a number), found " + quote(t));
  }
  return v;
}

bool Scanner::try_end_line() {
  if (binary_) return true;
  skip_blanks();
  if (pos_ < text_.size() && text_[pos_] != '\n') return false;
  if (pos_ < text_.size()) ++pos_;
  return true;
}

void Scanner::end_line(const char* what) {
  if (try_end_line()) return;
  fail(std::string("expected the end of the line after ") + what + ", found " +
       quote(token("a token")));
}

std::string Scanner::quoted(const char* what) {
  skip_blanks();
  const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
  const std::size_t close = pos_ < end ? text_.find('"', pos_ + 1) : std::string::npos;
  if (pos_ >= end || text_[pos_] != '"' || close == std::string::npos || close >= end) {
    fail(std::string("expected ") + what + " in double quotes on the same line");
  }
  std::string out = text_.substr(pos_ + 1, close - pos_ - 1);
  pos_ = close + 1;
  return out;
}

void Scanner::check_count(std::uint64_t count, std::size_t ascii_bytes, std::size_t binary_bytes,
                          const std::string& what) {
  const std::size_t each = binary_ ? binary_bytes : ascii_bytes;
  const std::size_t left = text_.size() - pos_;
  if (count <= left / each) return;
  fail(what + " (" + std::to_string(count) + ") is more than the rest of the file can hold (" +
       std::to_string(left) + " bytes left, at least " + std::to_string(each) + " per item)");
}

std::string Scanner::location() const {
  std::string loc;
  if (binary_file_) {
    loc = "byte " + std::to_string(pos_);
  } else {
    const auto end = text_.begin() + static_cast<std::ptrdiff_t>(std::min(pos_, text_.size()));
    loc = "line " + std::to_string(1 + std::count(text_.begin(), end, '\n'));
  }
  return section_.empty() ? loc : loc + " ($" + section_ + ")";
}

void Scanner::fail(const std::string& what) const {
  throw InputError(where_ + ": " + location() + ": " + what);
}

void Scanner::fail_section(const std::string& what) const {
  throw InputError(where_ + ": $" + section_ + ": " + what);
}

std::string Scanner::quote(const std::string& token) {
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < 24; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    out += c >= 32 && c < 127 ? static_cast<char>(c) : '?';
  }
  return out + (token.size() > 24 ? "...'" : "'");
}

}  // namespace emc::mesh::msh
