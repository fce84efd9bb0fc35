#include "emcontact/contact/law.hpp"

namespace emc::contact {

std::shared_ptr<const Law> make_full_stick();
std::shared_ptr<const Law> make_frictionless();
std::shared_ptr<const Law> make_coulomb();

std::shared_ptr<const Law> make_law(Kind kind) {
  switch (kind) {
    case Kind::full_stick:
      return make_full_stick();
    case Kind::frictionless:
      return make_frictionless();
    case Kind::coulomb:
      return make_coulomb();
  }
  return nullptr;
}

}  // namespace emc::contact
