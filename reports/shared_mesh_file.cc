// SharedMeshFileOutput (shared_mesh_file.h).
#include "reports/shared_mesh_file.h"

#include <unistd.h>

#include <cstring>
#include <vector>

#include "core/mesh_file.h"

namespace meshreuse {

SharedMeshFileOutput::SharedMeshFileOutput(const std::string& path, Communicator& tx) : tx_(tx) {
  if (tx.rank() == 0) {
    out_ = std::make_unique<AtomicOutput>(path);
    tmp_ = out_->temporary();
  }
  tmp_ = tx.AllGather(tmp_)[0];
  if (!out_ && !tmp_.empty()) slot_ = RegisterTemporary(tmp_);
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
