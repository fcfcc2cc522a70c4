#include "jobs/stop_signal.h"

#include "solver/common/error.h"

namespace skewbridge::jobs {
namespace {

// A signal handler can only reach process-wide state; this flag is that state, owned by the
// one StopSignal object alive.
volatile std::sig_atomic_t g_stop = 0;
bool g_installed = false;
struct sigaction g_previous_term {};
struct sigaction g_previous_int {};

extern "C" void OnStopSignal(int signal_number) { g_stop = signal_number; }

}  // namespace

StopSignal::StopSignal() {
  SB_DEMAND(!g_installed, "one StopSignal at a time");
  g_installed = true;
  g_stop = 0;
  struct sigaction action {};
  action.sa_handler = OnStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, &g_previous_term);
  sigaction(SIGINT, &action, &g_previous_int);
}

StopSignal::~StopSignal() {
  sigaction(SIGTERM, &g_previous_term, nullptr);
  sigaction(SIGINT, &g_previous_int, nullptr);
  g_installed = false;
}

const volatile std::sig_atomic_t* StopSignal::Flag() const { return &g_stop; }

int StopSignal::Received() const { return static_cast<int>(g_stop); }

}  // namespace skewbridge::jobs
