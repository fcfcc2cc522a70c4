#pragma once
/// @file
/// How cells and results move between ranks, seen by the sweep runner without <mpi.h>:
/// a shared claim counter over the list of pending cells (dynamic load balancing in which
/// every rank computes) and a one-way stream of result batches to rank 0, the only writer.
/// A batch holds the results of one claimed chunk in columns, so that rank 0 copies them into
/// the cube with one memcpy per dataset (docs/hdf5-layout.md, "Scheduling").

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "jobs/cell.h"

namespace skewbridge::jobs {

/// The cells a run has to compute, in increasing order, kept as runs of consecutive cells: 16
/// bytes per run on every rank instead of 8 per cell (a fresh sweep is one run, a resumed one
/// has a run per gap), so that the list costs nothing for cubes of 10^9 cells.
class PendingCells {
 public:
  /// Appends a cell. @pre larger than every cell appended before.
  void Append(std::uint64_t cell);
  /// Number of cells.
  std::uint64_t size() const { return size_; }
  /// The cell at position pos (0 .. size() - 1): a binary search over the runs.
  std::uint64_t operator[](std::uint64_t pos) const;
  /// Number of runs of consecutive cells.
  std::size_t Runs() const { return run_first_cell_.size(); }
  /// The runs as (first cell, length) pairs flattened, for a broadcast.
  std::vector<std::uint64_t> Flatten() const;
  /// The inverse of Flatten. @throws std::runtime_error for an odd length or unsorted runs.
  static PendingCells FromFlat(const std::vector<std::uint64_t>& flat);

 private:
  std::vector<std::uint64_t> run_first_cell_;  // [run]
  std::vector<std::uint64_t> run_first_pos_;   // [run] position of the run's first cell
  std::uint64_t size_ = 0;
  std::uint64_t last_ = 0;  // the last cell, when size_ > 0
};

/// The failures of one status within a batch: how many, and the lowest cell with its text
/// (so that rank 0 keeps one example per status without looking at every cell).
struct FailureNote {
  std::int32_t status = kStatusException;  ///< the status (never kStatusOk)
  std::uint64_t count = 0;                 ///< cells of the batch with this status
  std::uint64_t lowest_cell = 0;           ///< linear cell index
  std::string text;                        ///< CellOutcome::status_text or the exception's message
};

/// The results of one claimed chunk: positions [begin, end) of the pending cell list, each
/// column indexed by position - begin (values in the cube layout's order, response-major).
struct ResultBatch {
  std::uint64_t begin = 0;            ///< first position in the pending list
  std::uint64_t end = 0;              ///< one past the last position
  std::uint32_t responses = 0;        ///< values per cell
  std::vector<std::int32_t> status;   ///< [i]
  std::vector<std::int64_t> events;   ///< [i] CellStats::events
  std::vector<std::int64_t> steps;    ///< [i] CellStats::steps
  std::vector<double> wall_s;         ///< [i] CellStats::wall_s [s]
  std::vector<double> values;         ///< [r * size + i]
  std::vector<FailureNote> failures;  ///< one note per failed status, none when all ok

  /// Number of cells (end - begin).
  std::uint64_t Size() const { return end - begin; }
  /// Empties the columns and sizes them for positions [from, to) and `response_count` values.
  void Reset(std::uint64_t from, std::uint64_t to, std::uint32_t response_count);
  /// Keeps only the first `count` cells (a stop request ended the chunk early).
  void Truncate(std::uint64_t count);
};

/// A batch as it lies in a received message: the columns point into the message bytes
/// (unaligned, read with memcpy), nothing is copied until rank 0 stores them.
struct BatchView {
  std::uint64_t begin = 0;            ///< first position in the pending list
  std::uint64_t end = 0;              ///< one past the last position
  std::uint32_t responses = 0;        ///< values per cell
  const char* status = nullptr;       ///< (end - begin) std::int32_t
  const char* events = nullptr;       ///< (end - begin) std::int64_t
  const char* steps = nullptr;        ///< (end - begin) std::int64_t
  const char* wall_s = nullptr;       ///< (end - begin) double
  const char* values = nullptr;       ///< responses * (end - begin) double, response-major
  std::vector<FailureNote> failures;  ///< copied: they are few
};

/// Serialises a batch into one message (host byte order; all ranks run the same build):
/// a fixed header, the five columns back to back, then the failure notes.
std::vector<char> PackBatch(const ResultBatch& batch);

/// The first multiple of `block` at or after `position` (`position` itself when block <= 1).
inline std::uint64_t BlockEnd(std::uint64_t position, std::uint64_t block) {
  return block <= 1 ? position : (position + block - 1) / block * block;
}

/// Reads a message of PackBatch without copying the columns. @throws std::runtime_error when
/// the bytes are truncated or not a batch (a bug or a foreign message).
BatchView UnpackBatch(std::span<const char> bytes);
/// A view of a batch in memory (rank 0's own cells), as UnpackBatch would give after packing.
BatchView ViewOf(const ResultBatch& batch);

/// What rank 0 has received so far (for the scheduler's cost model).
struct ReceiveStats {
  std::uint64_t messages = 0;  ///< result messages (stream ends excluded)
  std::uint64_t bytes = 0;     ///< their bytes
  double busy_s = 0.0;         ///< time from finding a message to the end of its handling [s]
};

/// The communication a sweep needs. Collective calls must be made by every rank in the same
/// order; the others are one-sided.
class Transport {
 public:
  virtual ~Transport() = default;
  /// This process's rank, 0 .. Size() - 1; rank 0 writes the cube.
  virtual int Rank() const = 0;
  /// The number of ranks.
  virtual int Size() const = 0;
  /// Collective: every rank gets rank 0's text (used to share a setup error or an empty string).
  virtual std::string BroadcastText(const std::string& text) = 0;
  /// Collective: every rank gets rank 0's list of pending cells; resets the claim counter to 0.
  virtual void BroadcastPending(PendingCells& pending) = 0;
  /// Atomically claims `count` positions of the pending list, or more: the claim ends at the
  /// first multiple of `block` (>= 1) at or after begin + count, so that claims of whole blocks
  /// stay aligned to them. Returns [begin, end), cut at the list's end; empty once every
  /// position has been handed out (or after StopClaims).
  virtual std::pair<std::uint64_t, std::uint64_t> Claim(std::uint64_t count,
                                                        std::uint64_t block) = 0;
  /// Hands out no more positions to anyone (called on a stop request).
  virtual void StopClaims() = 0;
  /// Ranks other than 0: sends one message (a packed batch) to rank 0. Does not wait for
  /// rank 0; the bytes are owned by the transport until delivered.
  virtual void Send(std::vector<char> message) = 0;
  /// Ranks other than 0: ends this rank's stream (after its last Send).
  virtual void EndStream() = 0;
  /// Rank 0: calls `handle` on each message that has arrived (waiting up to wait_s for the
  /// first), in each sender's order; the bytes are valid during the call only. Returns true
  /// once every other rank has ended its stream.
  virtual bool Receive(const std::function<void(std::span<const char>)>& handle, double wait_s) = 0;
  /// Rank 0: the messages received so far and the time spent on them.
  virtual ReceiveStats Received() const { return {}; }
  /// Collective: whether every rank passed true (the ranks of a collective write stop together).
  /// This base version, for a single process, returns `mine`.
  virtual bool AllTrue(bool mine) { return mine; }
  /// Collective: rank 0 gets every rank's `mine`, in rank order; the other ranks get nothing.
  /// This base version, for a single process, returns {mine}.
  virtual std::vector<std::string> GatherText(const std::string& mine) { return {mine}; }
  /// Collective, after every stream has ended: rank 0 hands jobs 0 .. count - 1 (job(i) makes
  /// the bytes of job i when it is sent) to the other ranks, which apply `work` and return its
  /// bytes; rank 0 gets each result through done(i, bytes), in any order. The other ranks pass
  /// count 0 and no job or done. This base version, for a single process, runs every job on
  /// rank 0 itself. A throwing done ends the farm (the other ranks are released) and rethrows.
  virtual void Farm(std::size_t count, const std::function<std::vector<char>(std::size_t)>& job,
                    const std::function<std::vector<char>(std::span<const char>)>& work,
                    const std::function<void(std::size_t, std::span<const char>)>& done);
  /// Collective: ends the sweep's communication (every pending send completed, shared
  /// resources freed); the last call on a transport.
  virtual void Finish() = 0;
};

/// The transport of a single process: a local counter, nothing to send.
std::unique_ptr<Transport> MakeInProcessTransport();

}  // namespace skewbridge::jobs
