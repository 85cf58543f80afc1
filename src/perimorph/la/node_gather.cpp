#include "perimorph/la/node_gather.hpp"

#include "perimorph/core/error.hpp"
#include "perimorph/la/petsc_check.hpp"
#include "perimorph/la/vector.hpp"

#include <petscvec.h>

#include <utility>

namespace perimorph::la {

struct NodeGather::Scatter {
  VecScatter scatter = nullptr;
  Vec received = nullptr;
  ~Scatter() {
    if (scatter) VecScatterDestroy(&scatter);
    if (received) VecDestroy(&received);
  }
};

NodeGather::NodeGather(std::shared_ptr<const Distribution> distribution, int block_size,
                       std::vector<Index> reads)
    : distribution_(std::move(distribution)), block_size_(block_size), reads_(std::move(reads)) {
  PERIMORPH_ASSERT(distribution_ != nullptr, "NodeGather needs a distribution");
}

NodeGather::~NodeGather() = default;
NodeGather::NodeGather(NodeGather&& other) noexcept = default;
NodeGather& NodeGather::operator=(NodeGather&& other) noexcept = default;

void NodeGather::gather(PetscVecHandle x, std::span<double> out) {
  const Distribution& d = *distribution_;
  const Index bs = block_size_;
  PERIMORPH_ASSERT(static_cast<Index>(out.size()) == d.num_nodes() * bs, "NodeGather: wrong output size");
  if (!scatter_) {
    scatter_ = std::make_unique<Scatter>();
    if (reads_.empty()) {
      PM_PETSC(VecScatterCreateToAll(x, &scatter_->scatter, &scatter_->received));
    } else {
      std::vector<PetscInt> blocks(reads_.size());
      for (std::size_t i = 0; i < reads_.size(); ++i)
        blocks[i] = d.to_distributed[static_cast<std::size_t>(reads_[i])];
      IS from = nullptr;
      PM_PETSC(ISCreateBlock(PETSC_COMM_SELF, bs, static_cast<PetscInt>(blocks.size()), blocks.data(),
                             PETSC_COPY_VALUES, &from));
      PM_PETSC(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(blocks.size()) * bs, &scatter_->received));
      PM_PETSC(VecScatterCreate(x, from, scatter_->received, nullptr, &scatter_->scatter));
      PM_PETSC(ISDestroy(&from));
    }
  }
  PM_PETSC(VecScatterBegin(scatter_->scatter, x, scatter_->received, INSERT_VALUES, SCATTER_FORWARD));
  PM_PETSC(VecScatterEnd(scatter_->scatter, x, scatter_->received, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar* a = nullptr;
  PM_PETSC(VecGetArrayRead(scatter_->received, &a));
  if (reads_.empty()) {
    for (Index node = 0; node < d.num_nodes(); ++node)
      for (Index k = 0; k < bs; ++k)
        out[static_cast<std::size_t>(node * bs + k)] =
            a[d.to_distributed[static_cast<std::size_t>(node)] * bs + k];
  } else {
    for (std::size_t i = 0; i < reads_.size(); ++i)
      for (Index k = 0; k < bs; ++k)
        out[static_cast<std::size_t>(reads_[i] * bs + k)] = a[static_cast<Index>(i) * bs + k];
  }
  PM_PETSC(VecRestoreArrayRead(scatter_->received, &a));
}

void NodeGather::gather(const Vector& x, std::span<double> out) {
  gather(x.read_handle(), out);
}

std::vector<double> NodeGather::gathered(const Vector& x, double elsewhere) {
  std::vector<double> out(static_cast<std::size_t>(distribution_->num_nodes() * block_size_), elsewhere);
  gather(x, out);
  return out;
}

Index NodeGather::received() const {
  const Distribution& d = *distribution_;
  if (reads_.empty()) return (d.num_nodes() - d.owned_nodes()) * block_size_;
  Index others = 0;
  for (Index node : reads_) others += d.owns(node) ? 0 : 1;
  return others * block_size_;
}

}  // namespace perimorph::la
