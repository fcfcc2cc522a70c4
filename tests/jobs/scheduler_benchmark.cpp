// Rank 0's side of the scheduler, measured (not run by ctest; timings vary): run under
//   mpiexec -n 8 --oversubscribe build/release/tests/jobs/scheduler_benchmark [CELLS_PER_ROW]
// It runs a sweep of trivial cells (the test evaluator without arithmetic) with rank 0 only
// gathering, with chunks of at most 16, 256 and 65536 cells, and prints
//  - what rank 0 spent per message and per cell (its CPU time, fitted over three chunk caps:
//    busy = messages * c_msg + cells * c_cell), and the cells/s it sustains while busy;
//  - the checkpoint and final-cube cost per cell: the final cube's chunks deflated by the other
//    ranks (wall time, and rank 0's own CPU time in it), by rank 0 alone for comparison, and
//    written collectively by every rank (parallel HDF5);
//  - the latency of one claim on the shared counter (every rank claiming one cell at a time).
// docs/performance.md turns these constants into the efficiency model at 1000 ranks.
#include <mpi.h>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "jobs/mpi/mpi_transport.h"
#include "jobs/sweep_runner.h"
#include "tests/jobs/test_evaluator.h"

namespace jobs = skewbridge::jobs;

namespace {

struct Run {
  double cells = 0, messages = 0, bytes = 0, busy_s = 0, checkpoint_s = 0, wall_s = 0, total_s = 0;
  double final_s = 0, final_cpu_s = 0, checkpointed = 0, final_cpu_max_s = 0, final_cpu_sum_s = 0;
};

Run Sweep(const jobs::SweepSpec& spec, std::uint64_t max_chunk, const std::filesystem::path& out,
          bool farm = true, bool collective = false) {
  const jobs::testing::TestEvaluator evaluator(spec, 0, 0);
  jobs::SweepOptions options;
  options.out = out;
  options.force = true;
  options.root_computes_up_to_ranks = 1;
  options.max_chunk = max_chunk;
  // Checkpoints of 400 000 cells while cells arrive, timed (without the share that defers
  // them, so that every one is written when due); a complete run writes no last one.
  options.checkpoint_seconds = 1e9;
  options.checkpoint_cells = 400000;
  options.checkpoint_share = 1.0;
  options.farm_final_cube = farm;
  options.collective_final_from_ranks = collective ? 2 : 1 << 30;
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
  run.checkpointed = static_cast<double>(r.cells_checkpointed);
  run.wall_s = r.wall_s;
  run.final_s = r.final_s;
  run.final_cpu_s = r.final_cpu_s;
  // Collectively written, every rank has a share: their largest and their sum.
  MPI_Reduce(&r.final_cpu_s, &run.final_cpu_max_s, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
  MPI_Reduce(&r.final_cpu_s, &run.final_cpu_sum_s, 1, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  std::filesystem::remove(out);
  return run;
}

// Mean time of one Claim(1) while every rank claims [s].
double ClaimLatency(std::uint64_t claims_per_rank, int ranks) {
  auto transport = jobs::MakeMpiTransport();
  jobs::PendingCells pending;
  for (std::uint64_t c = 0; c < claims_per_rank * static_cast<std::uint64_t>(ranks); ++c) {
    pending.Append(c);
  }
  transport->BroadcastPending(pending);
  std::uint64_t mine = 0;
  const auto start = std::chrono::steady_clock::now();
  while (transport->Claim(1, 1).first < pending.size()) {
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
  // One name on every rank (rank 0's process id): the collective final write opens it on all.
  long pid = static_cast<long>(::getpid());
  MPI_Bcast(&pid, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  const auto out = std::filesystem::temp_directory_path() /
                   ("sb_scheduler_benchmark_" + std::to_string(pid) + ".h5");
  const std::vector<std::uint64_t> caps = {16, 256, 65536};
  std::vector<Run> runs;
  for (const std::uint64_t cap : caps) {
    runs.push_back(Sweep(spec, cap, out));
  }
  // The final cube by rank 0 alone (HDF5's filters), against the farmed runs above.
  const Run alone = Sweep(spec, caps.back(), out, false);
  // ... and by every rank collectively (parallel HDF5), each writing the cells it computed.
  const Run together = Sweep(spec, caps.back(), out, true, true);
  const double claim_s = ClaimLatency(20000, mpi.Size());
  if (mpi.Rank() != 0) {
    return 0;
  }
  // busy = messages c_msg + cells c_cell: least squares over the runs (equal cells, messages
  // from one per 16 cells to one per tens of thousands).
  double smm = 0, smc = 0, scc = 0, smb = 0, scb = 0;
  for (const Run& r : runs) {
    smm += r.messages * r.messages;
    smc += r.messages * r.cells;
    scc += r.cells * r.cells;
    smb += r.messages * r.busy_s;
    scb += r.cells * r.busy_s;
  }
  const double det = smm * scc - smc * smc;
  const double c_msg = (smb * scc - scb * smc) / det;
  const double c_cell = (smm * scb - smc * smb) / det;
  std::printf("| quantity |");
  for (const std::uint64_t cap : caps)
    std::printf(" chunks <= %llu |", static_cast<unsigned long long>(cap));
  std::printf("\n|---|---|---|---|\n");
  const auto row = [&](const char* name, const char* format, auto value) {
    std::printf("| %s |", name);
    for (const Run& r : runs) std::printf(format, value(r));
    std::printf("\n");
  };
  std::printf("| ranks (rank 0 only gathers) | %d | %d | %d |\n", mpi.Size(), mpi.Size(),
              mpi.Size());
  row("cells", " %.0f |", [](const Run& r) { return r.cells; });
  row("messages to rank 0", " %.0f |", [](const Run& r) { return r.messages; });
  row("bytes per cell on the wire", " %.1f |", [](const Run& r) { return r.bytes / r.cells; });
  row("rank 0 CPU receiving + storing [s]", " %.4f |", [](const Run& r) { return r.busy_s; });
  row("rank 0 sustained while busy [cells/s]", " %.3g |",
      [](const Run& r) { return r.cells / r.busy_s; });
  row("cells/s over the run (all workers)", " %.3g |",
      [](const Run& r) { return r.cells / r.wall_s; });
  row("checkpoint [ns per checkpointed cell]", " %.1f |",
      [](const Run& r) { return 1e9 * r.checkpoint_s / std::max(1.0, r.checkpointed); });
  row("final cube and set-up [ns/cell, wall]", " %.0f |",
      [](const Run& r) { return 1e9 * (r.total_s - r.wall_s) / r.cells; });
  row("final cube, chunks deflated by the others [ns/cell, wall]", " %.0f |",
      [](const Run& r) { return 1e9 * r.final_s / r.cells; });
  row("final cube, rank 0's own CPU [ns/cell]", " %.1f |",
      [](const Run& r) { return 1e9 * r.final_cpu_s / r.cells; });
  std::printf(
      "\nfinal cube by rank 0 alone (HDF5's filters): %.0f ns/cell wall, %.0f ns/cell CPU\n",
      1e9 * alone.final_s / alone.cells, 1e9 * alone.final_cpu_s / alone.cells);
  std::printf(
      "final cube written collectively by the %d ranks: %.0f ns/cell wall; CPU per cell: rank 0 "
      "%.1f ns, the busiest rank %.0f ns, all ranks together %.0f ns\n",
      mpi.Size(), 1e9 * together.final_s / together.cells,
      1e9 * together.final_cpu_s / together.cells, 1e9 * together.final_cpu_max_s / together.cells,
      1e9 * together.final_cpu_sum_s / together.cells);
  std::printf("\nfit: c_msg = %.2f us per message, c_cell = %.2f ns per cell on rank 0\n",
              1e6 * c_msg, 1e9 * c_cell);
  std::printf("claim latency: %.2f us per Claim (%d ranks claiming at once)\n", 1e6 * claim_s,
              mpi.Size());
  return 0;
}
