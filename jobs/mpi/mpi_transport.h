#pragma once
/// @file
/// The MPI transport of the sweep runner and the MPI lifetime of the `sweep` command.
/// Free of <mpi.h>: the program and tests include this header only.

#include <memory>

#include "jobs/transport.h"

namespace skewbridge::jobs {

/// MPI_Init on construction, MPI_Finalize on destruction: owned by the `sweep` command alone,
/// so the other commands run without mpirun. @pre at most one per process.
class MpiSession {
 public:
  MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  ~MpiSession();
  /// This process's rank in MPI_COMM_WORLD.
  int Rank() const;
  /// The size of MPI_COMM_WORLD.
  int Size() const;
  /// Collective: the lowest rank whose `flag` is true, or Size() when none is (how the ranks
  /// agree, without MPI_Abort, that one of them found bad input and which one reports it).
  int FirstRankWith(bool flag) const;
  /// Collective: returns once every rank has called it.
  void Barrier() const;
};

/// Ends every rank (MPI_Abort): for a failure after setup that would leave the others waiting.
void AbortAll(int code);

/// The transport over (a duplicate of) MPI_COMM_WORLD: the claim counter is one 64-bit integer
/// in an MPI-3 window on rank 0, advanced with MPI_Fetch_and_op under a shared passive-target
/// lock (no rank waits for rank 0 to hand out work); results travel as one MPI_Isend per
/// claimed chunk (a packed ResultBatch) and are drained by rank 0 with MPI_Iprobe into one
/// reused buffer; a zero-byte message ends a rank's stream. Collective.
/// @pre MPI is initialised (an MpiSession is alive).
std::unique_ptr<Transport> MakeMpiTransport();

}  // namespace skewbridge::jobs
