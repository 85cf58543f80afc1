#pragma once
// The local damage law of THEORY §6 (thesis (3.35)–(3.41)) as a pure kernel:
// strain and damage history in; damage force, new damage, stress, tangent and
// dissipation out. No I/O, no allocation. Voigt vectors of the model's
// dimension (engineering shear), C₀ column-major nv × nv.
//
//   σ = [(1 − d_c) C₀ + (d_c − d) C₀] : ε = (1 − d) C₀ : ε   (residual + damageable branch)
//   Y = ½ ε : C₀ : ε                                        (3.40; = ½Λ tr(ε)² + Λ tr(ε²) for λ = μ = Λ)
//   f = Y − (k1 d + k0) ≤ 0,   d = min(d_c, max(d_prev, (Y − k0)/k1))   (3.39), (3.41)
//
// The threshold is on the path, so the energy dissipated to reach d from 0 is
// ∫₀^d (k0 + k1 s) ds = k0 d + ½ k1 d², whatever the loading path.

#include <algorithm>

namespace perimorph::fem {

struct DamageLaw {
  double k0 = 0.0;   ///< damage-force threshold at onset, ≥ 0
  double k1 = 1.0;   ///< hardening modulus of the threshold, > 0
  double d_c = 1.0;  ///< critical damage, 0 < d_c ≤ 1
};

/// Y = ½ εᵀ C₀ ε (nv Voigt components).
inline double damage_force(const double* C0, const double* strain, int nv) {
  double y = 0.0;
  for (int j = 0; j < nv; ++j) {
    double Ce = 0.0;
    for (int i = 0; i < nv; ++i) Ce += C0[i + j * nv] * strain[i];  // C₀ symmetric: column j = row j
    y += Ce * strain[j];
  }
  return 0.5 * y;
}

/// The damage after a step to damage force Y from `d_prev` (3.41):
/// irreversible, capped at d_c, unchanged below the threshold.
inline double updated_damage(const DamageLaw& law, double Y, double d_prev) {
  return std::min(law.d_c, std::max(d_prev, (Y - law.k0) / law.k1));
}

/// Energy per volume dissipated to bring the damage from 0 to d along the
/// threshold: k0 d + ½ k1 d².
inline double damage_dissipation(const DamageLaw& law, double d) {
  return law.k0 * d + 0.5 * law.k1 * d * d;
}

/// σ = (1 − d) C₀ ε (`stress`: nv values).
inline void damaged_stress(const double* C0, const double* strain, double d, int nv, double* stress) {
  for (int i = 0; i < nv; ++i) {
    double s = 0.0;
    for (int j = 0; j < nv; ++j) s += C0[i + j * nv] * strain[j];
    stress[i] = (1.0 - d) * s;
  }
}

/// True if the step from d_prev to Y is on the loading branch, where d grows
/// with Y: (Y − k0)/k1 > d_prev and below d_c.
inline bool damage_loading(const DamageLaw& law, double Y, double d_prev) {
  const double trial = (Y - law.k0) / law.k1;
  return trial > d_prev && trial < law.d_c;
}

/// The consistent tangent dσ/dε (column-major nv × nv) at strain ε after the
/// update from d_prev: (1 − d) C₀, minus (C₀ε)(C₀ε)ᵀ / k1 on the loading
/// branch (∂d/∂ε = C₀ε / k1 there, 0 otherwise).
inline void damage_tangent(const DamageLaw& law, const double* C0, const double* strain, double d_prev,
                           int nv, double* tangent) {
  const double Y = damage_force(C0, strain, nv);
  const double d = updated_damage(law, Y, d_prev);
  for (int k = 0; k < nv * nv; ++k) tangent[k] = (1.0 - d) * C0[k];
  if (!damage_loading(law, Y, d_prev)) return;
  double Ce[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < nv; ++i)
    for (int j = 0; j < nv; ++j) Ce[i] += C0[i + j * nv] * strain[j];
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nv; ++i) tangent[i + j * nv] -= Ce[i] * Ce[j] / law.k1;
}

}  // namespace perimorph::fem
