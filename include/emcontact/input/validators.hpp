#pragma once
// Small factories for the Teuchos validators the parameter schemas use (header only: every module
// declares its parameters with them). Teuchos number ranges are inclusive: a strict
// bound is the neighbouring double (the input module prints it back as "> 0", "< 0.5").
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace emc::input {

using ValidatorPtr = Teuchos::RCP<const Teuchos::ParameterEntryValidator>;

/// A double in [lo, hi] (either bound may be +-infinity: no bound).
inline ValidatorPtr double_range(double lo, double hi) {
  auto v = Teuchos::rcp(new Teuchos::EnhancedNumberValidator<double>());
  if (std::isfinite(lo)) v->setMin(lo);
  if (std::isfinite(hi)) v->setMax(hi);
  return v;
}

/// A double > lo (strict).
inline ValidatorPtr double_above(double lo) {
  return double_range(std::nextafter(lo, std::numeric_limits<double>::infinity()),
                      std::numeric_limits<double>::infinity());
}

/// A double > 0.
inline ValidatorPtr positive_double() {
  return double_above(0.0);
}

/// A double >= lo.
inline ValidatorPtr double_at_least(double lo) {
  return double_range(lo, std::numeric_limits<double>::infinity());
}

/// An int in [lo, hi].
inline ValidatorPtr int_range(int lo, int hi) {
  return Teuchos::rcp(new Teuchos::EnhancedNumberValidator<int>(lo, hi));
}

/// An int >= lo.
inline ValidatorPtr int_at_least(int lo) {
  auto v = Teuchos::rcp(new Teuchos::EnhancedNumberValidator<int>());
  v->setMin(lo);
  return v;
}

/// One of the given strings (case-sensitive) for the parameter `name`; `docs` documents each
/// choice. The value of choice i is values[i]: the module that reads the parameter takes it with
/// Teuchos::getIntegralValue<E>(list, name) (the list validated against this schema).
template <class E>
ValidatorPtr string_choice(const std::string& name, const std::vector<std::string>& choices,
                           const std::vector<std::string>& docs, const std::vector<E>& values) {
  const Teuchos::Array<std::string> strings(choices.begin(), choices.end());
  const Teuchos::Array<std::string> strings_docs(docs.begin(), docs.end());
  const Teuchos::Array<E> integral(values.begin(), values.end());
  return Teuchos::rcp(new Teuchos::StringToIntegralParameterEntryValidator<E>(
      strings(), strings_docs(), integral(), name));
}

/// Sets the string parameter `name` of `pl` (default `value`, documented `doc`) to one of
/// `choices`, documented by `docs`, whose values are `values` (string_choice above).
template <class E>
void set_choice(Teuchos::ParameterList& pl, const std::string& name, const std::string& value,
                const std::string& doc, const std::vector<std::string>& choices,
                const std::vector<std::string>& docs, const std::vector<E>& values) {
  pl.set(name, value, doc, string_choice(name, choices, docs, values));
}

/// As above, the value of choice i being i (Teuchos::getIntegralValue<int>).
inline ValidatorPtr string_choice(const std::string& name, const std::vector<std::string>& choices,
                                  const std::vector<std::string>& docs) {
  std::vector<int> values;
  for (int i = 0; i < static_cast<int>(choices.size()); ++i) values.push_back(i);
  return string_choice(name, choices, docs, values);
}

/// Any string (the meaning is checked later, e.g. a body or surface name).
inline ValidatorPtr any_string() {
  return Teuchos::rcp(new Teuchos::StringValidator());
}

/// An Array(double) of finite numbers; the input module also requires exactly 3 components
/// for every Array(double) parameter whose default has 3.
inline ValidatorPtr vector3() {
  return Teuchos::rcp(new Teuchos::ArrayNumberValidator<double>(
      Teuchos::rcp(new Teuchos::EnhancedNumberValidator<double>())));
}

/// The default of a 3-vector parameter.
inline Teuchos::Array<double> vec3(double x, double y, double z) {
  return Teuchos::tuple(x, y, z);
}

}  // namespace emc::input
