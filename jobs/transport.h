#pragma once
/// @file
/// How cells and results move between ranks, seen by the sweep runner without <mpi.h>:
/// a shared claim counter over the list of pending cells (dynamic load balancing in which
/// every rank computes) and a one-way stream of finished cells to rank 0, the only writer.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "jobs/cell.h"

namespace skewbridge::jobs {

/// One finished cell on its way to the writing rank (values in the cube layout's order).
struct CellRecord {
  std::uint64_t cell = 0;
  std::int32_t status = kStatusOk;
  CellStats stats;
  std::vector<double> values;
  std::string text;  ///< CellOutcome::status_text or the exception's message (failed cells).
};

/// Serialises records into bytes (host byte order; all ranks run the same build).
std::vector<char> PackRecords(std::span<const CellRecord> records, bool last);
/// The inverse of PackRecords; returns the `last` flag. @throws std::runtime_error when
/// the bytes are truncated (a bug or a foreign message).
bool UnpackRecords(std::span<const char> bytes, std::vector<CellRecord>& out);

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
  virtual void BroadcastPending(std::vector<std::uint64_t>& pending) = 0;
  /// Atomically claims `count` positions of the pending list: returns [begin, end), empty once
  /// every position has been handed out (or after StopClaims).
  virtual std::pair<std::uint64_t, std::uint64_t> Claim(std::uint64_t count) = 0;
  /// Hands out no more positions to anyone (called on a stop request).
  virtual void StopClaims() = 0;
  /// Ranks other than 0: sends finished cells to rank 0; `last` ends this rank's stream.
  /// Does not wait for rank 0.
  virtual void Send(std::span<const CellRecord> records, bool last) = 0;
  /// Rank 0: appends the records that have arrived (waiting up to wait_s for one message) and
  /// returns true once every other rank has ended its stream.
  virtual bool Receive(std::vector<CellRecord>& out, double wait_s) = 0;
  /// Collective: ends the sweep's communication (every pending send completed, shared
  /// resources freed); the last call on a transport.
  virtual void Finish() = 0;
};

/// The transport of a single process: a local counter, nothing to send.
std::unique_ptr<Transport> MakeInProcessTransport();

}  // namespace skewbridge::jobs
