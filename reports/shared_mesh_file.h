// A mesh file written by every rank of a job at once (core/mesh_file.h's writers in ranges; the
// distributed smoother's -o FILE.mrm and meshreuse-mpi refine): every rank learns where rank 0's
// temporary will be (TemporaryPathFor) and registers it, then rank 0 opens the output through
// AtomicOutput (the temporary beside it); once every rank has written its part, Finish has each
// rank hash a share of the blocks anew and rank 0 write the tables and header and rename the
// temporary into place. Destroyed unfinished, the temporary is removed and the target untouched;
// every rank registers it for removal on SIGINT, SIGTERM and the abort path (core/output_file.h)
// before it exists, so a cancelled or failed job leaves none, whichever rank dies first and when.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/output_file.h"
#include "core/ranks/halo_smoother.h"

namespace meshreuse {

class SharedMeshFileOutput {
 public:
  // Collective. temporary() is empty when the output is a device or FIFO: those are written in
  // place, which ranks cannot share.
  SharedMeshFileOutput(const std::string& path, Communicator& tx);
  const std::string& temporary() const { return tmp_; }
  // Collective, once every rank's writes are done: blocks [0, blocks) of the file hashed anew, a
  // share per rank (blocks past them keep their hashes); rank 0 finishes and renames the file and
  // gets its content id (the other ranks 0).
  uint64_t Finish(int64_t blocks);
  // Unfinished (an error on this rank): every rank removes the temporary, so that a failure
  // anywhere leaves none (rank 0's own is removed by its output).
  ~SharedMeshFileOutput();

 private:
  Communicator& tx_;
  std::unique_ptr<AtomicOutput> out_;  // rank 0's
  std::string tmp_;
  int slot_ = -1;  // the temporary in this rank's signal-cleanup list (core/output_file.h)
  bool finished_ = false;
};

}  // namespace meshreuse
