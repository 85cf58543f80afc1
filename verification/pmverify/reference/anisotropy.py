"""Anisotropic central-force materials (THEORY §2.1), independently of the program.

Stiffness tensors are 6 × 6 in Voigt order xx, yy, zz, yz, xz, xy (tensor components C_ijkl, acting on
engineering shear strains; C[3, 3] = C2323 ...). The micromodulus is c(ξ) = c_r(|ξ|) Y(e), e = ξ/|ξ|, with
the angular part Y expanded in real spherical harmonics (θ from e3, φ the azimuth in the e1–e2 plane) and
its coefficients given by THEORY §2.1's maps C → a with R4 = ∫₀^δ c_r(r) r⁴ dr. The round trip
C → a → (2.8) integrated over the sphere → C is `bulk_tensor`.
"""

import math

import numpy as np

VOIGT = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]


# ---------------------------------------------------------------------- engineering constants → C
def isotropic_stiffness(E, nu=0.25):
    lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    C = np.zeros((6, 6))
    C[:3, :3] = lam
    C[range(3), range(3)] = lam + 2 * mu
    C[range(3, 6), range(3, 6)] = mu
    return C


def normal_compliance(E1, E2, E3, nu12, nu13, nu23):
    """The normal block of the compliance (S_ij = −ν_ij/E_i, ν_ij the contraction along j under a uniaxial
    stress along i, ν_ij/E_i = ν_ji/E_j)."""
    return np.array([[1 / E1, -nu12 / E1, -nu13 / E1],
                     [-nu12 / E1, 1 / E2, -nu23 / E2],
                     [-nu13 / E1, -nu23 / E2, 1 / E3]])


def orthotropic_stiffness(E1, E2, E3, nu12, nu13, nu23):
    """The central-force orthotropic stiffness: the normal block is the inverse of the normal compliance,
    the shear moduli follow from the Cauchy relations C2323 = C2233, C1313 = C1133, C1212 = C1122."""
    Cn = np.linalg.inv(normal_compliance(E1, E2, E3, nu12, nu13, nu23))
    C = np.zeros((6, 6))
    C[:3, :3] = Cn
    C[3, 3], C[4, 4], C[5, 5] = Cn[1, 2], Cn[0, 2], Cn[0, 1]
    return C


def ti_in_plane_poisson(E_in, E_axis, nu_axial):
    """ν_in that central forces impose on a transversely isotropic material (C1122 = C1111/3, (2.88)):
    with ν31 = ν_axial E_axis/E_in, C1122/C1111 = (ν_in + ν13 ν31)/(1 − ν13 ν31) = 1/3."""
    p = nu_axial * nu_axial * E_axis / E_in
    return (1 - 4 * p) / 3


def transversely_isotropic_stiffness(E_in, E_axis, nu_axial):
    """The central-force stiffness transversely isotropic about e3 (ν_in from ti_in_plane_poisson)."""
    return orthotropic_stiffness(E_in, E_in, E_axis, ti_in_plane_poisson(E_in, E_axis, nu_axial), nu_axial, nu_axial)


def cauchy_defects(C):
    """C2323 − C2233, C1313 − C1133, C1212 − C1122 relative to max |C|: zero for a central-force material."""
    s = np.max(np.abs(C))
    return {"2323-2233": (C[3, 3] - C[1, 2]) / s, "1313-1133": (C[4, 4] - C[0, 2]) / s,
            "1212-1122": (C[5, 5] - C[0, 1]) / s}


# ---------------------------------------------------------------------- C → Y (THEORY §2.1)
def orthotropic_coefficients(C, R4):
    """a00, a20, a22, a40, a42, a44 from C1111, C2222, C3333, C1122, C1133, C2233."""
    C11, C22, C33, C12, C13, C23 = C[0, 0], C[1, 1], C[2, 2], C[0, 1], C[0, 2], C[1, 2]
    pi = math.pi
    return {"a00": (C11 + C22 + C33 + 2 * C12 + 2 * C13 + 2 * C23) / (2 * pi * R4),
            "a20": -5 * (C11 + C22 + 2 * C12 - C13 - C23 - 2 * C33) / (4 * pi * R4),
            "a22": 5 * (C11 - C22 + C13 - C23) / (8 * pi * R4),
            "a40": 9 * (3 * C11 + 3 * C22 + 8 * C33 + 6 * C12 - 24 * C13 - 24 * C23) / (16 * pi * R4),
            "a42": -3 * (C11 - C22 - 6 * C13 + 6 * C23) / (16 * pi * R4),
            "a44": 3 * (C11 + C22 - 6 * C12) / (128 * pi * R4)}


def ti_coefficients(C, R4):
    """a0, a2, a4 (transversely isotropic about e3) from C1111, C1133, C3333; δ⁵ of (2.84)–(2.86) → 5 R4."""
    C11, C13, C33 = C[0, 0], C[0, 2], C[2, 2]
    d5 = 5 * R4
    return {"a0": 5 * (8 * C11 + 12 * C13 + 3 * C33) / (6 * math.pi * d5),
            "a2": -25 * (4 * C11 - 3 * C13 - 3 * C33) / (6 * math.pi * d5),
            "a4": 45 * (C11 - 6 * C13 + C33) / (2 * math.pi * d5)}


def y_value(a, e):
    """Y at unit directions e (N, 3) in material axes, for orthotropic (a00 ...) or transversely isotropic
    (a0, a2, a4) coefficients. Cartesian forms: x = cos θ = e3, (1 − x²) cos 2φ = e1² − e2²,
    (1 − x²)² cos 4φ = (e1² − e2²)² − 4 e1² e2²."""
    e = np.asarray(e, float)
    x2 = e[:, 2] ** 2
    P20 = (3 * x2 - 1) / 2
    P40 = (35 * x2**2 - 30 * x2 + 3) / 8
    if "a0" in a:
        return a["a0"] + a["a2"] * P20 + a["a4"] * P40
    d = e[:, 0] ** 2 - e[:, 1] ** 2
    p = e[:, 0] * e[:, 1]
    return (a["a00"] + a["a20"] * P20 + a["a22"] * 3 * d + a["a40"] * P40 + a["a42"] * 7.5 * (7 * x2 - 1) * d
            + a["a44"] * 105 * (d**2 - 4 * p**2))


def amplitude(a, R=None):
    """Y as a callable of unit directions in mesh axes; R: the material axes as the columns of a rotation
    (e_material = Rᵀ e_mesh), None for material axes = mesh axes."""
    if R is None:
        return lambda e: y_value(a, e)
    R = np.asarray(R, float)
    return lambda e: y_value(a, np.asarray(e, float) @ R)


# ---------------------------------------------------------------------- Y → C, rotations
def sphere_rule(n_theta=48, n_phi=96):
    """Unit vectors (N, 3) and weights summing to 4π: Gauss–Legendre in cos θ, midpoint rule in φ."""
    x, w = np.polynomial.legendre.leggauss(n_theta)
    ph = (np.arange(n_phi) + 0.5) * 2 * math.pi / n_phi
    X, P = np.meshgrid(x, ph, indexing="ij")
    s = np.sqrt(1 - X**2)
    n = np.stack([s * np.cos(P), s * np.sin(P), X], axis=-1).reshape(-1, 3)
    return n, np.outer(w, np.full(n_phi, 2 * math.pi / n_phi)).reshape(-1)


def bulk_tensor(Y, R4):
    """C_ijkl = (R4/2) ∮ Y(n) n_i n_j n_k n_l dS (THEORY (2.8) with c = Y(e) c_r(r)), Voigt 6 × 6."""
    n, W = sphere_rule()
    f = 0.5 * R4 * W * Y(n)
    C = np.empty((6, 6))
    for A, (p, q) in enumerate(VOIGT):
        for B, (s, t) in enumerate(VOIGT):
            C[A, B] = np.sum(f * n[:, p] * n[:, q] * n[:, s] * n[:, t])
    return C


def full_tensor(C):
    """Voigt 6 × 6 → C_ijkl (3, 3, 3, 3)."""
    idx = {}
    for A, (i, j) in enumerate(VOIGT):
        idx[(i, j)] = idx[(j, i)] = A
    T = np.empty((3, 3, 3, 3))
    for i, j, k, l in np.ndindex(3, 3, 3, 3):
        T[i, j, k, l] = C[idx[(i, j)], idx[(k, l)]]
    return T


def rotate(C, R):
    """The Voigt stiffness in mesh axes of a material whose axes are the columns of the rotation R."""
    T = np.einsum("ia,jb,kc,ld,abcd->ijkl", R, R, R, R, full_tensor(C))
    return np.array([[T[i, j, k, l] for k, l in VOIGT] for i, j in VOIGT])


def rotation(axis, angle):
    """Rotation matrix about `axis` by `angle` (radians), Rodrigues."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K
