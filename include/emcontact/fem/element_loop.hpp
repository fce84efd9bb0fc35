#pragma once
// The element loops of the assembly, coloured or atomic (include/emcontact/fem/colouring.hpp).
// A loop body is a functor with `template <bool Atomic> void element(int k, ...) const`, which
// adds into shared rows with scatter_add<Atomic>; its call per element is the same either way.
#include "emcontact/fem/colouring.hpp"

namespace emc::fem {

using MinLoc = Kokkos::MinLoc<double, int>;

/// x += v: an atomic add when elements adding into the same x may run at once, else plain.
template <bool Atomic>
KOKKOS_INLINE_FUNCTION void scatter_add(double& x, double v) {
  if constexpr (Atomic)
    Kokkos::atomic_add(&x, v);
  else
    x += v;
}

using ChunkPolicy = Kokkos::RangePolicy<ExecSpace, Kokkos::Schedule<Kokkos::Dynamic>>;

/// f.element<Atomic>(k) for every element k < ne: one parallel_for over all elements with
/// atomic adds, or one per colour (in colour order) over its chunks with plain adds (a chunk's
/// elements in ascending order, by one thread; dynamic schedule: chunks cost alike but threads
/// may not run alike).
template <class F>
void for_each_element(const char* label, const F& f, const Colouring& colouring, Scatter how,
                      int ne) {
  if (how == Scatter::atomic) {
    Kokkos::parallel_for(
        label, Kokkos::RangePolicy<ExecSpace>(0, ne),
        KOKKOS_LAMBDA(const int k) { f.template element<true>(k); });
    return;
  }
  const ChunkList cl = colouring.list;
  for (int c = 0; c < colouring.colours(); ++c)
    Kokkos::parallel_for(
        label, ChunkPolicy(colouring.begin(c), colouring.end(c)), KOKKOS_LAMBDA(const int i) {
          for (int k = cl.first(i); k < cl.last(i); ++k) f.template element<false>(k);
        });
}

/// The same with a MinLoc reduction of f.element<Atomic>(k, mn) (min over all elements, its
/// element id in loc; loc = -1 if ne = 0).
template <class F>
MinLoc::value_type reduce_elements(const char* label, const F& f, const Colouring& colouring,
                                   Scatter how, int ne) {
  MinLoc::value_type worst;
  worst.val = Kokkos::reduction_identity<double>::min();
  worst.loc = -1;
  if (how == Scatter::atomic) {
    if (ne > 0)
      Kokkos::parallel_reduce(
          label, Kokkos::RangePolicy<ExecSpace>(0, ne),
          KOKKOS_LAMBDA(const int k, MinLoc::value_type& mn) { f.template element<true>(k, mn); },
          MinLoc(worst));
    return worst;
  }
  const ChunkList cl = colouring.list;
  for (int c = 0; c < colouring.colours(); ++c) {
    MinLoc::value_type w;
    Kokkos::parallel_reduce(
        label, ChunkPolicy(colouring.begin(c), colouring.end(c)),
        KOKKOS_LAMBDA(const int i, MinLoc::value_type& mn) {
          for (int k = cl.first(i); k < cl.last(i); ++k) f.template element<false>(k, mn);
        },
        MinLoc(w));
    if (w.val < worst.val) worst = w;  // the smallest over the colours (min is exact)
  }
  return worst;
}

}  // namespace emc::fem
