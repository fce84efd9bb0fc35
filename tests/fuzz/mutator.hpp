#pragma once
// Deterministic mutations of a seed file for the fuzz tests of the input readers: byte-level
// (flip, insert, delete, duplicate, truncate) and token-level (a number replaced by an extreme
// value, a line deleted, duplicated or swapped, an XML attribute changed). Same seed, same
// mutants: a failure found in CI reproduces anywhere.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace emc::fuzz {

/// Values that break naive parsers: overflow, sign, NaN, empty, huge counts, non-numbers.
inline const std::vector<std::string>& extreme_tokens() {
  static const std::vector<std::string> t = {
      "0",      "-1",    "1e308",         "-1e308",     "nan",         "inf",
      "-inf",   "",      "4294967296",    "2147483648", "-2147483649", "9999999999999999999",
      "1e-320", "0x10",  "1.5",           "abc",        "{1,2}",       "\"",
      "<",      "&amp;", "Array(double)", "{1,2,3,4}",  "{}",          "1,2,3"};
  return t;
}

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}

  /// 1 to 4 random mutations of `s`.
  std::string mutate(std::string s) {
    const int n = 1 + static_cast<int>(pick(4));
    for (int i = 0; i < n; ++i) s = once(std::move(s));
    return s;
  }

 private:
  std::mt19937_64 rng_;

  std::size_t pick(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng_() % n); }

  std::string once(std::string s) {
    if (s.empty()) return extreme_tokens()[pick(extreme_tokens().size())];
    switch (pick(10)) {
      case 0:
        s[pick(s.size())] = static_cast<char>(rng_() & 0xff);
        return s;
      case 1:
        s.insert(pick(s.size() + 1), 1, static_cast<char>(rng_() & 0xff));
        return s;
      case 2: {
        const std::size_t at = pick(s.size()),
                          len = 1 + pick(std::min<std::size_t>(64, s.size() - at));
        return s.erase(at, len);
      }
      case 3: {
        const std::size_t at = pick(s.size()),
                          len = 1 + pick(std::min<std::size_t>(256, s.size() - at));
        return s.insert(pick(s.size() + 1), s.substr(at, len));
      }
      case 4:
        s.resize(pick(s.size()));
        return s;
      case 5:
      case 6:
        return replace_number(std::move(s));
      case 7:
        return line_edit(std::move(s));
      default:
        return replace_quoted(std::move(s));
    }
  }

  /// A random number (digit run with sign, dot, exponent) replaced by an extreme token.
  std::string replace_number(std::string s) {
    std::vector<std::size_t> starts;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const bool digit = s[i] >= '0' && s[i] <= '9';
      const bool prev = i > 0 && ((s[i - 1] >= '0' && s[i - 1] <= '9') || s[i - 1] == '.' ||
                                  s[i - 1] == '-' || s[i - 1] == 'e');
      if (digit && !prev) starts.push_back(i);
    }
    if (starts.empty()) return s;
    std::size_t b = starts[pick(starts.size())], e = b;
    if (b > 0 && s[b - 1] == '-') --b;
    while (e < s.size() && std::string("0123456789.eE+-").find(s[e]) != std::string::npos) ++e;
    return s.replace(b, e - b, extreme_tokens()[pick(extreme_tokens().size())]);
  }

  /// A line deleted, duplicated, or swapped with another.
  std::string line_edit(const std::string& s) {
    std::vector<std::string> lines;
    std::size_t b = 0;
    while (b <= s.size()) {
      const std::size_t e = s.find('\n', b);
      lines.push_back(s.substr(b, e == std::string::npos ? std::string::npos : e - b));
      if (e == std::string::npos) break;
      b = e + 1;
    }
    const std::size_t i = pick(lines.size()), j = pick(lines.size());
    switch (pick(3)) {
      case 0:
        lines.erase(lines.begin() + static_cast<long>(i));
        break;
      case 1:
        lines.insert(lines.begin() + static_cast<long>(i), lines[j]);
        break;
      default:
        std::swap(lines[i], lines[j]);
    }
    std::string out;
    for (std::size_t k = 0; k < lines.size(); ++k)
      out += lines[k] + (k + 1 < lines.size() ? "\n" : "");
    return out;
  }

  /// The content of a random "..." (an XML attribute value, a Gmsh name) replaced.
  std::string replace_quoted(std::string s) {
    std::vector<std::size_t> quotes;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s[i] == '"') quotes.push_back(i);
    if (quotes.size() < 2) return replace_number(std::move(s));
    const std::size_t k = pick(quotes.size() / 2) * 2;
    const std::size_t b = quotes[k] + 1, e = quotes[k + 1];
    static const std::vector<std::string> names = {
        "int",           "double", "string", "bool", "Array(double)", "Array(int)",
        "ParameterList", "type",   "value",  "name", "file",          "box"};
    const std::string& r =
        pick(2) == 0 ? names[pick(names.size())] : extreme_tokens()[pick(extreme_tokens().size())];
    return s.replace(b, e - b, r);
  }
};

}  // namespace emc::fuzz
