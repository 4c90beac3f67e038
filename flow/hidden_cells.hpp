// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Which cells of a level a viewer should hide (VTK's ghost array, vtkDataSetAttributes::HIDDENCELL = 32): a cell
// is hidden when the next finer level covers its centre, or when its centre is inside a solid (flow/bodies.hpp:
// inside a sphere where the trajectory or the kernel has it, or beyond the wall). Cells in the order of
// LevelGeometry's vertices (i outer, j inner: cell (i, j) spans r ∈ [i h, (i+1) h]).
#include <cstdint>
#include <vector>

#include "flow/bodies.hpp"
#include "flow/fields.hpp"

namespace imcol::flow {

inline constexpr std::uint8_t kHiddenCell = 32;  // vtkDataSetAttributes::HIDDENCELL

struct CellFlags {
  std::vector<std::uint8_t> finer;  // 1 where the next finer level covers the cell's centre
  std::vector<std::uint8_t> ghost;  // kHiddenCell where the cell is hidden, else 0
};

CellFlags cell_flags(const std::vector<LevelFields>& levels, std::size_t level, const SnapshotBodies& bodies);

}  // namespace imcol::flow
