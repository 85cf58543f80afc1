#pragma once
// A process's part built on its window of the case's box (issue 17, item 1;
// setup::part_window): what run::process_model builds for a box without
// holes or cuts, with the collectives the window's set-up needs.

#include "perimorph/casefile/case_config.hpp"
#include "perimorph/setup/discretization.hpp"

#include <utility>
#include <vector>

namespace perimorph::run {

/// This process's part built on its window (no array as long as the whole
/// mesh), and the part of each cell of the window. The CG/DG flags of the
/// window's cells it does not compute come from their owners by neighbour
/// exchange (window_flags). Requires setup::has_windows(config). Collective.
std::pair<setup::Discretization, std::vector<int>> window_part(const casefile::CaseConfig& config,
                                                               const setup::PhaseCallback& on_phase = {});

/// ModelPart::share_flags for a part on the window `window` of the grid of
/// `box` (collective): each process asks the owners of its window's cells for
/// their flagged cells within its window (the window's index box, 6 numbers),
/// then each owner answers with those of its part's cells (global numbers).
/// Nothing goes to a process whose window does not hold the cell, and no
/// process receives the whole list. `flags` are the window's, 1 where this
/// process computed a flagged cell; the result adds the owners' flags.
std::vector<char> window_flags(const mesh::BoxSpec& box, const setup::MeshWindow& window,
                               std::vector<char> flags);

}  // namespace perimorph::run
