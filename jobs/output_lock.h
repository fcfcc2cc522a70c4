#pragma once
/// @file
/// One writer per cube: the output path is checked before any work, and the process that
/// writes a cube holds an advisory lock (flock) on FILE.lock beside it for the whole run.

#include <filesystem>
#include <string>

namespace skewbridge::jobs {

/// The lock file of the cube `out`: out + ".lock".
std::filesystem::path LockPath(const std::filesystem::path& out);

/// Checks what can be known of an output path before any work: not empty, not a folder (nor
/// FILE.partial), and its folder exists.
/// @throws InputError naming the path ("--out" when empty) and what is allowed.
void CheckOutputPath(const std::filesystem::path& out);

/// An exclusive advisory lock (flock) on FILE.lock, which holds "pid host" of its holder.
/// The kernel releases a flock when its process dies, so the file of a killed run is a stale
/// lock that the next writer takes over. Released (and the file removed) on destruction.
class OutputLock {
 public:
  /// Takes the lock of `out` without waiting.
  /// @throws InputError when another process holds it (naming its pid and host), or when the
  ///         lock file cannot be created (e.g. a folder without write permission), with the
  ///         system's reason.
  explicit OutputLock(const std::filesystem::path& out);
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace skewbridge::jobs
