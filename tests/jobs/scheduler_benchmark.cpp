// Rank 0's side of the scheduler, measured (not run by ctest; timings vary): run under
//   mpiexec -n 8 --oversubscribe build/release/tests/jobs/scheduler_benchmark [CELLS_PER_ROW]
// It runs a sweep of trivial cells (the test evaluator without arithmetic) with rank 0 only
// gathering, once with small chunks and once with large ones, and prints
//  - what rank 0 spent per message and per cell (a least-squares-free fit of the two runs:
//    busy = messages * c_msg + cells * c_cell), and the cells/s it sustains while busy;
//  - the checkpoint and final-cube cost per cell;
//  - the latency of one claim on the shared counter (every rank claiming one cell at a time).
// docs/performance.md turns these constants into the efficiency model at 1000 ranks.
#include <mpi.h>

#include <unistd.h>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "jobs/mpi/mpi_transport.h"
#include "jobs/sweep_runner.h"
#include "tests/jobs/test_evaluator.h"

namespace jobs = skewbridge::jobs;

namespace {

struct Run {
  double cells = 0, messages = 0, bytes = 0, busy_s = 0, checkpoint_s = 0, wall_s = 0, total_s = 0;
};

Run Sweep(const jobs::SweepSpec& spec, std::uint64_t max_chunk, const std::filesystem::path& out) {
  const jobs::testing::TestEvaluator evaluator(spec, 0, 0);
  jobs::SweepOptions options;
  options.out = out;
  options.force = true;
  options.root_computes_up_to_ranks = 1;
  options.max_chunk = max_chunk;
  options.checkpoint_seconds = 1e9;  // one checkpoint, at the end: timed separately
  auto transport = jobs::MakeMpiTransport();
  MPI_Barrier(MPI_COMM_WORLD);
  const auto start = std::chrono::steady_clock::now();
  const jobs::SweepReport r = jobs::RunSweep(spec, evaluator, *transport, options);
  Run run;
  run.total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.cells = static_cast<double>(r.cells_computed);
  run.messages = static_cast<double>(r.messages_received);
  run.bytes = static_cast<double>(r.bytes_received);
  run.busy_s = r.receive_busy_s;
  run.checkpoint_s = r.checkpoint_s;
  run.wall_s = r.wall_s;
  std::filesystem::remove(out);
  return run;
}

// Mean time of one Claim(1) while every rank claims [s].
double ClaimLatency(std::uint64_t claims_per_rank, int ranks) {
  auto transport = jobs::MakeMpiTransport();
  std::vector<std::uint64_t> pending(claims_per_rank * static_cast<std::uint64_t>(ranks));
  transport->BroadcastPending(pending);
  std::uint64_t mine = 0;
  const auto start = std::chrono::steady_clock::now();
  while (transport->Claim(1).first < pending.size()) {
    ++mine;
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (transport->Rank() != 0) {
    transport->EndStream();
  }
  double mean = mine > 0 ? s / static_cast<double>(mine) : 0.0;
  double sum = 0.0;
  MPI_Reduce(&mean, &sum, 1, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  if (transport->Rank() == 0) {
    while (!transport->Receive([](std::span<const char>) {}, 0.05)) {
    }
  }
  transport->Finish();
  return sum / ranks;
}

}  // namespace

int main(int argc, char** argv) {
  jobs::MpiSession mpi;
  const long per_row = argc > 1 ? std::atol(argv[1]) : 25000;
  const std::string text =
      "[sweep]\nname = \"bench\"\nfamily = \"subsystem\"\n[axes]\n"
      "pulse = [\"cosine\", \"sine\"]\na_deg = {linspace = [1, 80, 40]}\n"
      "w0_over_wg = {logspace = [0.1, 10.0, " +
      std::to_string(per_row) + "]}\n";
  const jobs::SweepSpec spec = jobs::ParseSweepSpec(text, "bench.toml", ".");
  const auto out = std::filesystem::temp_directory_path() /
                   ("sb_scheduler_benchmark_" + std::to_string(::getpid()) + ".h5");
  const Run small = Sweep(spec, 256, out);
  const Run large = Sweep(spec, 65536, out);
  const double claim_s = ClaimLatency(20000, mpi.Size());
  if (mpi.Rank() != 0) {
    return 0;
  }
  // busy = messages c_msg + cells c_cell, from the two runs (equal cells, different messages).
  const double c_msg = (small.busy_s - large.busy_s) / (small.messages - large.messages);
  const double c_cell = (large.busy_s - c_msg * large.messages) / large.cells;
  std::printf("| quantity | small chunks (<= 256) | large chunks (<= 65536) |\n|---|---|---|\n");
  std::printf("| ranks (rank 0 only gathers) | %d | %d |\n", mpi.Size(), mpi.Size());
  std::printf("| cells | %.0f | %.0f |\n", small.cells, large.cells);
  std::printf("| messages to rank 0 | %.0f | %.0f |\n", small.messages, large.messages);
  std::printf("| bytes per cell on the wire | %.1f | %.1f |\n", small.bytes / small.cells,
              large.bytes / large.cells);
  std::printf("| rank 0 busy receiving + storing [s] | %.4f | %.4f |\n", small.busy_s,
              large.busy_s);
  std::printf("| rank 0 sustained while busy [cells/s] | %.3g | %.3g |\n",
              small.cells / small.busy_s, large.cells / large.busy_s);
  std::printf("| cells/s over the run (all workers) | %.3g | %.3g |\n", small.cells / small.wall_s,
              large.cells / large.wall_s);
  std::printf("| checkpoint [ns/cell] | %.1f | %.1f |\n", 1e9 * small.checkpoint_s / small.cells,
              1e9 * large.checkpoint_s / large.cells);
  std::printf("| final cube and set-up [ns/cell] | %.1f | %.1f |\n",
              1e9 * (small.total_s - small.wall_s) / small.cells,
              1e9 * (large.total_s - large.wall_s) / large.cells);
  std::printf("\nfit: c_msg = %.2f us per message, c_cell = %.2f ns per cell on rank 0\n",
              1e6 * c_msg, 1e9 * c_cell);
  std::printf("claim latency: %.2f us per Claim (%d ranks claiming at once)\n", 1e6 * claim_s,
              mpi.Size());
  return 0;
}
