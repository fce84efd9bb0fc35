// Describing schema entries and values in words, for error messages and the documentation.
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "emcontact/format.hpp"
#include "emcontact/input/detail.hpp"
#include "emcontact/input/echo.hpp"

namespace emc::input::detail {
namespace {

using Teuchos::any;
using Teuchos::any_cast;
using Teuchos::Array;
using Teuchos::ArrayValidator;
using Teuchos::EnhancedNumberValidator;
using Teuchos::ParameterEntry;
using Teuchos::ParameterEntryValidator;
using Teuchos::ParameterList;

template <class T>
std::string format_array(const Array<T>& a) {
  std::string s = "{";
  for (Teuchos::Ordinal i = 0; i < a.size(); ++i) {
    if (i) s += ", ";
    s += format_value(any(a[i]), true);
  }
  return s + "}";
}

/// A bound of a double range: the bound itself (inclusive) or its neighbour (exclusive),
/// whichever prints shorter (Teuchos ranges are inclusive; strict bounds are stored as the
/// neighbouring double).
std::string double_bound(double bound, bool is_min) {
  const double outside = std::nextafter(bound, is_min ? -std::numeric_limits<double>::infinity()
                                                      : std::numeric_limits<double>::infinity());
  const std::string inclusive = format_double(bound), exclusive = format_double(outside);
  if (exclusive.size() < inclusive.size()) return (is_min ? "> " : "< ") + exclusive;
  return (is_min ? ">= " : "<= ") + inclusive;
}

template <class T>
std::string int_range(const EnhancedNumberValidator<T>& v) {
  const bool lo = v.hasMin() && v.getMin() > std::numeric_limits<T>::lowest();
  const bool hi = v.hasMax() && v.getMax() < std::numeric_limits<T>::max();
  if (lo && hi) return "from " + std::to_string(v.getMin()) + " to " + std::to_string(v.getMax());
  if (lo) return ">= " + std::to_string(v.getMin());
  if (hi) return "<= " + std::to_string(v.getMax());
  return "";
}

std::string double_range(const EnhancedNumberValidator<double>& v) {
  constexpr double kMax = std::numeric_limits<double>::max();
  const double lo = v.getMin(), hi = v.getMax();
  std::string s;
  // A minimum in (0, smallest normal double] is the usual way to say "> 0"; +-max: no bound.
  if (v.hasMin() && lo > 0 && lo <= std::numeric_limits<double>::min()) {
    s = "> 0";
  } else if (v.hasMin() && lo > -kMax) {
    s = double_bound(lo, true);
  }
  if (v.hasMax() && hi < kMax) s += (s.empty() ? "" : " and ") + double_bound(hi, false);
  return s;
}

/// The range a number validator allows ("> 0", "from 0 to 20"), "" if unbounded, nullopt if
/// `v` is not a number validator.
std::optional<std::string> number_range(const ParameterEntryValidator* v) {
  if (auto d = dynamic_cast<const EnhancedNumberValidator<double>*>(v)) return double_range(*d);
  if (auto i = dynamic_cast<const EnhancedNumberValidator<int>*>(v)) return int_range(*i);
  if (auto l = dynamic_cast<const EnhancedNumberValidator<long long>*>(v)) return int_range(*l);
  return std::nullopt;
}

/// The element validator of an array validator of numbers, else null.
const ParameterEntryValidator* array_element_validator(const ParameterEntryValidator* v) {
  if (auto a = dynamic_cast<const ArrayValidator<EnhancedNumberValidator<double>, double>*>(v))
    return a->getPrototype().get();
  if (auto a = dynamic_cast<const ArrayValidator<EnhancedNumberValidator<int>, int>*>(v))
    return a->getPrototype().get();
  return nullptr;
}

/// The kind of value, with an article ("a double", "3 numbers {x, y, z}").
std::string type_phrase(const ParameterEntry& valid) {
  const any& value = valid.getAny(false);
  const std::string t = type_name(value);
  if (t == "double") return "a double";
  if (t == "int") return "an int";
  if (t == "bool") return "a bool (true or false)";
  if (t == "string") return "a string";
  if (auto n = required_size(valid)) return "exactly " + std::to_string(*n) + " numbers {x, y, z}";
  return "an " + t;
}

/// A list of strings: quoted ("a", "b") or as Markdown code spans.
std::string join_choices(const Array<std::string>& v, bool markdown) {
  std::string s;
  for (Teuchos::Ordinal i = 0; i < v.size(); ++i) {
    if (i) s += ", ";
    s += markdown ? "`" + v[i] + "`" : "\"" + v[i] + "\"";
  }
  return s;
}

/// The constraint a validator adds to the type ("> 0"), "" if none.
std::string constraint(const ParameterEntry& valid) {
  const auto v = valid.validator();
  if (v.is_null()) return "";
  if (auto r = number_range(v.get())) return *r;
  if (auto e = array_element_validator(v.get())) {
    const auto r = number_range(e);
    return r && !r->empty() ? "each " + *r : "";
  }
  if (auto f = dynamic_cast<const Teuchos::FileNameValidator*>(v.get()))
    return f->fileMustExist() ? "(an existing file)" : "(a file name)";
  return "";
}

/// The valid strings of a string validator, or null for any string.
Teuchos::RCP<const Array<std::string>> valid_strings(const ParameterEntry& valid) {
  const auto v = valid.validator();
  if (v.is_null() || number_range(v.get()) || array_element_validator(v.get()))
    return Teuchos::null;
  auto s = v->validStringValues();
  return (s.is_null() || s->empty()) ? Teuchos::null : s;
}

/// Levenshtein distance (for "did you mean").
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> d(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) d[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = d[0];
    d[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = d[j];
      const bool same = std::tolower(a[i - 1]) == std::tolower(b[j - 1]);
      d[j] = std::min({d[j] + 1, d[j - 1] + 1, diag + (same ? 0 : 1)});
      diag = up;
    }
  }
  return d[b.size()];
}

}  // namespace

std::string format_double(double x) {
  if (std::isnan(x) || std::isinf(x)) return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  if (x == std::floor(x) && std::fabs(x) < 1e6) return std::to_string(static_cast<long long>(x));
  std::string s;
  for (int p = 1; p <= 17; ++p) {
    s = format("%.*g", p, x);
    if (std::strtod(s.c_str(), nullptr) == x) break;
  }
  // "1e+06" -> "1e6", "1e-05" -> "1e-5"
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

std::string type_name(const any& value) {
  return value.typeName();
}

std::string shorten(const std::string& text) {
  return echo(text);  // a refused value is echoed, not dumped
}

namespace {
std::string format_whole_value(const any& value, bool quote_strings) {
  if (value.type() == typeid(double)) return format_double(any_cast<double>(value));
  if (value.type() == typeid(int)) return std::to_string(any_cast<int>(value));
  if (value.type() == typeid(long long)) return std::to_string(any_cast<long long>(value));
  if (value.type() == typeid(bool)) return any_cast<bool>(value) ? "true" : "false";
  if (value.type() == typeid(std::string)) {
    const auto& s = any_cast<std::string>(value);
    return quote_strings ? "\"" + s + "\"" : s;
  }
  if (value.type() == typeid(Array<double>)) return format_array(any_cast<Array<double>>(value));
  if (value.type() == typeid(Array<int>)) return format_array(any_cast<Array<int>>(value));
  if (value.type() == typeid(Array<std::string>))
    return format_array(any_cast<Array<std::string>>(value));
  std::ostringstream os;
  value.print(os);
  return os.str();
}
}  // namespace

std::string format_value(const any& value, bool quote_strings) {
  return shorten(format_whole_value(value, quote_strings));
}

std::optional<int> required_size(const ParameterEntry& valid) {
  const any& value = valid.getAny(false);
  if (value.type() != typeid(Array<double>)) return std::nullopt;
  if (any_cast<Array<double>>(value).size() != 3) return std::nullopt;
  return 3;
}

std::string allowed_text(const ParameterEntry& valid) {
  if (auto s = valid_strings(valid)) return "one of " + join_choices(*s, false);
  const std::string c = constraint(valid);
  return type_phrase(valid) + (c.empty() ? "" : " " + c);
}

std::string allowed_markdown(const ParameterEntry& valid) {
  if (auto s = valid_strings(valid)) return join_choices(*s, true);
  if (type_name(valid.getAny(false)) == "bool") return "`true`, `false`";
  std::string c = constraint(valid);
  if (auto n = required_size(valid))
    return std::to_string(*n) + " numbers" + (c.empty() ? "" : ", " + c);
  if (c.empty())
    return valid.validator().is_null() ? "any" : "any " + type_name(valid.getAny(false));
  return c;
}

std::string entry_names(const ParameterList& valid) {
  std::string s;
  for (auto it = valid.begin(); it != valid.end(); ++it)
    s += (s.empty() ? "" : ", ") + valid.name(it);
  return s;
}

std::string suggestion(const std::string& name, const ParameterList& valid) {
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, name.size() / 3) + 1;
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::size_t d = edit_distance(name, valid.name(it));
    if (d < best_d) best_d = d, best = valid.name(it);
  }
  return best.empty() ? "" : " (did you mean \"" + best + "\"?)";
}

bool is_pass_through(const ParameterList& valid) {
  // ParameterList has no getter for disableRecursiveValidation(): probe it with an entry that
  // no schema declares.
  ParameterList outer, probe;
  outer.set("list", valid);
  probe.sublist("list").set("__emc_probe__", 0);
  try {
    probe.validateParameters(outer);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

std::string condense(const std::string& message) {
  std::istringstream in(message);
  std::string line, out;
  while (std::getline(in, line)) {
    line.erase(0, line.find_first_not_of(" \t"));
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
    const bool noise = line.empty() || line.rfind("Throw number", 0) == 0 ||
                       line.rfind("Throw test", 0) == 0 ||
                       (line.find(".cpp:") != std::string::npos && line.back() == ':') ||
                       (line.find(".hpp:") != std::string::npos && line.back() == ':');
    if (!noise) out += (out.empty() ? "" : " ") + line;
  }
  return out.empty() ? message : out;
}

}  // namespace emc::input::detail
