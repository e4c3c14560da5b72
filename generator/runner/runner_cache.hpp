// SPDX-License-Identifier: GPL-2.0-or-later
// The runner cache on disk: where it is, who may write it, one builder per
// entry at a time, and a manifest that tells an entry changed after it was
// built (docs/errors.md#security). What goes into an entry is runner_build's.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace kanegen::runner {

/// $KANEGEN_CACHE_DIR, else $XDG_CACHE_HOME/kanegen, else ~/.cache/kanegen,
/// else <tmp>/kanegen-cache; created (mode 0700) if missing. Throws
/// std::runtime_error, with the fix, when it is not a directory, is owned by
/// another user, or is writable by group or others: kanegen runs what it finds
/// there, so only its owner may write it.
std::filesystem::path checked_cache_root();

/// Holds an exclusive lock on one cache entry (the directory, created 0700)
/// from construction to destruction: concurrent kanegen processes that need
/// the same entry wait for the one building it, then use its runner. Prints
/// one line when it has to wait (if `verbose`).
class EntryLock {
 public:
  EntryLock(const std::filesystem::path& entry, bool verbose);
  EntryLock(const EntryLock&) = delete;
  EntryLock& operator=(const EntryLock&) = delete;
  ~EntryLock();

 private:
  int fd_ = -1;
};

/// Whether entry/<artifact> (the runner, or a model library's kernels.so) is
/// there and it and every file the manifest lists have the digests written
/// when the entry was built. `changed` says what differs (for the message)
/// when it is not intact but the artifact is there.
enum class EntryState { missing, intact, changed };
EntryState entry_state(const std::filesystem::path& entry, std::string* changed,
                       const std::string& artifact = "runner");

/// Writes entry/manifest (atomically): the digest of entry/<artifact> and of
/// each of `files` (names of files in the entry). Call once the artifact is built.
void seal_entry(const std::filesystem::path& entry, const std::vector<std::string>& files,
                const std::string& artifact = "runner");

/// Removes the artifact and the manifest of an entry that changed, so that it
/// is rebuilt; the lock must be held.
void discard_entry(const std::filesystem::path& entry, const std::string& artifact = "runner");

}  // namespace kanegen::runner
