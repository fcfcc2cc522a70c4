#include "jobs/mpi/mpi_transport.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <ctime>
#include <deque>
#include <exception>
#include <limits>
#include <list>
#include <thread>

#include "solver/common/error.h"

namespace skewbridge::jobs {
namespace {

constexpr int kRecordTag = 7101;
constexpr int kJobTag = 7102;     // rank 0 -> a rank: a job; 0 bytes = stop
constexpr int kResultTag = 7103;  // a rank -> rank 0: the result of its oldest job
constexpr int kJobsInFlight = 2;  // per rank: one to work on, one already waiting
// Up to this many ranks rank 0 also runs farm jobs itself: it is then a large share of the
// workers (half with 2 ranks), and a job of its own delays the others' results by one job only.
constexpr int kRootWorksUpToRanks = 4;

void CheckMpi(int code, const char* what) { SB_DEMAND(code == MPI_SUCCESS, what); }

// CPU time of the calling thread [s]: what handling a message costs rank 0, unaffected by the
// time it spends descheduled on a shared or oversubscribed node.
double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

class MpiTransport final : public Transport {
 public:
  MpiTransport() {
    CheckMpi(MPI_Comm_dup(MPI_COMM_WORLD, &comm_), "MPI_Comm_dup");
    CheckMpi(MPI_Comm_rank(comm_, &rank_), "MPI_Comm_rank");
    CheckMpi(MPI_Comm_size(comm_, &size_), "MPI_Comm_size");
    const MPI_Aint bytes = rank_ == 0 ? static_cast<MPI_Aint>(sizeof(std::uint64_t)) : 0;
    CheckMpi(
        MPI_Win_allocate(bytes, sizeof(std::uint64_t), MPI_INFO_NULL, comm_, &counter_, &window_),
        "MPI_Win_allocate");
    if (rank_ == 0) {
      CheckMpi(MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, window_), "MPI_Win_lock");
      *counter_ = 0;
      CheckMpi(MPI_Win_unlock(0, window_), "MPI_Win_unlock");
    }
    CheckMpi(MPI_Barrier(comm_), "MPI_Barrier");
  }

  // Freeing the window and the communicator is collective, so it happens in Finish(); after
  // an error on one rank they are left to MPI_Finalize or MPI_Abort rather than risk a hang.
  ~MpiTransport() override = default;

  int Rank() const override { return rank_; }
  int Size() const override { return size_; }

  std::string BroadcastText(const std::string& text) override {
    std::uint64_t n = text.size();
    CheckMpi(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm_), "MPI_Bcast");
    std::string out = rank_ == 0 ? text : std::string(n, '\0');
    CheckMpi(MPI_Bcast(out.data(), static_cast<int>(n), MPI_CHAR, 0, comm_), "MPI_Bcast");
    return out;
  }

  void BroadcastPending(PendingCells& pending) override {
    // As runs of consecutive cells: 16 bytes per run, whatever the number of cells.
    std::vector<std::uint64_t> flat = rank_ == 0 ? pending.Flatten() : std::vector<std::uint64_t>{};
    std::uint64_t words = flat.size();
    CheckMpi(MPI_Bcast(&words, 1, MPI_UINT64_T, 0, comm_), "MPI_Bcast");
    flat.resize(words);
    constexpr std::uint64_t kPiece = 1 << 26;  // MPI counts are int
    for (std::uint64_t at = 0; at < words; at += kPiece) {
      CheckMpi(MPI_Bcast(flat.data() + at, static_cast<int>(std::min(kPiece, words - at)),
                         MPI_UINT64_T, 0, comm_),
               "MPI_Bcast");
    }
    if (rank_ != 0) {
      pending = PendingCells::FromFlat(flat);
    }
    const std::uint64_t n = pending.size();
    total_ = n;
    if (rank_ == 0) {
      CheckMpi(MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, window_), "MPI_Win_lock");
      *counter_ = 0;
      CheckMpi(MPI_Win_unlock(0, window_), "MPI_Win_unlock");
    }
    CheckMpi(MPI_Barrier(comm_), "MPI_Barrier");
  }

  std::pair<std::uint64_t, std::uint64_t> Claim(std::uint64_t count, std::uint64_t block) override {
    if (block <= 1) {
      const std::uint64_t old = FetchAdd(count);
      const std::uint64_t begin = std::min(old, total_);
      return {begin, std::min(total_, begin + count)};
    }
    // The end depends on the counter's value: read and written under an exclusive lock, which
    // no other claim (a shared lock's fetch-and-add) can enter. Past the end (every position
    // handed out, or StopClaims): an empty claim, the counter left as it is.
    std::uint64_t begin = 0;
    CheckMpi(MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, window_), "MPI_Win_lock");
    CheckMpi(MPI_Get(&begin, 1, MPI_UINT64_T, 0, 0, 1, MPI_UINT64_T, window_), "MPI_Get");
    CheckMpi(MPI_Win_flush(0, window_), "MPI_Win_flush");
    const std::uint64_t end = begin < total_ ? std::min(total_, BlockEnd(begin + count, block)) : 0;
    if (begin < total_) {
      CheckMpi(MPI_Put(&end, 1, MPI_UINT64_T, 0, 0, 1, MPI_UINT64_T, window_), "MPI_Put");
    }
    CheckMpi(MPI_Win_unlock(0, window_), "MPI_Win_unlock");
    if (begin >= total_) return {total_, total_};
    return {begin, end};
  }

  void StopClaims() override { FetchAdd(total_ + 1); }

  void Send(std::vector<char> message) override {
    SB_DEMAND(rank_ != 0, "rank 0 never sends");
    SB_DEMAND(!message.empty(), "an empty message would end the stream");
    Post(std::move(message));
  }

  // The end of a stream is a message of zero bytes: every batch has a header, and MPI keeps
  // the order of messages between two ranks on one tag, so it arrives after the last batch.
  void EndStream() override {
    SB_DEMAND(rank_ != 0, "rank 0 never sends");
    Post({});
  }

  bool Receive(const std::function<void(std::span<const char>)>& handle, double wait_s) override {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_s);
    bool got_any = false;
    // Between tries, sleeps of 10 us doubling to 200 us: a message that arrives soon is taken
    // within tens of microseconds, a long wait wakes rank 0 at most 5 000 times a second.
    auto nap = std::chrono::microseconds(10);
    while (finished_ < size_ - 1) {
      int flag = 0;
      MPI_Status status;
      CheckMpi(MPI_Iprobe(MPI_ANY_SOURCE, kRecordTag, comm_, &flag, &status), "MPI_Iprobe");
      if (flag) {
        const double found = ThreadCpuSeconds();
        int bytes = 0;
        CheckMpi(MPI_Get_count(&status, MPI_BYTE, &bytes), "MPI_Get_count");
        // One buffer for every message: rank 0 allocates only when a larger batch arrives.
        if (buffer_.size() < static_cast<std::size_t>(bytes)) {
          buffer_.resize(static_cast<std::size_t>(bytes));
        }
        CheckMpi(MPI_Recv(buffer_.data(), bytes, MPI_BYTE, status.MPI_SOURCE, kRecordTag, comm_,
                          MPI_STATUS_IGNORE),
                 "MPI_Recv");
        if (bytes == 0) {
          ++finished_;
        } else {
          handle(std::span<const char>(buffer_.data(), static_cast<std::size_t>(bytes)));
          ++received_.messages;
          received_.bytes += static_cast<std::uint64_t>(bytes);
          received_.busy_s += ThreadCpuSeconds() - found;
        }
        got_any = true;
        continue;
      }
      if (got_any || std::chrono::steady_clock::now() >= deadline) {
        break;
      }
      std::this_thread::sleep_for(nap);
      nap = std::min(2 * nap, std::chrono::microseconds(200));
    }
    return finished_ == size_ - 1;
  }

  ReceiveStats Received() const override { return received_; }

  bool AllTrue(bool mine) override {
    int flag = mine ? 1 : 0;
    int all = 0;
    CheckMpi(MPI_Allreduce(&flag, &all, 1, MPI_INT, MPI_LAND, comm_), "MPI_Allreduce");
    return all != 0;
  }

  std::vector<std::string> GatherText(const std::string& mine) override {
    SB_DEMAND(mine.size() <= static_cast<std::size_t>(std::numeric_limits<int>::max()),
              "a gathered text exceeds MPI's int count");
    int n = static_cast<int>(mine.size());
    std::vector<int> sizes(rank_ == 0 ? static_cast<std::size_t>(size_) : 0);
    CheckMpi(MPI_Gather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, comm_), "MPI_Gather");
    std::vector<int> offsets(sizes.size(), 0);
    std::size_t total = 0;
    for (std::size_t r = 0; r < sizes.size(); ++r) {
      SB_DEMAND(total + static_cast<std::size_t>(sizes[r]) <=
                    static_cast<std::size_t>(std::numeric_limits<int>::max()),
                "gathered texts exceed MPI's int count");
      offsets[r] = static_cast<int>(total);
      total += static_cast<std::size_t>(sizes[r]);
    }
    std::string all(total, '\0');
    CheckMpi(MPI_Gatherv(mine.data(), n, MPI_CHAR, all.data(), sizes.data(), offsets.data(),
                         MPI_CHAR, 0, comm_),
             "MPI_Gatherv");
    std::vector<std::string> out;
    for (std::size_t r = 0; r < sizes.size(); ++r) {
      out.push_back(
          all.substr(static_cast<std::size_t>(offsets[r]), static_cast<std::size_t>(sizes[r])));
    }
    return out;
  }

  // Rank 0 keeps kJobsInFlight jobs at every other rank and hands the next job to whichever
  // returns a result (dynamic, as the cells); then a zero-byte job tells each rank to stop.
  // MPI keeps the order of messages between two ranks, so a rank's results come back in the
  // order of its jobs: rank 0 keeps the job numbers of each rank in a queue and the messages
  // carry nothing but the bytes. With few ranks rank 0 runs the next job itself whenever no
  // result is waiting, and a rank sends its result without waiting for rank 0 to take it (it
  // may be in a job of its own), going on with the job already waiting.
  void Farm(std::size_t count, const std::function<std::vector<char>(std::size_t)>& job,
            const std::function<std::vector<char>(std::span<const char>)>& work,
            const std::function<void(std::size_t, std::span<const char>)>& done) override {
    if (size_ == 1) {
      Transport::Farm(count, job, work, done);
      return;
    }
    if (rank_ != 0) {
      std::vector<char> in;
      std::list<Outgoing> results;  // a list: Isend buffers must not move
      while (true) {
        const int bytes = ProbeSleeping(0, kJobTag);
        in.resize(static_cast<std::size_t>(bytes));
        CheckMpi(MPI_Recv(in.data(), bytes, MPI_BYTE, 0, kJobTag, comm_, MPI_STATUS_IGNORE),
                 "MPI_Recv");
        if (bytes == 0) {
          break;
        }
        results.push_back({work(in), MPI_REQUEST_NULL});
        Outgoing& result = results.back();
        SB_DEMAND(result.bytes.size() <= static_cast<std::size_t>(std::numeric_limits<int>::max()),
                  "a farm result exceeds MPI's int count");
        CheckMpi(MPI_Isend(result.bytes.data(), static_cast<int>(result.bytes.size()), MPI_BYTE, 0,
                           kResultTag, comm_, &result.request),
                 "MPI_Isend");
        ReapSends(results);
      }
      for (Outgoing& result : results) {
        CheckMpi(MPI_Wait(&result.request, MPI_STATUS_IGNORE), "MPI_Wait");
      }
      return;
    }
    std::list<Outgoing> sends;  // a list: Isend buffers must not move
    std::vector<std::deque<std::size_t>> queued(static_cast<std::size_t>(size_));
    std::size_t next = 0;
    std::size_t outstanding = 0;
    std::exception_ptr error;
    auto send = [&](int to, std::vector<char> bytes) {
      SB_DEMAND(bytes.size() <= static_cast<std::size_t>(std::numeric_limits<int>::max()),
                "a farm job exceeds MPI's int count");
      sends.push_back({std::move(bytes), MPI_REQUEST_NULL});
      Outgoing& msg = sends.back();
      CheckMpi(MPI_Isend(msg.bytes.data(), static_cast<int>(msg.bytes.size()), MPI_BYTE, to,
                         kJobTag, comm_, &msg.request),
               "MPI_Isend");
    };
    auto hand_out = [&](int to) {
      if (error || next >= count) {
        return;
      }
      try {
        send(to, job(next));
      } catch (...) {
        error = std::current_exception();
        return;
      }
      queued[static_cast<std::size_t>(to)].push_back(next);
      ++next;
      ++outstanding;
    };
    for (int k = 0; k < kJobsInFlight; ++k) {
      for (int to = 1; to < size_; ++to) {
        hand_out(to);
      }
    }
    const bool root_works = size_ <= kRootWorksUpToRanks;
    while (outstanding > 0 || (root_works && !error && next < count)) {
      MPI_Status status;
      int waiting = 0;
      CheckMpi(MPI_Iprobe(MPI_ANY_SOURCE, kResultTag, comm_, &waiting, &status), "MPI_Iprobe");
      if (!waiting && root_works && !error && next < count) {
        const std::size_t index = next++;
        try {
          const std::vector<char> result = work(job(index));
          done(index, result);
        } catch (...) {
          error = std::current_exception();  // no more jobs; results on their way are drained
        }
        continue;
      }
      const int bytes =
          waiting ? CountOf(status) : ProbeSleeping(MPI_ANY_SOURCE, kResultTag, &status);
      if (buffer_.size() < static_cast<std::size_t>(bytes)) {
        buffer_.resize(static_cast<std::size_t>(bytes));
      }
      CheckMpi(MPI_Recv(buffer_.data(), bytes, MPI_BYTE, status.MPI_SOURCE, kResultTag, comm_,
                        MPI_STATUS_IGNORE),
               "MPI_Recv");
      --outstanding;
      std::deque<std::size_t>& mine = queued[static_cast<std::size_t>(status.MPI_SOURCE)];
      SB_DEMAND(!mine.empty(), "a farm result without a job");
      const std::size_t index = mine.front();
      mine.pop_front();
      if (!error) {
        try {
          done(index, std::span<const char>(buffer_.data(), static_cast<std::size_t>(bytes)));
        } catch (...) {
          error = std::current_exception();  // no more jobs; results on their way are drained
        }
      }
      hand_out(status.MPI_SOURCE);
      ReapSends(sends);
    }
    for (int to = 1; to < size_; ++to) {
      send(to, {});
    }
    for (Outgoing& msg : sends) {
      CheckMpi(MPI_Wait(&msg.request, MPI_STATUS_IGNORE), "MPI_Wait");
    }
    if (error) {
      std::rethrow_exception(error);
    }
  }

  void Finish() override {
    Reap(true);
    CheckMpi(MPI_Barrier(comm_), "MPI_Barrier");
    CheckMpi(MPI_Win_free(&window_), "MPI_Win_free");
    CheckMpi(MPI_Comm_free(&comm_), "MPI_Comm_free");
  }

 private:
  // The byte count of a probed message.
  static int CountOf(const MPI_Status& status) {
    int bytes = 0;
    CheckMpi(MPI_Get_count(&status, MPI_BYTE, &bytes), "MPI_Get_count");
    return bytes;
  }

  // Waits for a message (MPI_Iprobe, sleeping 20 us between tries: a blocking MPI_Probe spins
  // and would take the core from the ranks computing beside it) and returns its byte count.
  int ProbeSleeping(int source, int tag, MPI_Status* out = nullptr) {
    MPI_Status status;
    while (true) {
      int flag = 0;
      CheckMpi(MPI_Iprobe(source, tag, comm_, &flag, &status), "MPI_Iprobe");
      if (flag) {
        break;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(20));
    }
    int bytes = 0;
    CheckMpi(MPI_Get_count(&status, MPI_BYTE, &bytes), "MPI_Get_count");
    if (out != nullptr) {
      *out = status;
    }
    return bytes;
  }

  struct Outgoing {
    std::vector<char> bytes;
    MPI_Request request;
  };

  // Frees the buffers of the sends that have completed.
  static void ReapSends(std::list<Outgoing>& sends) {
    for (auto it = sends.begin(); it != sends.end();) {
      int complete = 0;
      CheckMpi(MPI_Test(&it->request, &complete, MPI_STATUS_IGNORE), "MPI_Test");
      it = complete ? sends.erase(it) : std::next(it);
    }
  }

  std::uint64_t FetchAdd(std::uint64_t add) {
    std::uint64_t old = 0;
    CheckMpi(MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, window_), "MPI_Win_lock");
    CheckMpi(MPI_Fetch_and_op(&add, &old, MPI_UINT64_T, 0, 0, MPI_SUM, window_),
             "MPI_Fetch_and_op");
    CheckMpi(MPI_Win_unlock(0, window_), "MPI_Win_unlock");
    return old;
  }

  void Post(std::vector<char> bytes) {
    Reap(false);
    SB_DEMAND(bytes.size() <= static_cast<std::size_t>(std::numeric_limits<int>::max()),
              "a result batch exceeds MPI's int count");
    pending_sends_.push_back({std::move(bytes), MPI_REQUEST_NULL});
    Outgoing& msg = pending_sends_.back();
    CheckMpi(MPI_Isend(msg.bytes.data(), static_cast<int>(msg.bytes.size()), MPI_BYTE, 0,
                       kRecordTag, comm_, &msg.request),
             "MPI_Isend");
  }

  // Frees the buffers of completed sends (all of them when `wait`).
  void Reap(bool wait) {
    for (auto it = pending_sends_.begin(); it != pending_sends_.end();) {
      int done = 0;
      if (wait) {
        CheckMpi(MPI_Wait(&it->request, MPI_STATUS_IGNORE), "MPI_Wait");
        done = 1;
      } else {
        CheckMpi(MPI_Test(&it->request, &done, MPI_STATUS_IGNORE), "MPI_Test");
      }
      it = done ? pending_sends_.erase(it) : std::next(it);
    }
  }

  MPI_Comm comm_ = MPI_COMM_NULL;
  MPI_Win window_ = MPI_WIN_NULL;
  std::uint64_t* counter_ = nullptr;
  int rank_ = 0;
  int size_ = 1;
  std::uint64_t total_ = 0;
  int finished_ = 0;
  std::list<Outgoing> pending_sends_;  // a list: Isend buffers must not move
  std::vector<char> buffer_;           // rank 0's receive buffer, reused
  ReceiveStats received_;
};

}  // namespace

MpiSession::MpiSession() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  SB_DEMAND(!initialized, "MPI initialised twice");
  CheckMpi(MPI_Init(nullptr, nullptr), "MPI_Init");
}

MpiSession::~MpiSession() { MPI_Finalize(); }

int MpiSession::Rank() const {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int MpiSession::Size() const {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

int MpiSession::FirstRankWith(bool flag) const {
  const int mine = flag ? Rank() : Size();
  int first = mine;
  CheckMpi(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD), "MPI_Allreduce");
  return first;
}

void MpiSession::Barrier() const { CheckMpi(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier"); }

void AbortAll(int code) { MPI_Abort(MPI_COMM_WORLD, code); }

std::unique_ptr<Transport> MakeMpiTransport() { return std::make_unique<MpiTransport>(); }

}  // namespace skewbridge::jobs
