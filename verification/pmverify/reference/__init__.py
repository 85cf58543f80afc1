"""Independent numpy physics, written from THEORY.md: the figures the program is checked against.

Nothing here calls or shares code with perimorph. Modules:
  kernels     radial kernels, their moments, the continuum calibration (THEORY §2), G_c closed forms (§5)
  quadrature  Gauss–Legendre points of a structured box mesh (THEORY §4)
  alpha       α profiles and shapes (THEORY §3.1)
  cut         the closed pre-crack cut: which segments cross it (THEORY §4, tie rule of mesh::Cut)
  bar_1d      B1's continuum ghost forces F_g, f_g of the 1D bar (THEORY §3.2) and the discrete bar moduli
  anisotropy  orthotropic / transversely isotropic stiffness and the maps C → Y (THEORY §2.1), rotations
  ghost_force the residual K u of u = ε x on a Q1 box mesh, 2D and 3D, morphing or partition (THEORY §3.2, §4)
"""
