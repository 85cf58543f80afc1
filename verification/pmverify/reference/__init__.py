"""Independent numpy physics, written from THEORY.md: the figures the program is checked against.

Nothing here calls or shares code with perimorph. Modules:
  kernels     radial kernels, their moments, the continuum calibration (THEORY §2), G_c closed forms (§5)
  quadrature  Gauss–Legendre points of a structured box mesh (THEORY §4)
  alpha       α profiles and shapes (THEORY §3.1)
  cut         the closed pre-crack cut: which segments cross it (THEORY §4, tie rule of mesh::Cut)
"""
