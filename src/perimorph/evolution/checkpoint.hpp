#pragma once
// The run state in a checkpoint (run/checkpoint.hpp): every field of
// RunState, bit for bit. The components' own parts are their save/restore
// (component.hpp, component_checkpoint.cpp).

#include "perimorph/evolution/run_state.hpp"

namespace perimorph::core {
class BinaryWriter;
class BinaryReader;
}  // namespace perimorph::core

namespace perimorph::evolution {

void save_state(const RunState& state, core::BinaryWriter& out);
/// Overwrites `state` (made for the discretization the checkpoint was written
/// on: RunState(disc)) with what save_state wrote; fails (Error naming the
/// checkpoint) where the sizes do not fit that discretization.
void restore_state(RunState& state, core::BinaryReader& in);

void save_alpha(const alpha::AlphaField& alpha, core::BinaryWriter& out);
alpha::AlphaField restore_alpha(core::BinaryReader& in);

}  // namespace perimorph::evolution
