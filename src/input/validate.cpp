// Checking user values against the schema, with one-paragraph messages (file, path, allowed).
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include "emcontact/error.hpp"
#include "emcontact/input/detail.hpp"

namespace emc::input::detail {
namespace {

using Teuchos::any;
using Teuchos::ParameterEntry;
using Teuchos::ParameterEntryValidator;
using Teuchos::ParameterList;

/// Validators that accept several types (and convert): the type check is theirs.
bool accepts_several_types(const ParameterEntryValidator* v) {
  return dynamic_cast<const Teuchos::AnyNumberParameterEntryValidator*>(v) ||
         dynamic_cast<const Teuchos::BoolParameterEntryValidator*>(v);
}

bool is_number_validator(const ParameterEntryValidator* v) {
  return dynamic_cast<const Teuchos::EnhancedNumberValidator<double>*>(v) ||
         dynamic_cast<const Teuchos::EnhancedNumberValidator<int>*>(v) ||
         dynamic_cast<const Teuchos::EnhancedNumberValidator<long long>*>(v);
}

/// What is wrong with a value its validator refused.
std::string value_problem(const any& value, const ParameterEntryValidator* v) {
  const std::string shown = format_value(value);
  if (is_number_validator(v)) return "value " + shown + " is out of range";
  if (value.type() == typeid(Teuchos::Array<double>) || value.type() == typeid(Teuchos::Array<int>))
    return "value " + shown + " has a component out of range";
  return "value " + shown + " is not allowed";
}

std::string join(const std::string& path, const std::string& name) {
  return path.empty() ? name : path + "/" + name;
}

}  // namespace

void fail(const std::string& file, const std::string& path, const Problem& p) {
  throw InputError(file + ": parameter \"" + shorten(path) + "\": " + p.what +
                   "; allowed: " + p.allowed);
}

std::optional<Problem> check_entry(const ParameterEntry& user, const ParameterEntry& valid) {
  const any& u = user.getAny(false);
  const any& v = valid.getAny(false);
  const auto validator = valid.validator();
  const bool strict_type = validator.is_null() || !accepts_several_types(validator.get());
  if (strict_type && u.type() != v.type())
    return Problem{"has type " + type_name(u) + " (value " + format_value(u) + "), expected type " +
                       type_name(v),
                   allowed_text(valid)};
  if (auto n = required_size(valid)) {
    const auto size = Teuchos::any_cast<Teuchos::Array<double>>(u).size();
    if (static_cast<int>(size) != *n)
      return Problem{"has " + std::to_string(size) + " components " + format_value(u),
                     allowed_text(valid)};
  }
  if (validator.is_null()) return std::nullopt;
  try {
    validator->validate(user, "value", "input");
  } catch (const Teuchos::Exceptions::InvalidParameterType&) {
    return Problem{"has the wrong type " + type_name(u), allowed_text(valid)};
  } catch (const std::exception&) {
    return Problem{value_problem(u, validator.get()), allowed_text(valid)};
  }
  return std::nullopt;
}

void check_list(const ParameterList& user, const ParameterList& valid, const std::string& path,
                const std::string& file) {
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string& name = user.name(it);
    const ParameterEntry& entry = user.entry(it);
    const std::string p = join(path, name);
    if (!valid.isParameter(name))
      fail(file, p, {"unknown name" + suggestion(name, valid), entry_names(valid)});
    const ParameterEntry& schema = valid.getEntry(name);
    if (schema.isList()) {
      const ParameterList& sub = valid.sublist(name);
      if (!entry.isList())
        fail(file, p,
             {"must be a sublist, not a parameter", "a sublist with: " + entry_names(sub)});
      if (!is_pass_through(sub)) check_list(user.sublist(name), sub, p, file);
      continue;
    }
    if (entry.isList()) fail(file, p, {"must be a parameter, not a sublist", allowed_text(schema)});
    if (auto problem = check_entry(entry, schema)) fail(file, p, *problem);
  }
}

}  // namespace emc::input::detail
