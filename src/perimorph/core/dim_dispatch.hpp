#pragma once
// Calls a generic lambda with the space dimension as a compile-time constant:
//   dispatch_dim(mesh.dim(), [&](auto D) { return kernel<D()>(...); });
// 1 and 2 map to themselves, anything else to 3.

#include <type_traits>
#include <utility>

namespace perimorph {

template <class F>
decltype(auto) dispatch_dim(int dim, F&& f) {
  switch (dim) {
    case 1:
      return std::forward<F>(f)(std::integral_constant<int, 1>{});
    case 2:
      return std::forward<F>(f)(std::integral_constant<int, 2>{});
    default:
      return std::forward<F>(f)(std::integral_constant<int, 3>{});
  }
}

}  // namespace perimorph
