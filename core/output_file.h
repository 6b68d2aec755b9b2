// Writing an output, the one way every command does it (beside core/input_file.h, the one way to
// read). What a path may be decides how it is written:
//   - a new path or a regular file: written to PATH.tmp.PID in the same folder, then renamed over
//     PATH when complete, so a failed or interrupted write never leaves a half-written file and
//     never replaces a good one;
//   - a symbolic link: resolved, and its target written by these same rules (the link stays);
//   - a character device or a FIFO (/dev/null, a pipe to another program): written in place,
//     never replaced by a regular file (as root, renaming over /dev/null would destroy it);
//   - anything else (a folder, a socket, a block device): refused.
// Several files that belong together (a mesh's .node and .ele, a trace and its index) are written
// as a unit: every temporary complete before the first rename (AtomicOutputs::CommitAll).
// On SIGINT and SIGTERM the temporaries of this process are removed before it ends (exit status of
// the signal); InstallOutputCleanup() arms that once, in main.
// Failures to write are EnvironmentError (exit 3: disk full, permission denied); a path that can
// never be written (empty, too long, its folder missing, an input of the same run) is a
// UsageError (exit 2), checked before any work by CheckOutputPath.
#pragma once

#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace meshreuse {

// Before any work: refuses (UsageError naming `option`) an empty path, a name or path too long for
// the file system, a folder, a path whose folder does not exist or is not a folder, a socket or
// block device, and a path that is the same file as one of `inputs` (also through links).
void CheckOutputPath(const std::string& path, const std::string& option,
                     const std::vector<std::string>& inputs = {});

// One output being written. Open in the constructor (EnvironmentError when it cannot be), write
// through file(), then Commit(); destroyed uncommitted, the temporary is removed and the target is
// untouched.
class AtomicOutput {
 public:
  explicit AtomicOutput(const std::string& path);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  std::FILE* file() const { return f_; }
  const std::string& path() const { return path_; }
  bool in_place() const { return in_place_; }  // a device or FIFO: no temporary
  // The temporary's path (empty in place): where other processes may write before Commit (the
  // ranks of a distributed mesh file, mesh_file.h).
  const std::string& temporary() const { return tmp_; }
  // Flushes and closes the file (EnvironmentError on a write error: disk full); then renames the
  // temporary into place unless `defer_rename` (CommitAll renames a group once all are closed).
  void Commit(bool defer_rename = false);
  void Rename();  // after Commit(true)

 private:
  std::string path_, target_, tmp_;
  std::FILE* f_ = nullptr;
  bool in_place_ = false, closed_ = false, done_ = false;
  int slot_ = -1;  // in the signal handler's list of temporaries
};

// The temporary AtomicOutput(path) would write in this process, without making it (empty for a
// device or FIFO, written in place); the same UsageError where the path cannot be an output. A
// job whose ranks share one temporary announces it with this before it exists, so that a rank
// killed the moment it appears leaves none (SharedMeshFileOutput).
std::string TemporaryPathFor(const std::string& path);

// Writes `path` through `body` (AtomicOutput). Throws EnvironmentError on failure; anything `body`
// throws leaves the target untouched.
void WriteAtomically(const std::string& path, const std::function<void(std::FILE*)>& body);
void WriteTextFile(const std::string& path, const std::string& text);

// Writes every file through its body, then renames them all: none is replaced unless all were
// written completely.
void WriteAtomicallyAll(
    const std::vector<std::pair<std::string, std::function<void(std::FILE*)>>>& files);

// Arms the removal of temporaries on SIGINT and SIGTERM (idempotent).
void InstallOutputCleanup();
// A temporary another process made that this one must remove too when it ends by a signal or
// aborts (the shared temporary every rank of a job writes): registered with the signal handler's
// list (-1 when the list is full), unregistered once committed.
int RegisterTemporary(const std::string& path);
void UnregisterTemporary(int slot);
// Removes every registered temporary now (the abort path: MPI_Abort ends this process without
// unwinding); async-signal-safe.
void RemoveTemporaries();
// Temporaries of `path` (PATH.tmp.PID beside its target) whose process is gone: what an earlier run
// that was killed left behind.
std::vector<std::string> StaleTemporaries(const std::string& path);

}  // namespace meshreuse
