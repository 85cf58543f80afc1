#pragma once
// Loops that apply the local-model kernels (fem/elasticity_kernel.hpp) over the
// mesh (THEORY §1, §4). Element blocks are computed in parallel (OpenMP) in
// chunks and inserted in cell order, so the assembled matrix is bit-identical
// for any thread count (STYLE.md habit 7).

#include "perimorph/assembly/inserter.hpp"
#include "perimorph/fem/quadrature.hpp"

#include <functional>
#include <span>
#include <vector>

namespace perimorph::mesh {
class Mesh;
struct CellFace;
}  // namespace perimorph::mesh
namespace perimorph::dofs {
class DofMap;
}
namespace perimorph::fem {
class ConstitutiveField;
}

namespace perimorph::assembly {

/// What the local loops need to know about the discretization. A view: the
/// references and the span are non-owning.
struct LocalSpace {
  const mesh::Mesh& mesh;                      ///< non-owning
  const dofs::DofMap& dofmap;                  ///< non-owning
  std::span<const fem::QuadraturePoint> rule;  ///< reference-cell rule (matches the ConstitutiveField)
  double scale = 1.0;                          ///< thickness in 2D, cross-section area in 1D, 1 in 3D
};

/// K += Σ_cells ∫ Bᵀ C(x) B over the cells for which `include(c)` holds (all
/// if empty).
void assemble_elasticity(const LocalSpace& space, const fem::ConstitutiveField& C, MatrixInserter& K,
                         const std::function<bool(Index)>& include = {});

/// F += ∫ N b(x) dx over every cell (b: force per volume, mesh coordinates).
/// A DG degree 0 cell (one node, N ≡ 1) takes the whole load of its volume.
void assemble_body_force(const LocalSpace& space, const std::function<Vec3(const Vec3&)>& b,
                         std::span<double> F);

/// F += ∫ N t dS over the given faces for a constant traction t (force per area;
/// per length in 2D before the thickness scale). A face of a DG degree 0 cell
/// puts its whole load on the cell's one node.
void assemble_traction(const LocalSpace& space, std::span<const mesh::CellFace> faces, const Vec3& t,
                       std::span<double> F);

/// Volume-weighted cell averages of the strain and of the local stress
/// σ = C(x) : ε (Voigt, engineering shear; voigt_size(dim) values per cell)
/// for the displacement u (dof vector). DG degree 0 cells are left at 0.
struct CellFields {
  std::vector<double> strain, stress;
  std::vector<double> energy_density;  ///< 1/2 σ:ε averaged over the cell
};
/// The fields of the listed `cells`, in their order (k-th cell's values at
/// k · voigt_size(dim)), or with no list of every cell in order. A process's
/// piece of the output lists its cells: its arrays are as long as its piece.
CellFields cell_strain_stress(const LocalSpace& space, const fem::ConstitutiveField& C,
                              std::span<const double> u, std::span<const Index> cells = {});

/// The strain (voigt_size(dim) values per point, point-major) and the volume
/// weight w|J|·scale at every point of `space.rule` in cell c (a Q1 cell: not
/// a DG degree 0 one) for the dof vector u. No allocation.
void strains_at_points(const LocalSpace& space, Index c, std::span<const double> u, std::span<double> strain,
                       std::span<double> volume);

/// Strain at point ξ of cell c for the dof vector u (voigt_size(dim) values).
std::vector<double> strain_at(const LocalSpace& space, Index c, const Vec3& xi, std::span<const double> u);

}  // namespace perimorph::assembly
