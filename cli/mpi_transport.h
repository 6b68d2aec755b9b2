// The MPI transports of meshreuse-mpi (cli/mpi_main.cc): they only move bytes between ranks for
// the libraries' runners -- the analysis's streamed stacks and summaries (ChunkTransport), the
// distributed smoother's and refinement's ghost values, exact quality sums, gathers and all-gathers
// (HaloTransport). A test hook makes a rank kill itself at a set point (MESHREUSE_MPI_KILL_RANK).
#pragma once

#include <mpi.h>
#include <signal.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/fixed_sum.h"
#include "core/halo_smoother.h"
#include "reports/chunk_summary.h"

namespace meshreuse::cli {

constexpr int kTagIds = 1, kTagSize = 2, kTagBytes = 3;
constexpr size_t kPiece = size_t{1} << 30;  // bytes per message: counts are int

class MpiTransport : public ChunkTransport {
 public:
  MpiTransport() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void SendIds(const uint64_t* ids, size_t n) override {
    MPI_Send(ids, static_cast<int>(n), MPI_UINT64_T, rank_ + 1, kTagIds, MPI_COMM_WORLD);
  }
  size_t RecvIds(std::vector<uint64_t>* ids) override {
    MPI_Status st;
    MPI_Probe(rank_ - 1, kTagIds, MPI_COMM_WORLD, &st);
    int n = 0;
    MPI_Get_count(&st, MPI_UINT64_T, &n);
    ids->resize(static_cast<size_t>(n));
    MPI_Recv(ids->data(), n, MPI_UINT64_T, rank_ - 1, kTagIds, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return static_cast<size_t>(n);
  }
  void SendBytes(int to, const std::string& b) override {
    uint64_t n = b.size();
    MPI_Send(&n, 1, MPI_UINT64_T, to, kTagSize, MPI_COMM_WORLD);
    for (size_t at = 0; at < b.size(); at += kPiece)
      MPI_Send(b.data() + at, static_cast<int>(std::min(kPiece, b.size() - at)), MPI_BYTE, to,
               kTagBytes, MPI_COMM_WORLD);
  }
  std::string RecvBytes(int from) override {
    uint64_t n = 0;
    MPI_Recv(&n, 1, MPI_UINT64_T, from, kTagSize, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::string b(n, '\0');
    for (size_t at = 0; at < n; at += kPiece)
      MPI_Recv(&b[at], static_cast<int>(std::min<uint64_t>(kPiece, n - at)), MPI_BYTE, from,
               kTagBytes, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return b;
  }
  // Pairwise, step k sending to rank + k and receiving from rank - k: the sizes by one exchange,
  // then the bytes sent without waiting and received in pieces, so no two ranks wait on each other.
  std::vector<std::string> AllToAll(std::vector<std::string>&& out) override {
    std::vector<std::string> in(static_cast<size_t>(size_));
    for (int k = 1; k < size_; ++k) {
      const int to = (rank_ + k) % size_, from = (rank_ - k + size_) % size_;
      const std::string& b = out[static_cast<size_t>(to)];
      uint64_t n = b.size(), m = 0;
      MPI_Sendrecv(&n, 1, MPI_UINT64_T, to, kTagSize, &m, 1, MPI_UINT64_T, from, kTagSize,
                   MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      std::vector<MPI_Request> sends;
      for (size_t at = 0; at < b.size(); at += kPiece) {
        sends.emplace_back();
        MPI_Isend(b.data() + at, static_cast<int>(std::min(kPiece, b.size() - at)), MPI_BYTE, to,
                  kTagBytes, MPI_COMM_WORLD, &sends.back());
      }
      std::string& got = in[static_cast<size_t>(from)];
      got.assign(m, '\0');
      for (size_t at = 0; at < m; at += kPiece)
        MPI_Recv(&got[at], static_cast<int>(std::min<uint64_t>(kPiece, m - at)), MPI_BYTE, from,
                 kTagBytes, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      MPI_Waitall(static_cast<int>(sends.size()), sends.data(), MPI_STATUSES_IGNORE);
    }
    return in;
  }
  std::vector<uint64_t> AllReduceMax(const std::vector<uint64_t>& v) override {
    std::vector<uint64_t> out(v.size());
    MPI_Allreduce(v.data(), out.data(), static_cast<int>(v.size()), MPI_UINT64_T, MPI_MAX,
                  MPI_COMM_WORLD);
    return out;
  }
  std::vector<uint64_t> ExclusiveScanSum(const std::vector<uint64_t>& v) override {
    std::vector<uint64_t> out(v.size(), 0);
    MPI_Exscan(v.data(), out.data(), static_cast<int>(v.size()), MPI_UINT64_T, MPI_SUM,
               MPI_COMM_WORLD);
    if (rank_ == 0) std::fill(out.begin(), out.end(), 0);  // MPI leaves rank 0's undefined
    return out;
  }

 private:
  int rank_ = 0, size_ = 1;
};

// The distributed smoother's messages: ghost values to and from neighbouring ranks (one message per
// neighbour per sweep and direction, in order: MPI does not overtake on one tag and communicator),
// the 128-bit quality sum through a user-defined reduction, the gather to rank 0.
constexpr int kTagHalo = 4, kTagGather = 5;

inline void SumFixed(void* in, void* inout, int* len, MPI_Datatype*) {
  const uint64_t* a = static_cast<const uint64_t*>(in);
  uint64_t* b = static_cast<uint64_t*>(inout);
  for (int i = 0; i < *len; ++i) {
    meshreuse::FixedSum s = meshreuse::FixedSum::FromWords(b + 2 * i);
    s.Add(meshreuse::FixedSum::FromWords(a + 2 * i));
    s.ToWords(b + 2 * i);
  }
}

class MpiHalo : public HaloTransport {
 public:
  // kill: the tests' fault injection, this rank dies (SIGKILL) in its second reduction.
  explicit MpiHalo(bool kill) : kill_(kill) {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Type_contiguous(2, MPI_UINT64_T, &fixed_);
    MPI_Type_commit(&fixed_);
    MPI_Op_create(&SumFixed, /*commute=*/1, &sum_);
  }
  ~MpiHalo() override {
    MPI_Op_free(&sum_);
    MPI_Type_free(&fixed_);
  }
  int32_t rank() const override { return rank_; }
  int32_t size() const override { return size_; }
  void Send(int32_t to, const double* data, size_t n) override {
    requests_.emplace_back();
    MPI_Isend(data, Count(n), MPI_DOUBLE, to, kTagHalo, MPI_COMM_WORLD, &requests_.back());
  }
  void Recv(int32_t from, double* data, size_t n) override {
    MPI_Recv(data, Count(n), MPI_DOUBLE, from, kTagHalo, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
  void Flush() override {
    MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
    requests_.clear();
  }
  meshreuse::FixedSum SumAll(const meshreuse::FixedSum& mine) override {
    if (kill_ && ++reductions_ == 2) raise(SIGKILL);
    uint64_t in[2], out[2];
    mine.ToWords(in);
    MPI_Allreduce(in, out, 1, fixed_, sum_, MPI_COMM_WORLD);
    return meshreuse::FixedSum::FromWords(out);
  }
  std::vector<std::string> Gather(const std::string& mine) override {
    if (rank_ != 0) {
      tx_.SendBytes(0, mine);
      return {};
    }
    std::vector<std::string> all(size_);
    all[0] = mine;
    for (int r = 1; r < size_; ++r) all[r] = tx_.RecvBytes(r);
    return all;
  }
  // Small messages (a rank's share of the checks): sizes first, then the bytes.
  std::vector<std::string> AllGather(const std::string& mine) override {
    const int n = Count(mine.size());
    std::vector<int> sizes(size_), at(size_, 0);
    MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD);
    int64_t total = 0;
    for (int r = 0; r < size_; ++r) at[r] = static_cast<int>(total), total += sizes[r];
    if (total > INT_MAX) throw std::length_error("an all-gather of more than 2^31 bytes");
    std::string bytes(static_cast<size_t>(total), '\0');
    MPI_Allgatherv(mine.data(), n, MPI_BYTE, &bytes[0], sizes.data(), at.data(), MPI_BYTE,
                   MPI_COMM_WORLD);
    std::vector<std::string> all(size_);
    for (int r = 0; r < size_; ++r) all[r] = bytes.substr(at[r], sizes[r]);
    return all;
  }

 private:
  static int Count(size_t n) {
    if (n > static_cast<size_t>(INT_MAX))  // MPI 3.1 counts are int
      throw std::length_error("a ghost message of more than 2^31 values");
    return static_cast<int>(n);
  }
  int rank_ = 0, size_ = 1;
  bool kill_;
  int reductions_ = 0;
  MPI_Datatype fixed_;
  MPI_Op sum_;
  std::vector<MPI_Request> requests_;
  MpiTransport tx_;  // its byte messages for the gather
};

// The fault-injection hook of the tests: the transport of a rank that dies after its chunk.
class KillingTransport : public MpiTransport {
 public:
  explicit KillingTransport(bool kill) : kill_(kill) {}
  std::vector<uint64_t> AllReduceMax(const std::vector<uint64_t>& v) override {
    if (kill_) raise(SIGKILL);
    return MpiTransport::AllReduceMax(v);
  }

 private:
  bool kill_;
};

}  // namespace meshreuse::cli
