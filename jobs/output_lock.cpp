#include "jobs/output_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "solver/common/error.h"

namespace skewbridge::jobs {
namespace {

std::string Reason(int error) { return std::strerror(error); }

// The holder's "pid host", as it wrote it (empty when unreadable).
std::string Holder(int fd) {
  char buffer[256] = {};
  const ssize_t n = ::pread(fd, buffer, sizeof buffer - 1, 0);
  std::string text = n > 0 ? std::string(buffer, static_cast<std::size_t>(n)) : std::string();
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) {
    text.pop_back();
  }
  return text;
}

std::string HostName() {
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0) {
    return "unknown-host";
  }
  return host;
}

}  // namespace

std::filesystem::path LockPath(const std::filesystem::path& out) {
  return std::filesystem::path(out.string() + ".lock");
}

void CheckOutputPath(const std::filesystem::path& out) {
  if (out.empty()) {
    throw InputError::AtField("--out", "FILE", "is empty; name the cube file, e.g. --out cube.h5");
  }
  std::error_code ec;
  for (const std::filesystem::path& p : {out, std::filesystem::path(out.string() + ".partial")}) {
    if (std::filesystem::is_directory(p, ec)) {
      throw InputError::AtLine(
          p.string(), 0,
          "is a folder; --out names the cube file, e.g. --out " + (out / "cube.h5").string());
    }
  }
  if (out.filename().empty() || out.filename() == "." || out.filename() == "..") {
    throw InputError::AtLine(out.string(), 0, "names a folder; --out names the cube file");
  }
  const std::filesystem::path folder =
      out.parent_path().empty() ? std::filesystem::path(".") : out.parent_path();
  if (!std::filesystem::is_directory(folder, ec)) {
    throw InputError::AtLine(out.string(), 0,
                             "its folder " + folder.string() + " does not exist or is no folder");
  }
}

OutputLock::OutputLock(const std::filesystem::path& out) : path_(LockPath(out)) {
  // A holder removes the file before it lets go; a process that opened the old file in the
  // meantime must not believe it holds the lock of the new one, hence the inode comparison.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      throw InputError::AtLine(path_.string(), 0,
                               "cannot create the lock file of the output: " + Reason(errno));
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const std::string holder = Holder(fd);
      ::close(fd);
      if (error == EWOULDBLOCK) {
        const std::string who = holder.empty()
                                    ? std::string("another process")
                                    : "process " + holder.substr(0, holder.find(' ')) +
                                          " on host " + holder.substr(holder.find(' ') + 1);
        throw InputError::AtLine(out.string(), 0,
                                 "is being written by another sweep (" + who + ", lock file " +
                                     path_.string() +
                                     "); wait for it to end or choose another --out");
      }
      throw InputError::AtLine(path_.string(), 0, "cannot lock: " + Reason(error));
    }
    struct stat held {};
    struct stat named {};
    if (::fstat(fd, &held) == 0 && ::stat(path_.c_str(), &named) == 0 &&
        held.st_dev == named.st_dev && held.st_ino == named.st_ino) {
      fd_ = fd;
      break;
    }
    ::close(fd);  // the file was removed or replaced under us: try the new one
  }
  if (fd_ < 0) {
    throw InputError::AtLine(path_.string(), 0, "cannot lock: the file keeps being replaced");
  }
  // A stale lock (its holder died) is simply taken over: write our own identity over it.
  const std::string me = std::to_string(::getpid()) + " " + HostName() + "\n";
  if (::ftruncate(fd_, 0) != 0 ||
      ::pwrite(fd_, me.data(), me.size(), 0) != static_cast<ssize_t>(me.size())) {
    const std::string reason = Reason(errno);
    ::unlink(path_.c_str());
    ::close(fd_);
    throw InputError::AtLine(path_.string(), 0, "cannot write the lock file: " + reason);
  }
}

OutputLock::~OutputLock() {
  if (fd_ >= 0) {
    ::unlink(path_.c_str());  // still holding the lock, so no other process holds this file
    ::close(fd_);
  }
}

}  // namespace skewbridge::jobs
