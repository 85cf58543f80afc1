#include "perimorph/la/shell_matrix.hpp"

#include "perimorph/la/petsc_check.hpp"

#include <petscmat.h>

#include <utility>
#include <vector>

namespace perimorph::la {

/// What a product needs: the callback and, spread over processes, the
/// gathering of x and the map between the numberings.
struct ShellMatrix::Context {
  Apply apply;
  std::shared_ptr<const Distribution> distribution;  ///< null on one process
  int block_size = 1;
  VecScatter to_all = nullptr;  ///< x → every process (distributed numbering)
  Vec all = nullptr;
  std::vector<double> x, y;  ///< whole, assembly numbering
  ~Context() {
    if (to_all) VecScatterDestroy(&to_all);
    if (all) VecDestroy(&all);
  }
};

namespace {

PetscErrorCode shell_mult(Mat A, Vec x, Vec y) {
  void* ctx = nullptr;
  PetscCall(MatShellGetContext(A, &ctx));
  auto& c = *static_cast<ShellMatrix::Context*>(ctx);
  if (!c.distribution) {
    PetscInt n = 0;
    PetscCall(VecGetLocalSize(x, &n));
    const PetscScalar* xa = nullptr;
    PetscScalar* ya = nullptr;
    PetscCall(VecGetArrayRead(x, &xa));
    PetscCall(VecGetArrayWrite(y, &ya));
    c.apply(std::span<const double>(xa, static_cast<std::size_t>(n)),
            std::span<double>(ya, static_cast<std::size_t>(n)));
    PetscCall(VecRestoreArrayWrite(y, &ya));
    PetscCall(VecRestoreArrayRead(x, &xa));
    return 0;
  }
  const Distribution& d = *c.distribution;
  const Index bs = c.block_size;
  if (!c.to_all) PetscCall(VecScatterCreateToAll(x, &c.to_all, &c.all));
  PetscCall(VecScatterBegin(c.to_all, x, c.all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(c.to_all, x, c.all, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar* xa = nullptr;
  PetscCall(VecGetArrayRead(c.all, &xa));
  const auto n = static_cast<std::size_t>(d.num_nodes() * bs);
  c.x.resize(n);
  c.y.assign(n, 0.0);
  for (Index node = 0; node < d.num_nodes(); ++node)
    for (Index k = 0; k < bs; ++k)
      c.x[static_cast<std::size_t>(node * bs + k)] =
          xa[d.to_distributed[static_cast<std::size_t>(node)] * bs + k];
  PetscCall(VecRestoreArrayRead(c.all, &xa));
  c.apply(c.x, c.y);
  PetscScalar* ya = nullptr;
  PetscCall(VecGetArrayWrite(y, &ya));
  for (Index node = 0; node < d.num_nodes(); ++node) {
    if (!d.owns(node)) continue;
    const Index at = (d.to_distributed[static_cast<std::size_t>(node)] - d.begin) * bs;
    for (Index k = 0; k < bs; ++k) ya[at + k] = c.y[static_cast<std::size_t>(node * bs + k)];
  }
  PetscCall(VecRestoreArrayWrite(y, &ya));
  return 0;
}

}  // namespace

ShellMatrix::ShellMatrix(Index size, int block_size, Apply apply)
    : ShellMatrix(nullptr, block_size, std::move(apply), size) {}

ShellMatrix::ShellMatrix(std::shared_ptr<const Distribution> distribution, int block_size, Apply apply)
    : ShellMatrix(distribution, block_size, std::move(apply), distribution->num_nodes() * block_size) {}

ShellMatrix::ShellMatrix(std::shared_ptr<const Distribution> distribution, int block_size, Apply apply,
                         Index size)
    : size_(size), context_(std::make_unique<Context>()) {
  context_->apply = std::move(apply);
  context_->distribution = std::move(distribution);
  context_->block_size = block_size;
  const Index local = context_->distribution ? context_->distribution->owned_nodes() * block_size : size;
  PM_PETSC(MatCreateShell(PETSC_COMM_WORLD, local, local, size, size, context_.get(), &m_));
  PM_PETSC(MatSetBlockSize(m_, block_size));
  PM_PETSC(MatShellSetOperation(m_, MATOP_MULT, reinterpret_cast<void (*)(void)>(&shell_mult)));
  PM_PETSC(MatSetOption(m_, MAT_SYMMETRIC, PETSC_TRUE));
}

ShellMatrix::~ShellMatrix() {
  if (m_) MatDestroy(&m_);
}

ShellMatrix::ShellMatrix(ShellMatrix&& other) noexcept
    : m_(std::exchange(other.m_, nullptr)), size_(other.size_), context_(std::move(other.context_)) {}

ShellMatrix& ShellMatrix::operator=(ShellMatrix&& other) noexcept {
  if (this != &other) {
    if (m_) MatDestroy(&m_);
    m_ = std::exchange(other.m_, nullptr);
    size_ = other.size_;
    context_ = std::move(other.context_);
  }
  return *this;
}

void ShellMatrix::mult(const Vector& x, Vector& y) const {
  PM_PETSC(MatMult(m_, x.read_handle(), y.handle()));
}

}  // namespace perimorph::la
