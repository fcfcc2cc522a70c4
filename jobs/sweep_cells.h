#pragma once
/// @file
/// A rank's side of the sweep's cells (jobs/sweep_runner.cpp): how many cells it claims next
/// and how one cell's outcome goes into its chunk's result batch.

#include <cstddef>
#include <cstdint>

#include "jobs/cell.h"
#include "jobs/cube.h"
#include "jobs/sweep_runner.h"
#include "jobs/transport.h"

namespace skewbridge::jobs {

/// Guided self-scheduling [Polychronopoulos and Kuck 1987]: the cells to claim next, a share
/// of what is left (`total` positions, `seen` handed out), smaller near the end so that the
/// `ranks` finish together, capped so that a chunk takes about options.chunk_seconds at this
/// rank's last measured cell time `cell_s` [s] (1 cell while none is measured).
std::uint64_t ChunkSize(std::uint64_t total, std::uint64_t seen, int ranks,
                        const SweepOptions& options, double cell_s);

/// Evaluates `cell` into slot i of its chunk's batch (values in the layout's order, its wall
/// time, events and steps), with every failure, an exception included, turned into data.
void EvaluateInto(const SweepSpec& spec, const CellEvaluator& evaluator, const CubeLayout& layout,
                  std::uint64_t cell, std::size_t i, ResultBatch& batch);

}  // namespace skewbridge::jobs
