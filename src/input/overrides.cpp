// Command-line overrides "Section/Sub/name=value" and the strict parsing of values.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "emcontact/error.hpp"
#include "emcontact/input/detail.hpp"

namespace emc::input::detail {
namespace {

using Teuchos::any;
using Teuchos::Array;
using Teuchos::ParameterList;

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

long long parse_integer(const std::string& text, long long lo, long long hi) {
  const std::string s = trim(text);
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0') throw std::invalid_argument("not an integer");
  if (errno == ERANGE || v < lo || v > hi) throw std::invalid_argument("integer out of range");
  return v;
}

double parse_double(const std::string& text) {
  const std::string s = trim(text);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0') throw std::invalid_argument("not a number");
  if (!std::isfinite(v)) throw std::invalid_argument("not a finite number");
  return v;
}

bool parse_bool(const std::string& text) {
  const std::string s = lower(trim(text));
  if (s == "true" || s == "yes" || s == "1") return true;
  if (s == "false" || s == "no" || s == "0") return false;
  throw std::invalid_argument("not a bool");
}

/// The comma-separated items of "{a, b, c}" (the braces are optional).
std::vector<std::string> array_items(const std::string& text) {
  std::string s = trim(text);
  if (!s.empty() && s.front() == '{') {
    if (s.back() != '}') throw std::invalid_argument("missing }");
    s = trim(s.substr(1, s.size() - 2));
  }
  std::vector<std::string> items;
  if (s.empty()) return items;
  std::size_t start = 0;
  while (true) {
    const auto comma = s.find(',', start);
    items.push_back(trim(s.substr(start, comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return items;
}

template <class T, class F>
Array<T> parse_array(const std::string& text, F parse_item) {
  Array<T> a;
  for (const auto& item : array_items(text)) a.push_back(parse_item(item));
  return a;
}

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto slash = path.find('/', start);
    parts.push_back(path.substr(start, slash - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return parts;
}

/// Throws InputError `<file>: override "<text>": <what>; allowed: <allowed>`.
[[noreturn]] void refuse(const std::string& file, const std::string& text, const Problem& p) {
  throw InputError(file + ": override \"" + shorten(text) + "\": " + p.what +
                   "; allowed: " + p.allowed);
}

/// Where an override is applied: the user's list, its schema (null inside pass-through lists).
struct Target {
  ParameterList* user;
  const ParameterList* valid;
};

/// The user's sublist `name` of `user`, created if missing; refuses a plain parameter.
ParameterList* user_sublist(ParameterList* user, const std::string& name, const std::string& file,
                            const std::string& text) {
  if (user->isParameter(name) && !user->isSublist(name))
    refuse(file, text,
           {"\"" + shorten(name) + "\" is a parameter in the input, not a sublist", "a path"});
  return &user->sublist(name);
}

/// Resolves the section and, for named sections, the existing user-named sublist.
Target section_target(ParameterList& params, const std::vector<Section>& all,
                      const std::vector<std::string>& parts, std::size_t& next,
                      const std::string& file, const std::string& text,
                      Teuchos::RCP<const ParameterList>& keep_alive) {
  auto s =
      std::find_if(all.begin(), all.end(), [&](const Section& x) { return x.name == parts[0]; });
  if (s == all.end()) {
    std::string names;
    for (const auto& x : all) names += (names.empty() ? "" : ", ") + x.name;
    refuse(file, text, {"unknown section \"" + shorten(parts[0]) + "\"", names});
  }
  keep_alive = s->schema;
  ParameterList* user = user_sublist(&params, s->name, file, text);
  next = 1;
  if (!s->named()) return {user, s->schema.get()};
  if (parts.size() < 3 || !user->isSublist(parts[1])) {
    const std::string what = s->placeholder.substr(1, s->placeholder.size() - 2);
    const std::string names = entry_names(*user);
    refuse(file, text,
           {parts.size() < 3 ? "no " + what + " named"
                             : "\"" + shorten(parts[1]) + "\" is not a " + what + " of the input",
            s->name + "/" + s->placeholder + "/... with " + s->placeholder +
                " one of: " + (names.empty() ? "(none in the input)" : names)});
  }
  next = 2;
  return {&user->sublist(parts[1]), s->schema.get()};
}

/// Descends into the sublist `name` of the schema (until a pass-through list) and of the input.
Target descend(Target t, const std::string& name, const std::string& file,
               const std::string& text) {
  if (t.valid) {
    if (!t.valid->isSublist(name))
      refuse(file, text,
             {"no sublist \"" + shorten(name) + "\"" + suggestion(name, *t.valid),
              entry_names(*t.valid)});
    t.valid = &t.valid->sublist(name);
    if (is_pass_through(*t.valid)) t.valid = nullptr;
  }
  t.user = user_sublist(t.user, name, file, text);
  return t;
}

/// Sets the leaf parameter `name` from `value_text`, with the schema's type or, inside a
/// pass-through list, the existing entry's type (else a guess).
void set_leaf(const Target& t, const std::string& name, const std::string& value_text,
              const std::string& file, const std::string& text) {
  if (t.user->isSublist(name))
    refuse(file, text, {"\"" + shorten(name) + "\" is a sublist", "a parameter"});
  if (!t.valid) {
    Teuchos::any v = guess_value(value_text);
    if (t.user->isParameter(name)) {  // keep the type of the existing entry
      const Teuchos::any& old = t.user->getEntry(name).getAny(false);
      try {
        v = parse_value(value_text, old);
      } catch (const std::invalid_argument&) {
        refuse(file, text,
               {"\"" + shorten(value_text) + "\" is not a valid " + type_name(old),
                "a value of type " + type_name(old) + " (as the entry in the input)"});
      }
    }
    Teuchos::ParameterEntry e;
    e.setAnyValue(v);
    t.user->setEntry(name, e);
    return;
  }
  if (!t.valid->isParameter(name))
    refuse(file, text,
           {"unknown parameter \"" + shorten(name) + "\"" + suggestion(name, *t.valid),
            entry_names(*t.valid)});
  const Teuchos::ParameterEntry& valid = t.valid->getEntry(name);
  if (valid.isList())
    refuse(file, text,
           {"\"" + shorten(name) + "\" is a sublist",
            "a parameter inside it: " + entry_names(t.valid->sublist(name))});
  Teuchos::ParameterEntry e;
  try {
    e.setAnyValue(parse_value(value_text, valid.getAny(false)));
  } catch (const std::invalid_argument&) {
    refuse(file, text,
           {"\"" + shorten(value_text) + "\" is not a valid " + type_name(valid.getAny(false)),
            allowed_text(valid)});
  }
  if (auto p = check_entry(e, valid)) refuse(file, text, *p);
  t.user->setEntry(name, e);
}

}  // namespace

any parse_value(const std::string& text, const any& like) {
  const auto& t = like.type();
  if (t == typeid(double)) return any(parse_double(text));
  if (t == typeid(int)) return any(static_cast<int>(parse_integer(text, INT_MIN, INT_MAX)));
  if (t == typeid(long long)) return any(parse_integer(text, LLONG_MIN, LLONG_MAX));
  if (t == typeid(bool)) return any(parse_bool(text));
  if (t == typeid(std::string)) return any(text);
  if (t == typeid(Array<double>)) return any(parse_array<double>(text, parse_double));
  if (t == typeid(Array<int>))
    return any(parse_array<int>(text, [](const std::string& s) {
      return static_cast<int>(parse_integer(s, INT_MIN, INT_MAX));
    }));
  if (t == typeid(Array<std::string>))
    return any(parse_array<std::string>(text, [](const std::string& s) { return s; }));
  throw std::invalid_argument("cannot parse a value of type " + like.typeName());
}

any guess_value(const std::string& text) {
  for (const any& like : {any(0), any(0.0), any(false)}) {
    try {
      return parse_value(text, like);
    } catch (const std::invalid_argument&) {
    }
  }
  return any(text);
}

std::string override_path(const std::string& text) {
  return trim(text.substr(0, text.find('=')));  // as apply_override reads it
}

void apply_override(ParameterList& params, const std::string& text, const std::string& file,
                    const std::vector<Section>& sections) {
  const auto eq = text.find('=');
  const std::string path = eq == std::string::npos ? "" : trim(text.substr(0, eq));
  if (path.empty())
    refuse(file, text, {"not of the form Section/.../name=value", "e.g. Time/end=0.5"});
  const std::string value = trim(text.substr(eq + 1));
  const auto parts = split_path(path);
  if (std::find(parts.begin(), parts.end(), "") != parts.end())
    refuse(file, text, {"empty name in the path", "Section/.../name=value"});
  if (parts.size() < 2)
    refuse(file, text, {"\"" + shorten(path) + "\" is a section", "Section/.../name=value"});
  std::size_t next = 0;
  Teuchos::RCP<const ParameterList> keep_alive;
  Target t = section_target(params, sections, parts, next, file, text, keep_alive);
  for (; next + 1 < parts.size(); ++next) t = descend(t, parts[next], file, text);
  set_leaf(t, parts.back(), value, file, text);
}

}  // namespace emc::input::detail
