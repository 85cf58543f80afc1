#include "perimorph/assembly/local_assembly.hpp"

#include "perimorph/core/dim_dispatch.hpp"
#include "perimorph/core/error.hpp"
#include "perimorph/dofs/dof_map.hpp"
#include "perimorph/fem/constitutive_field.hpp"
#include "perimorph/fem/elasticity_kernel.hpp"
#include "perimorph/mesh/mesh.hpp"

#include <array>

namespace perimorph::assembly {

namespace {

constexpr Index chunk_size = 512;

template <int D>
fem::NodeCoords<D> cell_coordinates(const mesh::Mesh& mesh, Index c) {
  fem::NodeCoords<D> X;
  const auto nodes = mesh.cell(c);
  for (int a = 0; a < fem::q1_nodes<D>; ++a)
    X.col(a) = mesh.node(nodes[static_cast<std::size_t>(a)]).template head<D>();
  return X;
}

template <int D>
std::array<Index, fem::element_dofs<D>> cell_dofs(const dofs::DofMap& dofmap, Index c) {
  std::array<Index, fem::element_dofs<D>> dofs{};
  const auto nodes = dofmap.cell_nodes(c);
  for (int a = 0; a < fem::q1_nodes<D>; ++a)
    for (int d = 0; d < D; ++d)
      dofs[static_cast<std::size_t>(a * D + d)] = nodes[static_cast<std::size_t>(a)] * D + d;
  return dofs;
}

template <int D>
void assemble_elasticity_dim(const LocalSpace& s, const fem::ConstitutiveField& C, MatrixInserter& K,
                             const std::function<bool(Index)>& include) {
  PERIMORPH_ASSERT(C.points_per_cell() == static_cast<int>(s.rule.size()),
                   "rule and constitutive field disagree");
  const Index ncells = s.mesh.num_cells();
  std::vector<fem::ElementMatrix<D>> blocks(static_cast<std::size_t>(chunk_size));
  std::vector<char> used(static_cast<std::size_t>(chunk_size));
  for (Index first = 0; first < ncells; first += chunk_size) {
    const Index last = std::min(ncells, first + chunk_size);
#pragma omp parallel for schedule(static)
    for (Index c = first; c < last; ++c) {
      const auto k = static_cast<std::size_t>(c - first);
      used[k] = !include || include(c);
      if (!used[k]) continue;
      fem::elasticity_stiffness<D>(
          cell_coordinates<D>(s.mesh, c), s.rule, [&](int q) { return C.at(c, q); }, s.scale, blocks[k]);
    }
    for (Index c = first; c < last; ++c) {
      const auto k = static_cast<std::size_t>(c - first);
      if (!used[k]) continue;
      const auto dofs = cell_dofs<D>(s.dofmap, c);
      // Eigen is column-major; the inserter takes row-major blocks. K_e is symmetric.
      K.add(dofs, dofs,
            std::span<const double>(blocks[k].data(), static_cast<std::size_t>(blocks[k].size())));
    }
  }
}

template <int D>
void assemble_body_force_dim(const LocalSpace& s, const std::function<Vec3(const Vec3&)>& b,
                             std::span<double> F) {
  fem::ElementVector<D> f;
  for (Index c = 0; c < s.mesh.num_cells(); ++c) {
    fem::body_force_load<D>(cell_coordinates<D>(s.mesh, c), s.rule, b, s.scale, f);
    const auto nodes = s.dofmap.cell_nodes(c);
    // Q1 nodes, or the one node of a DG degree 0 cell (N ≡ 1: the sum of the Q1 loads).
    const int n = static_cast<int>(nodes.size());
    for (int a = 0; a < fem::q1_nodes<D>; ++a)
      for (int d = 0; d < D; ++d)
        F[static_cast<std::size_t>(nodes[static_cast<std::size_t>(n == 1 ? 0 : a)] * D + d)] += f[a * D + d];
  }
}

template <int D>
void assemble_traction_dim(const LocalSpace& s, std::span<const mesh::CellFace> faces, const Vec3& t,
                           std::span<double> F) {
  constexpr int nf = fem::q1_nodes<D - 1>;
  const int n1d =
      std::max(1, static_cast<int>(std::lround(std::pow(static_cast<double>(s.rule.size()), 1.0 / D))));
  std::vector<fem::QuadraturePoint> face_rule =
      D == 1 ? std::vector<fem::QuadraturePoint>{{Vec3::Zero(), 1.0}} : fem::gauss_legendre(D - 1, n1d);
  for (const mesh::CellFace& cf : faces) {
    const auto local = mesh::face_nodes(s.mesh.cell_type(), cf.face);
    Eigen::Matrix<double, 3, nf> Y;
    for (int a = 0; a < nf; ++a)
      Y.col(a) =
          s.mesh.node(s.mesh.cell(cf.cell)[static_cast<std::size_t>(local[static_cast<std::size_t>(a)])]);
    const auto f = fem::face_traction_load<D>(Y, face_rule, t, s.scale);
    const auto nodes = s.dofmap.cell_nodes(cf.cell);
    // The face's Q1 nodes, or the one node of a DG degree 0 cell (N ≡ 1: the whole face load).
    for (int a = 0; a < nf; ++a) {
      const Index node =
          nodes.size() == 1 ? nodes[0] : nodes[static_cast<std::size_t>(local[static_cast<std::size_t>(a)])];
      for (int d = 0; d < D; ++d) F[static_cast<std::size_t>(node * D + d)] += f[a * D + d];
    }
  }
}

template <int D>
fem::ElementVector<D> gather(const dofs::DofMap& dofmap, Index c, std::span<const double> u) {
  fem::ElementVector<D> ue;
  const auto dofs = cell_dofs<D>(dofmap, c);
  for (int i = 0; i < fem::element_dofs<D>; ++i)
    ue[i] = u[static_cast<std::size_t>(dofs[static_cast<std::size_t>(i)])];
  return ue;
}

template <int D>
CellFields cell_strain_stress_dim(const LocalSpace& s, const fem::ConstitutiveField& C,
                                  std::span<const double> u, std::span<const Index> cells) {
  constexpr int nv = fem::voigt_dim<D>;
  const Index count = cells.empty() ? s.mesh.num_cells() : static_cast<Index>(cells.size());
  CellFields out;
  out.strain.assign(static_cast<std::size_t>(count * nv), 0.0);
  out.stress.assign(static_cast<std::size_t>(count * nv), 0.0);
  out.energy_density.assign(static_cast<std::size_t>(count), 0.0);
#pragma omp parallel for schedule(static)
  for (Index k = 0; k < count; ++k) {
    const Index c = cells.empty() ? k : cells[static_cast<std::size_t>(k)];
    // DG degree 0 cells have no strain of their own (constant displacement): left 0.
    if (static_cast<int>(s.dofmap.cell_nodes(c).size()) != fem::q1_nodes<D>) continue;
    const auto X = cell_coordinates<D>(s.mesh, c);
    const auto ue = gather<D>(s.dofmap, c, u);
    fem::VoigtVector<D> eps_sum = fem::VoigtVector<D>::Zero(), sig_sum = fem::VoigtVector<D>::Zero();
    double vol = 0.0, energy = 0.0;
    fem::ShapeGradients<D> g;
    for (std::size_t q = 0; q < s.rule.size(); ++q) {
      const double dv = s.rule[q].weight * fem::q1_physical_gradients<D>(X, s.rule[q].xi, g);
      const fem::VoigtVector<D> eps = fem::strain_displacement<D>(g) * ue;
      const fem::VoigtVector<D> sig =
          Eigen::Map<const fem::VoigtMatrix<D>>(C.at(c, static_cast<int>(q))) * eps;
      eps_sum += eps * dv;
      sig_sum += sig * dv;
      energy += 0.5 * sig.dot(eps) * dv;
      vol += dv;
    }
    for (int i = 0; i < nv; ++i) {
      out.strain[static_cast<std::size_t>(k * nv + i)] = eps_sum[i] / vol;
      out.stress[static_cast<std::size_t>(k * nv + i)] = sig_sum[i] / vol;
    }
    out.energy_density[static_cast<std::size_t>(k)] = energy / vol;
  }
  return out;
}

template <int D>
std::vector<double> strain_at_dim(const LocalSpace& s, Index c, const Vec3& xi, std::span<const double> u) {
  fem::ShapeGradients<D> g;
  fem::q1_physical_gradients<D>(cell_coordinates<D>(s.mesh, c), xi, g);
  const fem::VoigtVector<D> eps = fem::strain_displacement<D>(g) * gather<D>(s.dofmap, c, u);
  return {eps.data(), eps.data() + fem::voigt_dim<D>};
}

template <int D>
void strains_at_points_dim(const LocalSpace& s, Index c, std::span<const double> u, std::span<double> strain,
                           std::span<double> volume) {
  const fem::NodeCoords<D> X = cell_coordinates<D>(s.mesh, c);
  const fem::ElementVector<D> ue = gather<D>(s.dofmap, c, u);
  fem::ShapeGradients<D> g;
  for (std::size_t q = 0; q < s.rule.size(); ++q) {
    const double detJ = fem::q1_physical_gradients<D>(X, s.rule[q].xi, g);
    const fem::VoigtVector<D> eps = fem::strain_displacement<D>(g) * ue;
    for (int k = 0; k < fem::voigt_dim<D>; ++k)
      strain[q * fem::voigt_dim<D> + static_cast<std::size_t>(k)] = eps[k];
    volume[q] = s.rule[q].weight * detJ * s.scale;
  }
}

}  // namespace

void strains_at_points(const LocalSpace& space, Index c, std::span<const double> u, std::span<double> strain,
                       std::span<double> volume) {
  dispatch_dim(space.mesh.dim(), [&](auto D) { strains_at_points_dim<D()>(space, c, u, strain, volume); });
}

void assemble_elasticity(const LocalSpace& space, const fem::ConstitutiveField& C, MatrixInserter& K,
                         const std::function<bool(Index)>& include) {
  dispatch_dim(space.mesh.dim(), [&](auto D) { assemble_elasticity_dim<D()>(space, C, K, include); });
}

void assemble_body_force(const LocalSpace& space, const std::function<Vec3(const Vec3&)>& b,
                         std::span<double> F) {
  dispatch_dim(space.mesh.dim(), [&](auto D) { assemble_body_force_dim<D()>(space, b, F); });
}

void assemble_traction(const LocalSpace& space, std::span<const mesh::CellFace> faces, const Vec3& t,
                       std::span<double> F) {
  dispatch_dim(space.mesh.dim(), [&](auto D) { assemble_traction_dim<D()>(space, faces, t, F); });
}

CellFields cell_strain_stress(const LocalSpace& space, const fem::ConstitutiveField& C,
                              std::span<const double> u, std::span<const Index> cells) {
  return dispatch_dim(space.mesh.dim(),
                      [&](auto D) { return cell_strain_stress_dim<D()>(space, C, u, cells); });
}

std::vector<double> strain_at(const LocalSpace& space, Index c, const Vec3& xi, std::span<const double> u) {
  return dispatch_dim(space.mesh.dim(), [&](auto D) { return strain_at_dim<D()>(space, c, xi, u); });
}

}  // namespace perimorph::assembly
