#pragma once
/// @file
/// Runs a sweep: opens or resumes the cube on rank 0, distributes the pending cells over the
/// ranks of a Transport in chunks that every rank claims for itself (guided self-scheduling,
/// capped by a target duration), gathers each chunk's results to rank 0 as one message,
/// checkpoints them into FILE.partial and, when every cell is done, writes the compressed FILE
/// (docs/hdf5-layout.md).

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>

#include "jobs/cell.h"
#include "jobs/sweep_spec.h"
#include "jobs/transport.h"

namespace skewbridge::jobs {

/// Progress of a running sweep, as rank 0 sees it.
struct SweepProgress {
  std::uint64_t cells_total = 0;  ///< Cells in the cube.
  std::uint64_t cells_done = 0;   ///< Cells finished (this run and earlier runs).
  std::uint64_t run_total = 0;    ///< Cells this run has to compute.
  std::uint64_t run_done = 0;     ///< Cells this run has computed so far.
  std::uint64_t run_failed = 0;   ///< Of those, cells with a status other than ok.
  double elapsed_s = 0.0;         ///< Since this run started its cells [s].
  double cells_per_s = 0.0;       ///< run_done / elapsed_s.
  double eta_s = 0.0;             ///< Remaining time at the current rate [s].
};

/// How a sweep runs.
struct SweepOptions {
  std::filesystem::path out;           ///< The final cube FILE; checkpoints go to FILE.partial.
  bool resume = false;                 ///< Continue FILE.partial (or start if none exists).
  bool force = false;                  ///< Replace an existing FILE / FILE.partial.
  double checkpoint_seconds = 60.0;    ///< Checkpoint at least this often [s].
  std::uint64_t checkpoint_cells = 0;  ///< Also checkpoint every this many cells (0 = off).
  /// While cells run, rank 0 spends at most this share of its time writing checkpoints: after
  /// one that took W seconds the next waits at least W (1 - share) / share, whatever the two
  /// settings above ask, so that checkpoints never starve the gathering of results. Cells come
  /// faster than one writer can checkpoint them (20-45 ns per cell) only with very cheap cells
  /// on hundreds of ranks; the checkpoints then lag, and what they hold is what a kill keeps.
  double checkpoint_share = 0.2;
  double progress_seconds = 1.0;  ///< Minimum interval between progress reports [s].
  /// Largest number of cells claimed at once (it bounds a result message: about 52 bytes per
  /// cell plus 8 per response beyond three).
  std::uint64_t max_chunk = 65536;
  /// A chunk is sized to take about this long on the rank that claims it, from the mean cell
  /// time of its previous chunk (the first chunk of a rank is one cell) [s]. It bounds the
  /// delay of results and progress and, with the guided share (what is left / 2 ranks), the
  /// idle time at the end of the sweep.
  double chunk_seconds = 0.05;
  /// A chunk runs on to the end of the evaluator's block of shared work
  /// (CellEvaluator::WorkBlock: a record's stripes and seat widths) when a block takes at most
  /// this long at the rank's last mean cell time and the sweep holds at least 4 blocks per
  /// rank, so that no two ranks repeat a shared run or trace [s]. It bounds what a chunk in
  /// flight holds; a stop request still ends a chunk after the cell being computed.
  double block_seconds = 2.0;
  /// Rank 0 computes cells too when there are at most this many ranks; above, it only
  /// gathers and writes, so that results and progress never wait for one of its own cells.
  int root_computes_up_to_ranks = 64;
  /// With more than one rank, the final cube's chunks are shuffled, deflated and checksummed
  /// by the other ranks (idle once the cells are done) and written by rank 0 as stored bytes;
  /// false: rank 0 alone filters them through HDF5 (the serial path, same file contents).
  bool farm_final_cube = true;
  /// From this many ranks on, every rank writes its own cells into the final cube with
  /// parallel HDF5's filtered collective writes (h5::WriteFinalCellsCollective) instead of the
  /// farm above, so that rank 0 handles only its share of the cube after the cells; every rank
  /// then keeps its results until the end (about 57 bytes per cell it computed).
  int collective_final_from_ranks = 65;
  /// Set asynchronously (a signal handler) to stop: the run checkpoints and returns
  /// interrupted. May be nullptr.
  const volatile std::sig_atomic_t* stop = nullptr;
  /// Called on rank 0 at most every progress_seconds, and once at the end. May be empty.
  std::function<void(const SweepProgress&)> progress;
};

/// What a run did (filled on rank 0; other ranks fill rank and cells_this_rank).
struct SweepReport {
  int rank = 0;
  int ranks = 1;
  std::int32_t run = 1;  ///< 1 for a fresh sweep, 2.. after resumes.
  std::uint64_t cells_total = 0;
  std::uint64_t cells_done = 0;       ///< Done in the file at the end.
  std::uint64_t cells_computed = 0;   ///< Computed in this run, all ranks.
  std::uint64_t cells_this_rank = 0;  ///< Computed in this run by this rank.
  std::uint64_t cells_failed = 0;     ///< Done cells with a status other than ok, all runs.
  std::map<std::string, std::uint64_t> failed_by_status;  ///< Status name -> count.
  std::uint64_t checkpoints = 0;                          ///< Checkpoints written in this run.
  double wall_s = 0.0;                                    ///< Wall time of this run's cells [s].
  bool interrupted = false;                               ///< A stop request ended the run early.
  bool complete = false;                                  ///< Every cell done and FILE written.
  bool already_complete = false;       ///< --resume found a complete FILE: nothing to do.
  std::uint64_t chunks_this_rank = 0;  ///< Chunks this rank claimed and computed.
  /// Rank 0: result messages received, their bytes, and the CPU time spent receiving and
  /// storing them into the cube (MPI_Recv, unpacking, copying) [s]; what a sweep costs rank 0 per
  /// message and per cell (tests/jobs/scheduler_benchmark.cpp).
  std::uint64_t messages_received = 0;
  std::uint64_t bytes_received = 0;
  double receive_busy_s = 0.0;
  double checkpoint_s = 0.0;             ///< Rank 0: time spent writing checkpoints [s].
  std::uint64_t cells_checkpointed = 0;  ///< Rank 0: cells those checkpoints wrote.
  /// Rank 0 (every rank when the ranks write the final cube collectively): time spent writing
  /// the final cube, study tables included [s], and this rank's own CPU time in it [s].
  double final_s = 0.0;
  double final_cpu_s = 0.0;
};

/// Runs (or resumes) a sweep on every rank of `transport`. Collective.
/// The evaluator must be pure (CellEvaluator); an exception from Evaluate is recorded as
/// kStatusException and never stops the sweep.
/// @throws InputError before any work, on every rank, for an unusable output file (exists
///         without --resume/--force, a different specification on resume), and for
///         responses the evaluator does not know; also on every rank when a fresh checkpoint
///         file cannot be written (ranks > 0 compute while rank 0 creates it: what they
///         computed is dropped, and nothing is left at FILE.partial or FILE).
SweepReport RunSweep(const SweepSpec& spec, const CellEvaluator& evaluator, Transport& transport,
                     const SweepOptions& options);

/// One line of progress, e.g. "sweep: 1200/5000 cells (24.0%), 350 cells/s, ETA 11 s".
std::string FormatProgress(const SweepProgress& progress);

/// The one-line summary printed at the end of a run.
std::string FormatSummary(const SweepReport& report);

/// The path of the checkpoint file of `out`: out + ".partial".
std::filesystem::path PartialPath(const std::filesystem::path& out);

}  // namespace skewbridge::jobs
