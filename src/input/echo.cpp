// Echoing user text in messages: escaped and cut (emcontact/input/echo.hpp).
#include "emcontact/input/echo.hpp"

#include "emcontact/format.hpp"

namespace emc::input {
namespace {

/// The escape of byte `c`, or "" if it is shown as it is (printable ASCII, bytes of UTF-8).
std::string escape(unsigned char c) {
  switch (c) {
    case '\n':
      return "\\n";
    case '\r':
      return "\\r";
    case '\t':
      return "\\t";
    case '\0':
      return "\\0";
    default:
      break;
  }
  if (c >= 0x20 && c != 0x7f) return "";
  return format("\\x%02x", c);
}

bool utf8_continuation(unsigned char c) {
  return (c & 0xc0) == 0x80;
}

}  // namespace

std::string echo(const std::string& text) {
  std::string out;
  std::size_t shown = 0;  // characters of the escaped text
  std::size_t i = 0;
  for (; i < text.size() && shown < kEchoMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const std::string e = escape(c);
    if (!e.empty()) {
      if (shown + e.size() > kEchoMax) break;
      out += e;
      shown += e.size();
      continue;
    }
    out += static_cast<char>(c);
    if (!utf8_continuation(c)) ++shown;
  }
  // finish a UTF-8 sequence begun within the limit
  while (i < text.size() && utf8_continuation(static_cast<unsigned char>(text[i])))
    out += text[i++];
  if (i == text.size()) return out;
  return out + "... (" + std::to_string(text.size()) + " characters)";
}

std::string echo_list(const std::vector<std::string>& names, std::size_t max_listed) {
  std::string s;
  const std::size_t listed = names.size() <= max_listed + 1 ? names.size() : max_listed;
  for (std::size_t k = 0; k < listed; ++k) s += (k ? ", \"" : "\"") + echo(names[k]) + "\"";
  if (listed < names.size()) s += " and " + std::to_string(names.size() - listed) + " more";
  return s;
}

std::string echo_number(double value) {
  return format("%.6g", value);
}

}  // namespace emc::input
