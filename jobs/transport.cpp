#include "jobs/transport.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "solver/common/error.h"

namespace skewbridge::jobs {
namespace {

constexpr std::uint32_t kBatchMagic = 0x31524253;  // "SBR1" in little-endian bytes

template <typename T>
void Put(std::vector<char>& out, const T& v) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &v, sizeof(T));
}

template <typename T>
void PutColumn(std::vector<char>& out, const std::vector<T>& column) {
  const std::size_t at = out.size();
  const std::size_t bytes = column.size() * sizeof(T);
  out.resize(at + bytes);
  if (bytes > 0) {
    std::memcpy(out.data() + at, column.data(), bytes);
  }
}

template <typename T>
T Take(std::span<const char> bytes, std::size_t& at) {
  if (at + sizeof(T) > bytes.size()) {
    throw std::runtime_error("truncated result batch message");
  }
  T v;
  std::memcpy(&v, bytes.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}

const char* TakeColumn(std::span<const char> bytes, std::size_t& at, std::uint64_t column_bytes) {
  if (column_bytes > bytes.size() - at) {
    throw std::runtime_error("truncated result batch message");
  }
  const char* p = bytes.data() + at;
  at += column_bytes;
  return p;
}

class InProcessTransport final : public Transport {
 public:
  int Rank() const override { return 0; }
  int Size() const override { return 1; }
  std::string BroadcastText(const std::string& text) override { return text; }
  void BroadcastPending(PendingCells& pending) override {
    size_ = pending.size();
    next_ = 0;
  }
  std::pair<std::uint64_t, std::uint64_t> Claim(std::uint64_t count, std::uint64_t block) override {
    const std::uint64_t begin = std::min(next_, size_);
    next_ = std::min(size_, BlockEnd(begin + count, block));
    return {begin, next_};
  }
  void StopClaims() override { next_ = size_; }
  void Send(std::vector<char>) override { SB_DEMAND(false, "rank 0 never sends"); }
  void EndStream() override { SB_DEMAND(false, "rank 0 never sends"); }
  bool Receive(const std::function<void(std::span<const char>)>&, double) override { return true; }
  void Finish() override {}

 private:
  std::uint64_t size_ = 0;
  std::uint64_t next_ = 0;
};

}  // namespace

void PendingCells::Append(std::uint64_t cell) {
  if (size_ > 0) {
    SB_DEMAND(cell > last_, "pending cells must increase");
    if (cell == last_ + 1) {
      ++size_;
      last_ = cell;
      return;
    }
  }
  last_ = cell;
  run_first_cell_.push_back(cell);
  run_first_pos_.push_back(size_);
  ++size_;
}

std::uint64_t PendingCells::operator[](std::uint64_t pos) const {
  SB_DEMAND(pos < size_, "pending position out of range");
  // The last run starting at or before pos.
  const auto it = std::upper_bound(run_first_pos_.begin(), run_first_pos_.end(), pos);
  const auto run = static_cast<std::size_t>(it - run_first_pos_.begin()) - 1;
  return run_first_cell_[run] + (pos - run_first_pos_[run]);
}

std::vector<std::uint64_t> PendingCells::Flatten() const {
  std::vector<std::uint64_t> flat;
  flat.reserve(2 * Runs());
  for (std::size_t r = 0; r < Runs(); ++r) {
    const std::uint64_t end = r + 1 < Runs() ? run_first_pos_[r + 1] : size_;
    flat.push_back(run_first_cell_[r]);
    flat.push_back(end - run_first_pos_[r]);
  }
  return flat;
}

PendingCells PendingCells::FromFlat(const std::vector<std::uint64_t>& flat) {
  if (flat.size() % 2 != 0) {
    throw std::runtime_error("pending runs: odd length");
  }
  PendingCells pending;
  for (std::size_t i = 0; i < flat.size(); i += 2) {
    const std::uint64_t first = flat[i];
    const std::uint64_t length = flat[i + 1];
    if (length == 0 || (pending.size_ > 0 && first <= pending.last_)) {
      throw std::runtime_error("pending runs: empty or unsorted");
    }
    pending.run_first_cell_.push_back(first);
    pending.run_first_pos_.push_back(pending.size_);
    pending.size_ += length;
    pending.last_ = first + length - 1;
  }
  return pending;
}

void ResultBatch::Reset(std::uint64_t from, std::uint64_t to, std::uint32_t response_count) {
  SB_DEMAND(from <= to, "a batch ends before it begins");
  begin = from;
  end = to;
  responses = response_count;
  const std::size_t n = to - from;
  status.assign(n, kStatusNotDone);
  events.assign(n, 0);
  steps.assign(n, 0);
  wall_s.assign(n, 0.0);
  values.assign(n * response_count, 0.0);
  failures.clear();
}

void ResultBatch::Truncate(std::uint64_t count) {
  const std::size_t n = Size();
  if (count >= n) {
    return;
  }
  // Response-major: response r moves from r * n to r * count.
  for (std::size_t r = 1; r < responses; ++r) {
    std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(r * n), count,
                values.begin() + static_cast<std::ptrdiff_t>(r * count));
  }
  values.resize(count * responses);
  status.resize(count);
  events.resize(count);
  steps.resize(count);
  wall_s.resize(count);
  end = begin + count;
}

std::vector<char> PackBatch(const ResultBatch& batch) {
  const std::uint64_t n = batch.Size();
  SB_DEMAND(batch.status.size() == n && batch.events.size() == n && batch.steps.size() == n &&
                batch.wall_s.size() == n && batch.values.size() == n * batch.responses,
            "a result batch's columns disagree with its size");
  std::vector<char> out;
  out.reserve(40 + n * (4 + 8 + 8 + 8 + 8 * batch.responses));
  Put(out, kBatchMagic);
  Put(out, batch.responses);
  Put(out, batch.begin);
  Put(out, batch.end);
  Put<std::uint64_t>(out, batch.failures.size());
  PutColumn(out, batch.status);
  PutColumn(out, batch.events);
  PutColumn(out, batch.steps);
  PutColumn(out, batch.wall_s);
  PutColumn(out, batch.values);
  for (const FailureNote& note : batch.failures) {
    Put(out, note.status);
    Put(out, note.count);
    Put(out, note.lowest_cell);
    Put<std::uint64_t>(out, note.text.size());
    const std::size_t at = out.size();
    out.resize(at + note.text.size());
    std::memcpy(out.data() + at, note.text.data(), note.text.size());
  }
  return out;
}

BatchView UnpackBatch(std::span<const char> bytes) {
  std::size_t at = 0;
  if (Take<std::uint32_t>(bytes, at) != kBatchMagic) {
    throw std::runtime_error("not a result batch message");
  }
  BatchView view;
  view.responses = Take<std::uint32_t>(bytes, at);
  view.begin = Take<std::uint64_t>(bytes, at);
  view.end = Take<std::uint64_t>(bytes, at);
  const auto notes = Take<std::uint64_t>(bytes, at);
  if (view.end < view.begin || view.end - view.begin > bytes.size() || notes > bytes.size()) {
    throw std::runtime_error("corrupt result batch message");
  }
  const std::uint64_t n = view.end - view.begin;
  view.status = TakeColumn(bytes, at, n * sizeof(std::int32_t));
  view.events = TakeColumn(bytes, at, n * sizeof(std::int64_t));
  view.steps = TakeColumn(bytes, at, n * sizeof(std::int64_t));
  view.wall_s = TakeColumn(bytes, at, n * sizeof(double));
  view.values = TakeColumn(bytes, at, n * view.responses * sizeof(double));
  for (std::uint64_t k = 0; k < notes; ++k) {
    FailureNote note;
    note.status = Take<std::int32_t>(bytes, at);
    note.count = Take<std::uint64_t>(bytes, at);
    note.lowest_cell = Take<std::uint64_t>(bytes, at);
    const auto length = Take<std::uint64_t>(bytes, at);
    if (length > bytes.size() - at) {
      throw std::runtime_error("truncated result batch message");
    }
    note.text.assign(bytes.data() + at, length);
    at += length;
    view.failures.push_back(std::move(note));
  }
  if (at != bytes.size()) {
    throw std::runtime_error("result batch message has trailing bytes");
  }
  return view;
}

BatchView ViewOf(const ResultBatch& batch) {
  BatchView view;
  view.begin = batch.begin;
  view.end = batch.end;
  view.responses = batch.responses;
  view.status = reinterpret_cast<const char*>(batch.status.data());
  view.events = reinterpret_cast<const char*>(batch.events.data());
  view.steps = reinterpret_cast<const char*>(batch.steps.data());
  view.wall_s = reinterpret_cast<const char*>(batch.wall_s.data());
  view.values = reinterpret_cast<const char*>(batch.values.data());
  view.failures = batch.failures;
  return view;
}

void Transport::Farm(std::size_t count, const std::function<std::vector<char>(std::size_t)>& job,
                     const std::function<std::vector<char>(std::span<const char>)>& work,
                     const std::function<void(std::size_t, std::span<const char>)>& done) {
  for (std::size_t i = 0; i < count; ++i) {
    const std::vector<char> result = work(job(i));
    done(i, result);
  }
}

std::unique_ptr<Transport> MakeInProcessTransport() {
  return std::make_unique<InProcessTransport>();
}

}  // namespace skewbridge::jobs
