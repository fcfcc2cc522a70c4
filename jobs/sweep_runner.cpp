#include "jobs/sweep_runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <exception>
#include <optional>

#include "jobs/cube.h"
#include "jobs/h5/cube_file.h"
#include "jobs/study.h"
#include "jobs/sweep_cells.h"
#include "solver/common/error.h"

namespace skewbridge::jobs {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// CPU time of the calling thread [s]: rank 0's own share of the final write, apart from the
// time it waits for the ranks that deflate its chunks.
double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

bool StopRequested(const SweepOptions& options) {
  return options.stop != nullptr && *options.stop != 0;
}

template <typename T>
void CopyColumn(T* cube, const char* column, std::size_t n) {
  std::memcpy(cube, column, n * sizeof(T));
}

template <typename T>
T At(const char* column, std::size_t i) {
  T v;
  std::memcpy(&v, column + i * sizeof(T), sizeof(T));
  return v;
}

// Rank 0's side: the cube image, the checkpoint file and the bookkeeping of the run.
class Writer {
 public:
  Writer(const SweepSpec& spec, const CubeLayout& layout, const SweepOptions& options)
      : spec_(spec), layout_(layout), options_(options) {}

  // What Open decided: the sweep is complete already, a checkpoint was resumed, or a fresh
  // checkpoint file is still to be created (Create).
  enum class Opened { kComplete, kResumed, kToCreate };

  // Checks the output and resumes a checkpoint, or prepares a fresh cube in memory (every cell
  // pending) whose checkpoint file Create then writes: the other ranks compute meanwhile.
  Opened Open() {
    const std::filesystem::path partial = PartialPath(options_.out);
    std::error_code ec;
    const bool out_exists = std::filesystem::exists(options_.out, ec);
    const bool partial_exists = std::filesystem::exists(partial, ec);
    if (!options_.resume || options_.force) {
      if ((out_exists || partial_exists) && !options_.force) {
        throw InputError::AtLine((out_exists ? options_.out : partial).string(), 0,
                                 "already exists; use --resume to continue it or --force to "
                                 "replace it");
      }
      std::filesystem::remove(options_.out, ec);
      std::filesystem::remove(partial, ec);
    } else if (!partial_exists && out_exists) {
      for (const h5::SweepSummary& s : h5::SummarizeCube(options_.out)) {
        if (s.name != spec_.name) continue;
        // A result never outlives its inputs: name what changed since the cube was written.
        const std::string change =
            DescribeIdentityChange(s.spec_canonical, s.inputs_canonical, spec_);
        if (!change.empty()) {
          throw InputError::AtLine(options_.out.string(), 0,
                                   "cannot resume: " + change +
                                       "; restore it, write a new output file, or use --force "
                                       "to recompute every cell from the inputs as they are now");
        }
        if (s.spec_hash == spec_.Hash() && s.complete) {
          data_.Reset(spec_.CellCount(), layout_.responses.size());
          return Opened::kComplete;
        }
      }
      throw InputError::AtLine(options_.out.string(), 0,
                               "cannot resume: it holds no complete sweep of this specification "
                               "(hash " +
                                   spec_.Hash() + "); use --force to replace it");
    }
    if (options_.resume && partial_exists && !options_.force) {
      file_.emplace(h5::CheckpointFile::Resume(partial, spec_, layout_, data_));
      if (data_.Cells() != spec_.CellCount()) {
        throw InputError::AtLine(partial.string(), 0, "cannot resume: its shape differs");
      }
      run_ = file_->Run();
      return Opened::kResumed;
    }
    data_.Reset(spec_.CellCount(), layout_.responses.size());
    return Opened::kToCreate;
  }

  // Creates the fresh checkpoint file that Open prepared (run 1). @throws h5::H5Error when it
  // cannot be written (nothing is left at its path then).
  void Create() {
    file_.emplace(h5::CheckpointFile::Create(PartialPath(options_.out), spec_, layout_));
    run_ = file_->Run();
  }

  PendingCells Pending() const {
    PendingCells pending;
    for (std::uint64_t c = 0; c < data_.Cells(); ++c) {
      if (data_.done[c] == 0) {
        pending.Append(c);
      }
    }
    return pending;
  }

  // Copies a chunk's results into the cube image: one memcpy per dataset when its cells are
  // consecutive (always, in a fresh sweep), a loop over them otherwise (a resume's gaps).
  void StoreBatch(const BatchView& batch, const PendingCells& pending) {
    const std::size_t n = batch.end - batch.begin;
    if (n == 0) {
      return;
    }
    SB_DEMAND(batch.end <= pending.size() && batch.responses == data_.responses.size(),
              "a result batch does not fit the sweep");
    const std::uint64_t first = pending[batch.begin];
    // Chunks are disjoint ranges of the pending list (one claim counter): a chunk whose first
    // cell is already here means a cell was delivered twice.
    SB_DEMAND(data_.done[first] == 0, "a cell was delivered twice");
    if (pending[batch.end - 1] - first == n - 1) {
      CopyColumn(&data_.status[first], batch.status, n);
      CopyColumn(&data_.events[first], batch.events, n);
      CopyColumn(&data_.steps[first], batch.steps, n);
      CopyColumn(&data_.wall_s[first], batch.wall_s, n);
      for (std::size_t r = 0; r < data_.responses.size(); ++r) {
        CopyColumn(&data_.responses[r][first], batch.values + r * n * sizeof(double), n);
      }
      std::fill_n(&data_.run[first], n, run_);
      // Done in memory: the checkpoint file gets the flags after the data (Checkpoint).
      std::fill_n(&data_.done[first], n, std::uint8_t{1});
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint64_t c = pending[batch.begin + i];
        data_.status[c] = At<std::int32_t>(batch.status, i);
        data_.events[c] = At<std::int64_t>(batch.events, i);
        data_.steps[c] = At<std::int64_t>(batch.steps, i);
        data_.wall_s[c] = At<double>(batch.wall_s, i);
        for (std::size_t r = 0; r < data_.responses.size(); ++r) {
          data_.responses[r][c] = At<double>(batch.values, r * n + i);
        }
        data_.run[c] = run_;
        data_.done[c] = 1;
      }
    }
    unwritten_.emplace_back(batch.begin, batch.end);
    unwritten_cells_ += n;
    computed_ += n;
    for (const FailureNote& note : batch.failures) {
      failed_ += note.count;
      // The lowest failed cell of each status, whatever the order of arrival.
      const auto it = example_cells_.find(note.status);
      if (it == example_cells_.end() || note.lowest_cell < it->second) {
        example_cells_[note.status] = note.lowest_cell;
        examples_[note.status] = "cell " + std::to_string(note.lowest_cell) + ": " + note.text;
      }
    }
  }

  bool CheckpointDue() const {
    if (unwritten_.empty()) {
      return false;
    }
    const double since = Seconds(last_checkpoint_);
    // The share of rank 0's time: a long checkpoint defers the next one.
    const double share = std::clamp(options_.checkpoint_share, 1e-3, 1.0);
    if (since < last_checkpoint_s_ * (1.0 - share) / share) {
      return false;
    }
    return since >= options_.checkpoint_seconds ||
           (options_.checkpoint_cells > 0 && unwritten_cells_ >= options_.checkpoint_cells);
  }

  void Checkpoint(const PendingCells& pending) {
    if (unwritten_.empty()) {
      return;
    }
    const Clock::time_point start = Clock::now();
    // Chunks are disjoint ranges of the pending list (one claim counter): two that overlap
    // mean a cell was delivered twice (StoreBatch checks a chunk's first cell).
    std::sort(unwritten_.begin(), unwritten_.end());
    std::vector<std::uint64_t> cells;
    cells.reserve(unwritten_cells_);
    for (std::size_t k = 0; k < unwritten_.size(); ++k) {
      const auto [begin, end] = unwritten_[k];
      SB_DEMAND(k == 0 || unwritten_[k - 1].second <= begin, "a cell was delivered twice");
      for (std::uint64_t pos = begin; pos < end; ++pos) {
        cells.push_back(pending[pos]);
      }
    }
    file_->Write(data_, cells);  // their done flags, set in memory by StoreBatch, come last
    checkpointed_ += cells.size();
    unwritten_.clear();
    unwritten_cells_ = 0;
    last_checkpoint_ = Clock::now();
    last_checkpoint_s_ = Seconds(start);
    ++checkpoints_;
    checkpoint_s_ += last_checkpoint_s_;
  }

  bool AllDone() const {
    return std::all_of(data_.done.begin(), data_.done.end(), [](std::uint8_t d) { return d; });
  }

  // Writes the final cube from memory, then drops the checkpoint file. Cells the checkpoints
  // have not caught up with are not written there first (with very cheap cells on many ranks
  // they can be most of the cube): only when the final write fails does the checkpoint catch
  // up, so that --resume finds every cell and just writes the cube.
  void Finalize(const std::vector<SweepRecord>* records, const h5::ChunkFarm* farm,
                const PendingCells& pending, std::vector<FragilityStudy>* fragility) {
    try {
      WriteFinal(records, farm, false, fragility);
    } catch (...) {
      CatchUp(pending);
      throw;
    }
    DropCheckpoint();
  }

  // The final file: everything, or (cells_collectively) everything but the per-cell data and
  // complete = 1, which WriteFinalCellsCollective and CompleteFinalCube add.
  void WriteFinal(const std::vector<SweepRecord>* records, const h5::ChunkFarm* farm,
                  bool cells_collectively, std::vector<FragilityStudy>* fragility) {
    // From the whole cube, so a resumed sweep's statistics cover the cells of every run.
    const StudyTables study = MakeStudyTables(spec_, layout_, data_, records, fragility);
    h5::WriteFinalCube(options_.out, spec_, layout_, data_, run_, file_->CreatedUtc(), examples_,
                       &study, farm, cells_collectively);
  }

  // After a failed final write: the checkpoint catches up, so that --resume finds every cell.
  void CatchUp(const PendingCells& pending) {
    try {
      Checkpoint(pending);
    } catch (const std::exception&) {
      // The final write's failure is the one to report (the same disk, most likely).
    }
  }

  // After the final cube is in place.
  void DropCheckpoint() {
    file_->Close();
    file_.reset();
    std::error_code ec;
    std::filesystem::remove(PartialPath(options_.out), ec);
  }

  // Rank 0's cells for the collective final write: those of earlier runs (the gaps between
  // the runs of the pending list) and the ones it computed itself (ranges of pending
  // positions); O(those cells + runs), never a pass over the whole cube.
  h5::FinalCells RootCells(const PendingCells& pending,
                           const std::vector<std::pair<std::uint64_t, std::uint64_t>>& own) {
    h5::FinalCells mine;
    const std::vector<std::uint64_t> runs = pending.Flatten();  // (first cell, length) pairs
    std::uint64_t next = 0;
    for (std::size_t k = 0; k + 1 < runs.size(); k += 2) {
      for (std::uint64_t c = next; c < runs[k]; ++c) mine.cells.push_back(c);
      next = runs[k] + runs[k + 1];
    }
    for (std::uint64_t c = next; c < data_.Cells(); ++c) mine.cells.push_back(c);
    for (const auto& [begin, end] : own) {
      for (std::uint64_t pos = begin; pos < end; ++pos) mine.cells.push_back(pending[pos]);
    }
    std::sort(mine.cells.begin(), mine.cells.end());
    mine.data.Reset(mine.cells.size(), data_.responses.size());
    for (std::size_t i = 0; i < mine.cells.size(); ++i) {
      const std::uint64_t c = mine.cells[i];
      mine.data.status[i] = data_.status[c];
      mine.data.events[i] = data_.events[c];
      mine.data.steps[i] = data_.steps[c];
      mine.data.wall_s[i] = data_.wall_s[c];
      mine.data.run[i] = data_.run[c];
      mine.data.done[i] = data_.done[c];
      for (std::size_t r = 0; r < data_.responses.size(); ++r) {
        mine.data.responses[r][i] = data_.responses[r][c];
      }
    }
    return mine;
  }

  std::int32_t run() const { return run_; }
  const CubeData& data() const { return data_; }

  void FillReport(SweepReport& report) const {
    report.run = run_;
    report.cells_total = data_.Cells();
    report.cells_computed = computed_;
    report.checkpoints = checkpoints_;
    for (std::uint64_t c = 0; c < data_.Cells(); ++c) {
      if (data_.done[c] == 0) {
        continue;
      }
      ++report.cells_done;
      if (data_.status[c] != kStatusOk) {
        ++report.cells_failed;
        std::string name = "code " + std::to_string(data_.status[c]);
        for (const auto& [code, label] : layout_.status_names) {
          if (code == data_.status[c]) {
            name = label;
          }
        }
        ++report.failed_by_status[name];
      }
    }
  }

  std::uint64_t computed() const { return computed_; }
  double checkpoint_s() const { return checkpoint_s_; }
  std::uint64_t checkpointed() const { return checkpointed_; }
  std::uint64_t failed() const { return failed_; }
  std::uint64_t done_before() const { return done_before_; }
  void set_done_before(std::uint64_t n) { done_before_ = n; }

 private:
  const SweepSpec& spec_;
  const CubeLayout& layout_;
  const SweepOptions& options_;
  CubeData data_;
  std::optional<h5::CheckpointFile> file_;
  // Chunks received since the last checkpoint, as [begin, end) positions of the pending list.
  std::vector<std::pair<std::uint64_t, std::uint64_t>> unwritten_;
  std::uint64_t unwritten_cells_ = 0;
  double checkpoint_s_ = 0.0;
  double last_checkpoint_s_ = 0.0;  // how long the last checkpoint took [s]
  std::uint64_t checkpointed_ = 0;  // cells written by checkpoints in this run
  Clock::time_point last_checkpoint_ = Clock::now();
  std::uint64_t computed_ = 0;
  std::uint64_t failed_ = 0;
  std::uint64_t checkpoints_ = 0;
  std::uint64_t done_before_ = 0;
  std::int32_t run_ = 1;
  std::map<std::int32_t, std::string> examples_;  // one failure per status in this run
  std::map<std::int32_t, std::uint64_t> example_cells_;
};

// The cells a rank other than 0 computed in this run, from its kept batches (in pending order,
// which is cell order), for the collective final write.
h5::FinalCells KeptCells(std::vector<ResultBatch>& kept, const PendingCells& pending,
                         std::size_t responses, std::int32_t run) {
  std::sort(kept.begin(), kept.end(),
            [](const ResultBatch& a, const ResultBatch& b) { return a.begin < b.begin; });
  std::uint64_t n = 0;
  for (const ResultBatch& b : kept) n += b.Size();
  h5::FinalCells mine;
  mine.cells.reserve(n);
  mine.data.Reset(n, responses);
  std::uint64_t i = 0;
  for (ResultBatch& b : kept) {
    const std::uint64_t size = b.Size();
    for (std::uint64_t k = 0; k < size; ++k, ++i) {
      mine.cells.push_back(pending[b.begin + k]);
      mine.data.status[i] = b.status[k];
      mine.data.events[i] = b.events[k];
      mine.data.steps[i] = b.steps[k];
      mine.data.wall_s[i] = b.wall_s[k];
      mine.data.run[i] = run;
      mine.data.done[i] = 1;
      for (std::size_t r = 0; r < responses; ++r) {
        mine.data.responses[r][i] = b.values[r * size + k];
      }
    }
    b = ResultBatch{};  // its memory goes as soon as it is copied
  }
  return mine;
}

// Collective: rank 0 writes the final file without the per-cell data, every rank then writes
// its cells with parallel HDF5, rank 0 sets complete = 1 and renames. A failure anywhere makes
// rank 0's checkpoint catch up and removes FILE.tmp; returned on rank 0.
std::exception_ptr WriteFinalCollectively(
    const SweepSpec& spec, const CubeLayout& layout, const CellEvaluator& evaluator,
    Transport& transport, std::optional<Writer>& writer, const PendingCells& pending,
    const std::filesystem::path& out, std::vector<ResultBatch>& kept,
    const std::vector<std::pair<std::uint64_t, std::uint64_t>>& own,
    std::vector<FragilityStudy>* fragility) {
  const bool root = transport.Rank() == 0;
  std::exception_ptr failure;
  if (root) {
    try {
      writer->WriteFinal(evaluator.Records(), nullptr, true, fragility);
    } catch (...) {
      failure = std::current_exception();
    }
  }
  const std::string go =
      transport.BroadcastText(root && !failure ? std::to_string(writer->run()) : "");
  if (!go.empty()) {
    const h5::FinalCells mine =
        root ? writer->RootCells(pending, own)
             : KeptCells(kept, pending, layout.responses.size(), std::stoi(go));
    const std::string error = h5::WriteFinalCellsCollective(
        out, spec, layout, mine, [&](bool ok) { return transport.AllTrue(ok); });
    if (root) {
      try {
        if (!error.empty()) {
          throw h5::H5Error(error);
        }
        h5::CompleteFinalCube(out, spec);
        writer->DropCheckpoint();
      } catch (...) {
        failure = std::current_exception();
      }
    }
  }
  if (root && failure) {
    writer->CatchUp(pending);
    std::error_code ec;
    std::filesystem::remove(out.string() + ".tmp", ec);
  }
  return failure;
}

// The fragility fits of the final cube, collective: rank 0's columns go to every rank, each
// fits its share of the combinations (spectra::FitShare: point fit, cloud fit and bootstrap;
// the bits of a fit do not depend on the rank that makes it) and rank 0 gathers them. One rank
// fits them all when the columns would not fit one MPI message.
std::vector<FragilityStudy> ShareFragility(const SweepSpec& spec, const CubeLayout& layout,
                                           const std::optional<Writer>& writer,
                                           Transport& transport) {
  const bool root = transport.Rank() == 0;
  const double bytes = static_cast<double>(spec.CellCount()) *
                       (5.0 + 8.0 * (3.0 + 2.0 * static_cast<double>(spec.limit_states.size())));
  if (transport.Size() == 1 || bytes > 1e9) {
    return root ? MakeFragilityStudies(spec, layout, writer->data())
                : std::vector<FragilityStudy>{};
  }
  const std::string columns =
      transport.BroadcastText(root ? PackFragilityInputs(spec, layout, writer->data()) : "");
  const CubeData theirs = root ? CubeData{} : UnpackFragilityInputs(layout, columns);
  std::vector<FragilityStudy> studies = MakeFragilityStudies(
      spec, layout, root ? writer->data() : theirs, transport.Rank(), transport.Size());
  const std::vector<std::string> fitted = transport.GatherText(
      root ? std::string() : PackFits(studies, transport.Rank(), transport.Size()));
  if (root) {
    for (std::size_t r = 1; r < fitted.size(); ++r) MergeFits(studies, fitted[r]);
  }
  return studies;
}

}  // namespace

std::filesystem::path PartialPath(const std::filesystem::path& out) {
  return std::filesystem::path(out.string() + ".partial");
}

SweepReport RunSweep(const SweepSpec& spec, const CellEvaluator& evaluator, Transport& transport,
                     const SweepOptions& options) {
  SweepReport report;
  report.rank = transport.Rank();
  report.ranks = transport.Size();
  const bool root = transport.Rank() == 0;
  CubeLayout layout = MakeCubeLayout(evaluator, spec.responses, spec.source);
  layout.methods = SweepMethods(spec);

  // Every rank read and checksummed the inputs itself: all must have seen rank 0's bytes.
  const std::string root_identity = transport.BroadcastText(root ? spec.Hash() : "");
  if (!transport.AllTrue(root_identity == spec.Hash())) {
    throw InputError(spec.source +
                     ": the ranks read different inputs (a file changed while they read it); "
                     "run again once no input file is being written");
  }

  // Setup errors surface on every rank before any work.
  std::optional<Writer> writer;
  std::string setup = "run";
  const auto setup_error = [&options](const std::exception& e, bool h5) {
    return std::string("error:") + (h5 ? options.out.string() + ".partial: " : "") + e.what();
  };
  if (root) {
    writer.emplace(spec, layout, options);
    try {
      const Writer::Opened opened = writer->Open();
      setup = opened == Writer::Opened::kComplete   ? "complete"
              : opened == Writer::Opened::kToCreate ? "create"
                                                    : "run";
    } catch (const InputError& e) {
      setup = setup_error(e, false);
    } catch (const h5::H5Error& e) {
      setup = setup_error(e, true);
    }
  }
  setup = transport.BroadcastText(setup);
  if (setup.rfind("error:", 0) == 0) {
    throw InputError(setup.substr(6));
  }
  if (setup == "complete") {
    report.already_complete = true;
    report.complete = true;
    if (root) {
      report.cells_total = spec.CellCount();
      report.cells_done = spec.CellCount();
    }
    return report;
  }

  PendingCells pending;
  if (root) {
    pending = writer->Pending();
    writer->set_done_before(spec.CellCount() - pending.size());
  }
  transport.BroadcastPending(pending);
  const std::uint64_t total = pending.size();

  bool all_finished = transport.Size() == 1;
  // A fresh checkpoint file (its datasets filled in memory, then written: about 8 us per cell
  // of 154 datasets) is created by rank 0 while the other ranks claim and compute their first
  // cells. Should it fail, the claims stop, rank 0 drains and drops what was computed, and
  // every rank ends with the one error line, as for any setup error (below).
  std::string create_error;
  if (root && setup == "create") {
    try {
      writer->Create();
    } catch (const InputError& e) {
      create_error = setup_error(e, false);
    } catch (const h5::H5Error& e) {
      create_error = setup_error(e, true);
    }
    if (!create_error.empty()) {
      transport.StopClaims();
      while (!all_finished) {
        all_finished = transport.Receive([](std::span<const char>) {}, 0.05);
      }
    }
  }
  // The cells' time as rank 0 sees it (ranks > 0 may have begun during the creation above).
  const Clock::time_point start = Clock::now();
  Clock::time_point last_progress = start;

  auto progress = [&](bool force) {
    if (!root || !options.progress) {
      return;
    }
    if (!force && Seconds(last_progress) < options.progress_seconds) {
      return;
    }
    last_progress = Clock::now();
    SweepProgress p;
    p.cells_total = spec.CellCount();
    p.run_total = total;
    p.run_done = writer->computed();
    p.run_failed = writer->failed();
    p.cells_done = writer->done_before() + p.run_done;
    p.elapsed_s = Seconds(start);
    p.cells_per_s = p.elapsed_s > 0 ? static_cast<double>(p.run_done) / p.elapsed_s : 0.0;
    p.eta_s = p.cells_per_s > 0
                  ? static_cast<double>(total - std::min(total, p.run_done)) / p.cells_per_s
                  : 0.0;
    options.progress(p);
  };

  // The collective final write: every rank keeps what it computed (rank 0: where its cells are).
  const bool collective =
      transport.Size() > 1 && transport.Size() >= options.collective_final_from_ranks;
  std::vector<ResultBatch> kept;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> own;
  const auto store = [&](std::span<const char> bytes) {
    writer->StoreBatch(UnpackBatch(bytes), pending);
  };
  auto service = [&](double wait_s) {
    if (!all_finished) {
      all_finished = transport.Receive(store, wait_s);
    }
    if (writer->CheckpointDue()) {
      writer->Checkpoint(pending);
    }
    progress(false);
  };

  ResultBatch batch;
  const auto responses = static_cast<std::uint32_t>(layout.responses.size());
  bool stopping = false;
  std::uint64_t seen = 0;
  double cell_s = 0.0;  // this rank's mean cell time in its last chunk [s]
  const std::uint64_t work_block = evaluator.WorkBlock();
  const bool computes =
      create_error.empty() &&
      (!root || transport.Size() <= options.root_computes_up_to_ranks || transport.Size() == 1);
  while (computes && !stopping) {
    if (StopRequested(options)) {
      stopping = true;
      break;
    }
    const bool whole_blocks =  // once a cell's time is known: the first chunk is one cell
        work_block > 1 && cell_s > 0.0 &&
        static_cast<double>(work_block) * cell_s <= options.block_seconds &&
        work_block * 4 * static_cast<std::uint64_t>(transport.Size()) <= total;
    const auto [begin, end] = transport.Claim(
        ChunkSize(total, seen, transport.Size(), options, cell_s), whole_blocks ? work_block : 1);
    seen = end;
    if (begin >= end) {
      break;
    }
    batch.Reset(begin, end, responses);
    const Clock::time_point chunk_start = Clock::now();
    std::uint64_t done = 0;
    for (std::uint64_t pos = begin; pos < end; ++pos) {
      if (StopRequested(options)) {
        stopping = true;
        break;
      }
      EvaluateInto(spec, evaluator, layout, pending[pos], pos - begin, batch);
      ++done;
      if (root) {
        service(0.0);  // the others' results and checkpoints never wait for this chunk
      }
    }
    if (done == 0) {
      break;
    }
    batch.Truncate(done);
    report.cells_this_rank += done;
    ++report.chunks_this_rank;
    // A floor of 1 ns keeps a clock that did not advance from pinning chunks at one cell.
    cell_s = std::max(1e-9, Seconds(chunk_start) / static_cast<double>(done));
    if (root) {
      writer->StoreBatch(ViewOf(batch), pending);
      if (collective) {
        own.emplace_back(batch.begin, batch.begin + done);
      }
      service(0.0);
    } else {
      transport.Send(PackBatch(batch));
      if (collective) {
        kept.push_back(std::move(batch));
        batch = ResultBatch{};
      }
    }
  }

  if (root && !create_error.empty()) {
    // Nothing was computed here, and the other ranks' streams are drained.
  } else if (root) {
    if (stopping) {
      transport.StopClaims();
      if (writer->computed() > 0) {
        writer->Checkpoint(pending);  // secure what is here before waiting for the others
      }
    }
    // Rank 0 drains until every rank has ended its stream, even after a stop request (what is
    // here is already checkpointed): a rank whose last message found no receiver would wait
    // in Finish forever.
    bool stop_seen = stopping;
    while (!all_finished) {
      service(0.05);
      if (StopRequested(options) && !stop_seen) {
        stop_seen = true;  // rank 0 that only gathers learns of the stop here
        transport.StopClaims();
        writer->Checkpoint(pending);
      }
    }
    report.interrupted = StopRequested(options);
    // A complete sweep goes straight to the final cube (Finalize); anything else checkpoints.
    if (report.interrupted || !writer->AllDone()) {
      writer->Checkpoint(pending);
    }
    const ReceiveStats received = transport.Received();
    report.messages_received = received.messages;
    report.bytes_received = received.bytes;
    report.receive_busy_s = received.busy_s;
    report.checkpoint_s = writer->checkpoint_s();
    report.cells_checkpointed = writer->checkpointed();
  } else {
    transport.EndStream();
    report.interrupted = stopping;
  }
  report.wall_s = Seconds(start);

  // Every rank learns whether rank 0 writes the final cube: the others, idle now, then deflate
  // its chunks (the 0.65-1 us per cell that rank 0 would spend alone, docs/hdf5-layout.md).
  const bool farm = transport.Size() > 1 && options.farm_final_cube;
  std::string ending;
  if (root) {
    ending = !create_error.empty()                      ? create_error
             : !report.interrupted && writer->AllDone() ? "final"
                                                        : "";
  }
  ending = transport.BroadcastText(ending);
  if (ending.rfind("error:", 0) == 0) {
    transport.Finish();  // every stream drained: no rank is left waiting
    throw InputError(ending.substr(6));
  }
  const bool finalize = ending == "final";
  // The fragility fits, their bootstraps spread over the ranks, before the final write.
  std::optional<std::vector<FragilityStudy>> fragility;
  if (finalize && !spec.limit_states.empty()) {
    fragility = ShareFragility(spec, layout, writer, transport);
  }
  std::vector<FragilityStudy>* fits = root && fragility ? &*fragility : nullptr;
  std::exception_ptr failure;
  if (finalize && collective) {
    const Clock::time_point final_start = Clock::now();
    const double final_cpu_start = ThreadCpuSeconds();
    failure = WriteFinalCollectively(spec, layout, evaluator, transport, writer, pending,
                                     options.out, kept, own, fits);
    report.final_s = Seconds(final_start);  // on every rank: each does its share
    report.final_cpu_s = ThreadCpuSeconds() - final_cpu_start;
    if (root) {
      progress(true);
      report.complete = !failure;
    } else {
      failure = nullptr;  // rank 0 reports it
    }
  } else if (root) {
    progress(true);
    if (finalize) {
      const Clock::time_point final_start = Clock::now();
      const double final_cpu_start = ThreadCpuSeconds();
      bool farmed = false;
      const h5::ChunkFarm chunk_farm = [&](std::size_t count, const auto& job, const auto& done) {
        farmed = true;
        transport.Farm(count, job, h5::RunChunkJob, done);
      };
      try {
        writer->Finalize(evaluator.Records(), farm ? &chunk_farm : nullptr, pending, fits);
        report.complete = true;
      } catch (...) {
        failure = std::current_exception();
        if (farm && !farmed) {
          chunk_farm(
              0, [](std::size_t) { return std::vector<char>{}; },
              [](std::size_t, std::span<const char>) {});  // release the other ranks
        }
      }
      report.final_s = Seconds(final_start);
      report.final_cpu_s = ThreadCpuSeconds() - final_cpu_start;
    }
  } else if (finalize && farm) {
    transport.Farm(0, {}, h5::RunChunkJob, {});
  }
  // After the farm, so that a failed final write leaves no rank waiting (a clean exit 1).
  transport.Finish();
  if (failure) {
    std::rethrow_exception(failure);
  }
  if (root) {
    writer->FillReport(report);
  }
  return report;
}

}  // namespace skewbridge::jobs
