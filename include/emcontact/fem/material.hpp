#pragma once
// The material models of `Bodies/<body>/Material/model` (docs/THEORY.md §1.2, §12) and each
// body's kernel material: the kernel library's policy type and its constants.
#include "kernels/hyperelastic.hpp"
#include "kernels/svk.hpp"

namespace emc::fem {

/// svk: Saint-Venant-Kirchhoff; neo_hookean, mooney_rivlin: compressible, with the volumetric
/// term -2 (c1 + 2 c2) ln J + lambda/2 (ln J)^2 (kernels/hyperelastic.hpp).
enum class MaterialModel { svk, neo_hookean, mooney_rivlin };

/// A body's material constants as the model reads them: young and poisson the small-strain
/// ones, c1 = mu / 2 - c2 and c2 Mooney-Rivlin's.
struct MaterialConstants {
  MaterialModel model = MaterialModel::svk;
  double young = 0, poisson = 0, c1 = 0, c2 = 0;
};

/// Saint-Venant-Kirchhoff's Lame constants.
inline kernels::Lame svk_material(const MaterialConstants& c) {
  return kernels::lame(c.young, c.poisson);
}

/// The Neo-Hookean (Lame constants of young, poisson) or Mooney-Rivlin (c1, c2 and lambda - 4 c2:
/// its small-strain constants are young's and poisson's) policy.
inline kernels::LogHyperelastic hyper_material(const MaterialConstants& c) {
  const kernels::Lame l = kernels::lame(c.young, c.poisson);
  if (c.model == MaterialModel::neo_hookean) return kernels::neo_hookean(l.lambda, l.mu);
  return kernels::mooney_rivlin(c.c1, c.c2, l.lambda - 4 * c.c2);
}

}  // namespace emc::fem
