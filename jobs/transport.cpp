#include "jobs/transport.h"

#include <cstring>
#include <stdexcept>

#include "solver/common/error.h"

namespace skewbridge::jobs {
namespace {

template <typename T>
void Put(std::vector<char>& out, const T& v) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &v, sizeof(T));
}

template <typename T>
T Take(std::span<const char> bytes, std::size_t& at) {
  if (at + sizeof(T) > bytes.size()) {
    throw std::runtime_error("truncated cell record message");
  }
  T v;
  std::memcpy(&v, bytes.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}

class InProcessTransport final : public Transport {
 public:
  int Rank() const override { return 0; }
  int Size() const override { return 1; }
  std::string BroadcastText(const std::string& text) override { return text; }
  void BroadcastPending(std::vector<std::uint64_t>& pending) override {
    size_ = pending.size();
    next_ = 0;
  }
  std::pair<std::uint64_t, std::uint64_t> Claim(std::uint64_t count) override {
    const std::uint64_t begin = std::min(next_, size_);
    next_ = std::min(size_, begin + count);
    return {begin, next_};
  }
  void StopClaims() override { next_ = size_; }
  void Send(std::span<const CellRecord>, bool) override { SB_DEMAND(false, "rank 0 never sends"); }
  bool Receive(std::vector<CellRecord>&, double) override { return true; }
  void Finish() override {}

 private:
  std::uint64_t size_ = 0;
  std::uint64_t next_ = 0;
};

}  // namespace

std::vector<char> PackRecords(std::span<const CellRecord> records, bool last) {
  std::vector<char> out;
  Put<std::uint8_t>(out, last ? 1 : 0);
  Put<std::uint64_t>(out, records.size());
  for (const CellRecord& r : records) {
    Put(out, r.cell);
    Put(out, r.status);
    Put(out, r.stats.events);
    Put(out, r.stats.steps);
    Put(out, r.stats.wall_s);
    Put<std::uint64_t>(out, r.values.size());
    for (double v : r.values) {
      Put(out, v);
    }
    Put<std::uint64_t>(out, r.text.size());
    const std::size_t at = out.size();
    out.resize(at + r.text.size());
    std::memcpy(out.data() + at, r.text.data(), r.text.size());
  }
  return out;
}

bool UnpackRecords(std::span<const char> bytes, std::vector<CellRecord>& out) {
  std::size_t at = 0;
  const bool last = Take<std::uint8_t>(bytes, at) != 0;
  const auto n = Take<std::uint64_t>(bytes, at);
  for (std::uint64_t i = 0; i < n; ++i) {
    CellRecord r;
    r.cell = Take<std::uint64_t>(bytes, at);
    r.status = Take<std::int32_t>(bytes, at);
    r.stats.events = Take<std::int64_t>(bytes, at);
    r.stats.steps = Take<std::int64_t>(bytes, at);
    r.stats.wall_s = Take<double>(bytes, at);
    const auto k = Take<std::uint64_t>(bytes, at);
    if (k > bytes.size()) {
      throw std::runtime_error("corrupt cell record message");
    }
    for (std::uint64_t j = 0; j < k; ++j) {
      r.values.push_back(Take<double>(bytes, at));
    }
    const auto length = Take<std::uint64_t>(bytes, at);
    if (length > bytes.size() - at) {
      throw std::runtime_error("truncated cell record message");
    }
    r.text.assign(bytes.data() + at, length);
    at += length;
    out.push_back(std::move(r));
  }
  return last;
}

std::unique_ptr<Transport> MakeInProcessTransport() {
  return std::make_unique<InProcessTransport>();
}

}  // namespace skewbridge::jobs
