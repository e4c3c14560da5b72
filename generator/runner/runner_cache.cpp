// SPDX-License-Identifier: GPL-2.0-or-later
#include "runner/runner_cache.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "pipeline/pipeline.hpp"

namespace kanegen::runner {
namespace fs = std::filesystem;
namespace {

const char* const kManifest = "manifest";
const char* const kManifestHeader = "kanegen runner cache manifest 1";

fs::path cache_root_path() {
  if (const char* dir = std::getenv("KANEGEN_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "kanegen";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "kanegen";
  return fs::temp_directory_path() / "kanegen-cache";
}

/// Creates `dir` with mode 0700 (its missing parents with the usual mode).
void make_private_directory(const fs::path& dir) {
  std::error_code error;
  if (dir.has_parent_path()) fs::create_directories(dir.parent_path(), error);
  if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
    throw std::runtime_error(dir.string() + ": cannot create the runner cache (" + std::strerror(errno) +
                             "); set KANEGEN_CACHE_DIR to a writable directory");
}

std::string octal_mode(mode_t mode) {
  char text[8];
  std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(mode & 07777));
  return text;
}

}  // namespace

fs::path checked_cache_root() {
  const fs::path root = cache_root_path();
  make_private_directory(root);
  struct stat st {};
  if (::stat(root.c_str(), &st) != 0)
    throw std::runtime_error(root.string() + ": cannot use the runner cache (" + std::strerror(errno) +
                             "); set KANEGEN_CACHE_DIR to a directory of your own");
  const std::string fix =
      "; kanegen compiles and runs what it finds there, so only you may write to it: set "
      "KANEGEN_CACHE_DIR to a directory of your own";
  if (!S_ISDIR(st.st_mode))
    throw std::runtime_error(root.string() + ": the runner cache is not a directory" + fix);
  if (st.st_uid != ::geteuid())
    throw std::runtime_error(root.string() + ": the runner cache belongs to another user (uid " +
                             std::to_string(st.st_uid) + ")" + fix);
  // Group write only for the user's own group (user-private groups, umask 002).
  if ((st.st_mode & S_IWOTH) || ((st.st_mode & S_IWGRP) && st.st_gid != ::getegid()))
    throw std::runtime_error(root.string() + ": the runner cache is writable by other users (mode " +
                             octal_mode(st.st_mode) + "); run chmod go-w " + root.string() +
                             ", or set KANEGEN_CACHE_DIR to a directory of your own");
  return root;
}

EntryLock::EntryLock(const fs::path& entry, bool verbose) {
  make_private_directory(entry);
  // The directory itself is locked, so that no lock file stays behind (an
  // interrupted build leaves nothing in its entry).
  fd_ = ::open(entry.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error(entry.string() + ": cannot open (" + std::strerror(errno) + ")");
  if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
  if (verbose)
    std::fprintf(stderr, "kanegen: waiting for another kanegen that is building this model (%s) ...\n",
                 entry.c_str());
  while (::flock(fd_, LOCK_EX) != 0) {
    if (errno == EINTR) continue;
    const std::string why = std::strerror(errno);
    ::close(fd_);
    throw std::runtime_error(entry.string() + ": cannot lock (" + why + ")");
  }
}

EntryLock::~EntryLock() {
  if (fd_ >= 0) ::close(fd_);  // and with it the lock
}

EntryState entry_state(const fs::path& entry, std::string* changed, const std::string& artifact) {
  std::error_code error;
  if (!fs::exists(entry / artifact, error)) return EntryState::missing;
  std::ifstream in(entry / kManifest);
  std::string line;
  if (!in || !std::getline(in, line) || line != kManifestHeader) {
    *changed = "it has no manifest (built by an older kanegen, or its build was stopped)";
    return EntryState::changed;
  }
  bool artifact_listed = false;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string digest, name;
    fields >> digest >> name;
    const fs::path file = entry / name;
    if (!fs::is_regular_file(file, error)) {
      *changed = name + " is missing";
      return EntryState::changed;
    }
    if (pipeline::digest(pipeline::read_file(file.string())) != digest) {
      *changed = name + " changed after it was built";
      return EntryState::changed;
    }
    artifact_listed = artifact_listed || name == artifact;
  }
  if (!artifact_listed) {
    *changed = "its manifest does not list the " + (artifact == "runner" ? artifact : "file " + artifact);
    return EntryState::changed;
  }
  return EntryState::intact;
}

void seal_entry(const fs::path& entry, const std::vector<std::string>& files, const std::string& artifact) {
  std::string text = std::string(kManifestHeader) + "\n";
  std::vector<std::string> sealed = files;
  sealed.push_back(artifact);
  for (const std::string& name : sealed)
    text += pipeline::digest(pipeline::read_file((entry / name).string())) + " " + name + "\n";
  const fs::path temporary = entry / (std::string(kManifest) + ".tmp." + std::to_string(::getpid()));
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  std::error_code error;
  if (!out) {
    fs::remove(temporary, error);
    throw std::runtime_error(temporary.string() + ": cannot write (disk full or no permission?)");
  }
  fs::rename(temporary, entry / kManifest, error);
  if (error)
    throw std::runtime_error((entry / kManifest).string() + ": cannot write (" + error.message() + ")");
}

void discard_entry(const fs::path& entry, const std::string& artifact) {
  std::error_code ignored;
  fs::remove(entry / kManifest, ignored);
  fs::remove(entry / artifact, ignored);
}

}  // namespace kanegen::runner
