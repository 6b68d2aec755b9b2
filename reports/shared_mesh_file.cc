// SharedMeshFileOutput (shared_mesh_file.h).
#include "reports/shared_mesh_file.h"

#include <unistd.h>

#include <cstring>
#include <vector>

#include "core/error.h"
#include "core/mesh_file.h"

namespace meshreuse {

// The temporary's name goes to every rank, and every rank registers it, before rank 0 makes it:
// made first (the form before), a rank 0 killed (SIGKILL, the OOM killer) between making it and
// the others' registering it left it behind, the one process that knew it gone (by hand, rank 0
// killed as its temporary appeared: 8 runs in 10 at -np 3; the likely cause, not verified, of a
// CI run's one temporary left by mpi_smooth.sh's SIGKILL to "the newest rank"). Two barriers:
// all registered before it exists, it exists before any rank opens it.
SharedMeshFileOutput::SharedMeshFileOutput(const std::string& path, Communicator& tx) : tx_(tx) {
  if (tx.rank() == 0) tmp_ = TemporaryPathFor(path);
  tmp_ = tx.AllGather(tmp_)[0];
  if (tx.rank() != 0 && !tmp_.empty()) slot_ = RegisterTemporary(tmp_);
  tx.Barrier();
  if (tx.rank() == 0) {
    out_ = std::make_unique<AtomicOutput>(path);
    // The path changed between the two looks (a FIFO made or removed there): nothing to share.
    if (out_->temporary() != tmp_)
      throw EnvironmentError(path, "the output changed while the job opened it; run it again");
  }
  tx.Barrier();
}

SharedMeshFileOutput::~SharedMeshFileOutput() {
  if (!finished_ && !out_ && !tmp_.empty()) ::unlink(tmp_.c_str());
  UnregisterTemporary(slot_);
}

uint64_t SharedMeshFileOutput::Finish(int64_t blocks) {
  tx_.AllGather(std::string());  // a barrier: every rank's bytes are in the file
  const int32_t P = tx_.size(), r = tx_.rank();
  const std::vector<uint64_t> mine = HashMeshFileBlocks(tmp_, blocks * r / P, blocks * (r + 1) / P);
  const std::vector<std::string> all =
      tx_.Gather(std::string(reinterpret_cast<const char*>(mine.data()), 8 * mine.size()));
  if (r != 0) {
    finished_ = true;  // rank 0 finishes the file (or, failing, its output removes it)
    return 0;
  }
  std::vector<uint64_t> hashes;
  for (const std::string& b : all) {
    const size_t at = hashes.size();
    hashes.resize(at + b.size() / 8);
    if (!b.empty()) std::memcpy(&hashes[at], b.data(), b.size());
  }
  if (static_cast<int64_t>(hashes.size()) != blocks)
    throw std::logic_error("SharedMeshFileOutput: block hashes missing");
  const uint64_t id = FinishMeshFile(tmp_, hashes);
  out_->Commit();
  return id;
}

}  // namespace meshreuse
