#include "emcontact/time/restoration.hpp"

#include <BelosSolverFactory_Tpetra.hpp>
#include <BelosTpetraAdapter.hpp>
#include <cmath>

namespace emc::time {

using Teuchos::RCP;
using Teuchos::rcp;

namespace {

/// [M_ff 0; 0 I]: the consistent mass on the free dofs, the identity on the fixed ones (SPD).
class FreeMass : public Operator {
 public:
  FreeMass(const fem::Discretization& disc, RCP<const Vector> free) : disc_(disc), free_(free) {}
  RCP<const Map> getDomainMap() const override { return disc_.owned_map(); }
  RCP<const Map> getRangeMap() const override { return disc_.owned_map(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp, double alpha,
             double beta) const override {
    Vector xf(disc_.owned_map()), Mx(disc_.owned_map());
    for (std::size_t j = 0; j < X.getNumVectors(); ++j) {
      const auto x = X.getVector(j);
      xf.elementWiseMultiply(1.0, *free_, *x, 0.0);
      disc_.apply_mass(xf, Mx);
      Mx.elementWiseMultiply(1.0, *free_, Mx, 0.0);  // free rows: (M_ff x_f)
      Mx.update(1.0, *x, -1.0, xf, 1.0);             // fixed rows: x
      Y.getVectorNonConst(j)->update(alpha, Mx, beta);
    }
  }

 private:
  const fem::Discretization& disc_;
  RCP<const Vector> free_;
};

/// Y = alpha diag(d) X + beta Y.
class Diagonal : public Operator {
 public:
  explicit Diagonal(RCP<const Vector> d) : d_(d) {}
  RCP<const Map> getDomainMap() const override { return d_->getMap(); }
  RCP<const Map> getRangeMap() const override { return d_->getMap(); }
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp, double alpha,
             double beta) const override {
    Y.elementWiseMultiply(alpha, *d_, X, beta);
  }

 private:
  RCP<const Vector> d_;
};

}  // namespace

EnergyRestoration::EnergyRestoration(const fem::Discretization& disc, const std::vector<GO>& fixed)
    : disc_(disc) {
  const auto map = disc.owned_map();
  free_ = rcp(new Vector(map));
  free_->putScalar(1.0);
  {
    auto h = free_->getLocalViewHost(Tpetra::Access::ReadWrite);
    for (GO d : fixed) h(map->getLocalElement(d), 0) = 0.0;
  }
  Vector ones(map), lumped(map);
  ones.putScalar(1.0);
  disc.apply_mass(ones, lumped);  // row sums of M
  inverse_ = rcp(new Vector(map));
  auto f = free_->getLocalViewHost(Tpetra::Access::ReadOnly);
  auto l = lumped.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto inv = inverse_->getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (std::size_t i = 0; i < inv.extent(0); ++i)
    inv(i, 0) = f(i, 0) > 0 && l(i, 0) > 0 ? 1.0 / l(i, 0) : 1.0;
}

Restoration EnergyRestoration::restore(const Vector& p, double D, double roundoff,
                                       Vector& V) const {
  Restoration r;
  if (std::fabs(D) <= roundoff) return r;
  const auto map = disc_.owned_map();
  Vector pf(map), dv(map);
  pf.elementWiseMultiply(1.0, *free_, p, 0.0);
  if (pf.normInf() == 0) {  // no compressive entry to push along: the energy cannot go back
    r.ok = false;
    return r;
  }
  // dv = M_ff^-1 p_f by CG with the inverse lumped mass (M is well conditioned)
  using Problem = Belos::LinearProblem<double, MultiVector, Operator>;
  auto problem = rcp(new Problem(rcp(new FreeMass(disc_, free_)), Teuchos::rcpFromRef(dv),
                                 Teuchos::rcpFromRef(pf)));
  problem->setLeftPrec(rcp(new Diagonal(inverse_)));
  problem->setProblem();
  auto params = rcp(new Teuchos::ParameterList);
  params->set("Convergence Tolerance", 1e-14);
  params->set("Maximum Iterations", 500);
  Belos::SolverFactory<double, MultiVector, Operator> factory;
  auto solver = factory.create("CG", params);
  solver->setProblem(problem);
  solver->solve();
  r.iterations = solver->getNumIters();
  dv.elementWiseMultiply(1.0, *free_, dv, 0.0);
  // K(V + gamma dv) - K(V) = gamma a + gamma^2 b / 2 with M itself: exact for this dv
  Vector Mw(map);
  disc_.apply_mass(V, Mw);
  const double a = dv.dot(Mw);
  disc_.apply_mass(dv, Mw);
  const double b = dv.dot(Mw);
  const double disc = a * a + 2 * b * D;
  if (!(b > 0) || !(disc >= 0)) {
    r.ok = false;
    return r;
  }
  // D >= 0: the root gamma >= 0 (a contact impulse pushes the bodies apart); D < 0 (a closure
  // that pushed nodes out): the root nearest 0. Written without cancellation.
  const double s = std::sqrt(disc);
  r.gamma = a >= 0 ? 2 * D / (a + s) : (D >= 0 ? (s - a) / b : 2 * D / (a - s));
  V.update(r.gamma, dv, 1.0);
  return r;
}

}  // namespace emc::time
