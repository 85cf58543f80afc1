#include "perimorph/la/shell_matrix.hpp"

#include "perimorph/la/node_gather.hpp"
#include "perimorph/la/petsc_check.hpp"

#include <petscmat.h>

#include <optional>
#include <utility>
#include <vector>

namespace perimorph::la {

/// What a product needs: the callback and, spread over processes, the
/// gathering of x and the map between the numberings.
struct ShellMatrix::Context {
  Apply apply;
  std::shared_ptr<const Distribution> distribution;  ///< null on one process
  int block_size = 1;
  std::optional<NodeGather> gather;  ///< x → this process: its halo, or all of x
  std::vector<double> x, y;          ///< whole, assembly numbering
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
  const auto n = static_cast<std::size_t>(d.num_nodes() * bs);
  if (c.x.size() != n) c.x.assign(n, 0.0);  // entries outside the halo stay 0: never read
  c.gather->gather(x, c.x);
  c.y.assign(n, 0.0);
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
    : ShellMatrix(nullptr, block_size, std::move(apply), size, {}) {}

ShellMatrix::ShellMatrix(std::shared_ptr<const Distribution> distribution, int block_size, Apply apply,
                         std::vector<Index> reads)
    : ShellMatrix(distribution, block_size, std::move(apply), PETSC_DETERMINE, std::move(reads)) {}

ShellMatrix::ShellMatrix(std::shared_ptr<const Distribution> distribution, int block_size, Apply apply,
                         Index size, std::vector<Index> reads)
    : size_(size), context_(std::make_unique<Context>()) {
  context_->apply = std::move(apply);
  context_->distribution = std::move(distribution);
  context_->block_size = block_size;
  if (context_->distribution) context_->gather.emplace(context_->distribution, block_size, std::move(reads));
  const Index local = context_->distribution ? context_->distribution->owned_nodes() * block_size : size;
  // Spread over processes the global size is the sum of the owned rows (the
  // assembly numbering may be a piece's, shorter than the whole model's).
  PM_PETSC(MatCreateShell(PETSC_COMM_WORLD, local, local, size, size, context_.get(), &m_));
  PetscInt rows = 0;
  PM_PETSC(MatGetSize(m_, &rows, nullptr));
  size_ = rows;
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

Index ShellMatrix::received_per_product() const {
  return context_->gather ? context_->gather->received() : 0;
}

void ShellMatrix::mult(const Vector& x, Vector& y) const {
  PM_PETSC(MatMult(m_, x.read_handle(), y.handle()));
}

}  // namespace perimorph::la
