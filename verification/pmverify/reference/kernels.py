"""Radial kernels c(r) = ĉ φ(r) of THEORY §1.1, their moments, the continuum calibration of ĉ (THEORY §2)
and the bulk G_c closed forms (THEORY §5), by Gauss–Legendre quadrature on [0, δ] (exact to round-off for
these smooth integrands with 200 points)."""

import math

import numpy as np


def phi(kernel, r, length=None, horizon=None):
    """φ(r) = c(r)/ĉ for r < δ (the caller applies the cut-off)."""
    r = np.asarray(r, dtype=float)
    if kernel == "constant":
        return np.ones_like(r)
    if kernel == "conical":
        return 1.0 - r / horizon
    if kernel == "exponential":
        return r**2 * np.exp(-r / length)
    if kernel == "gaussian":
        return r**2 * np.exp(-(r / length) ** 2)
    raise ValueError(f"unknown kernel {kernel!r}")


def moment(kernel, p, horizon, length=None, points=200):
    """∫₀^δ φ(r) r^p dr."""
    x, w = np.polynomial.legendre.leggauss(points)
    r = 0.5 * horizon * (x + 1)
    return 0.5 * horizon * float(np.sum(w * r**p * phi(kernel, r, length, horizon)))


def lame_per_c_hat(dim, kernel, horizon, length=None):
    """λ = μ of the kernel with ĉ = 1 (THEORY §2): 3D (2π/15) ∫ φ r⁴, 2D (π/8) ∫ φ r³; 1D: E = ∫ φ r²."""
    if dim == 3:
        return 2 * math.pi / 15 * moment(kernel, 4, horizon, length)
    if dim == 2:
        return math.pi / 8 * moment(kernel, 3, horizon, length)
    return moment(kernel, 2, horizon, length)


def c_hat(dim, kernel, horizon, E, length=None, plane="strain", thickness=1.0):
    """The continuum calibration of ĉ for Young's modulus E (THEORY §2): 3D and plane strain E = 5μ/2,
    plane stress E = 8μ/3, 1D E = ∫ c r² dr (per unit cross-section). `thickness` is not used: the 2D
    micromodulus is per unit thickness."""
    if dim == 1:
        return E / lame_per_c_hat(1, kernel, horizon, length)
    mu = E / (8 / 3 if (dim == 2 and plane == "stress") else 5 / 2)
    return mu / lame_per_c_hat(dim, kernel, horizon, length)


def gc_factor(dim, kernel, horizon, c_hat_value, length=None):
    """κ of the bulk closed form G_c = κ s_crit² (THEORY §5): 3D (π/2) ∫ c r⁵, 2D ∫ c r⁴, 1D ½ ∫ c r³."""
    p, f = {3: (5, math.pi / 2), 2: (4, 1.0), 1: (3, 0.5)}[dim]
    return f * c_hat_value * moment(kernel, p, horizon, length)
