// The MPI implementation of the one message layer (core/ranks/communicator.h) for meshreuse-mpi
// (cli/mpi_main.cc): it only moves bytes for the libraries' runners -- the distributed analysis's
// streamed stacks, histogram slices and resolved chunks, the distributed smoother's and
// refinement's ghost values, exact quality sums, gathers and all-gathers. The only file that
// includes mpi.h besides the program's main and PT-Scotch's glue.
// Messages: one tag, so MPI's non-overtaking order is the order sent. A message of bytes below
// kPiece goes whole (its length from MPI_Probe); a longer one as a header (tag kTagLong: its
// length) followed by pieces of kPiece bytes (counts are int in MPI 3.1). Sends are non-blocking:
// each keeps its bytes until MPI completes it; a link with kDepth sends in flight waits for its
// oldest (the bound of communicator.h), and completed sends are released as new ones start.
// A test hook makes a rank kill itself at its N-th all-reduce (MESHREUSE_MPI_KILL_RANK).
#pragma once

#include <mpi.h>
#include <signal.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <deque>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/fixed_sum.h"
#include "core/ranks/communicator.h"

namespace meshreuse::cli {

class MpiCommunicator : public Communicator {
 public:
  static constexpr int kTag = 1, kTagLong = 2;
  static constexpr size_t kPiece = size_t{1} << 30;

  // kill_at: the tests' fault injection, this rank dies (SIGKILL) in its kill_at-th all-reduce
  // (0: never).
  explicit MpiCommunicator(int kill_at = 0) : kill_at_(kill_at) {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Type_contiguous(2, MPI_UINT64_T, &fixed_);
    MPI_Type_commit(&fixed_);
    MPI_Op_create(&SumFixed, /*commute=*/1, &sum_);
  }
  ~MpiCommunicator() override {
    for (auto& [to, link] : pending_)
      for (Pending& p : link)
        MPI_Waitall(static_cast<int>(p.requests.size()), p.requests.data(), MPI_STATUSES_IGNORE);
    MPI_Op_free(&sum_);
    MPI_Type_free(&fixed_);
  }
  int32_t rank() const override { return rank_; }
  int32_t size() const override { return size_; }

  void Send(int32_t to, std::string&& bytes) override {
    Pending& p = Start(to);
    p.bytes = std::move(bytes);
    const size_t n = p.bytes.size();
    if (n < kPiece) {
      Isend(p, p.bytes.data(), n, to, kTag);
      return;
    }
    p.length = n;
    Isend(p, &p.length, sizeof p.length, to, kTagLong);
    for (size_t at = 0; at < n; at += kPiece)
      Isend(p, p.bytes.data() + at, std::min(kPiece, n - at), to, kTagLong);
  }
  std::string Recv(int32_t from) override {
    MPI_Status st;
    MPI_Probe(from, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
    if (st.MPI_TAG == kTag) {
      int n = 0;
      MPI_Get_count(&st, MPI_BYTE, &n);
      std::string b(static_cast<size_t>(n), '\0');
      MPI_Recv(&b[0], n, MPI_BYTE, from, kTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      return b;
    }
    uint64_t n = 0;
    MPI_Recv(&n, 8, MPI_BYTE, from, kTagLong, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::string b(n, '\0');
    for (size_t at = 0; at < n; at += kPiece)
      MPI_Recv(&b[at], static_cast<int>(std::min<uint64_t>(kPiece, n - at)), MPI_BYTE, from,
               kTagLong, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return b;
  }
  // Ghost values go as they lie (no copy): `data` is the caller's until Flush().
  void SendValues(int32_t to, const void* data, size_t bytes) override {
    if (bytes >= kPiece) throw std::length_error("a message of values of 2^30 bytes or more");
    Isend(Start(to), data, bytes, to, kTag);
  }
  void RecvValues(int32_t from, void* data, size_t bytes) override {
    if (bytes >= kPiece) throw std::length_error("a message of values of 2^30 bytes or more");
    MPI_Recv(data, static_cast<int>(bytes), MPI_BYTE, from, kTag, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
  }
  void Flush() override {
    for (auto& [to, link] : pending_) {
      for (Pending& p : link)
        MPI_Waitall(static_cast<int>(p.requests.size()), p.requests.data(), MPI_STATUSES_IGNORE);
      link.clear();
    }
  }

  // Small messages (a rank's share of the checks): lengths first, then the bytes.
  std::vector<std::string> AllGather(const std::string& mine) override {
    const int n = Count(mine.size());
    std::vector<int> sizes(static_cast<size_t>(size_)), at(static_cast<size_t>(size_), 0);
    MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD);
    int64_t total = 0;
    for (int r = 0; r < size_; ++r) at[r] = static_cast<int>(total), total += sizes[r];
    if (total > INT_MAX) throw std::length_error("an all-gather of more than 2^31 bytes");
    std::string bytes(static_cast<size_t>(total), '\0');
    MPI_Allgatherv(mine.data(), n, MPI_BYTE, &bytes[0], sizes.data(), at.data(), MPI_BYTE,
                   MPI_COMM_WORLD);
    std::vector<std::string> all(static_cast<size_t>(size_));
    for (int r = 0; r < size_; ++r) all[r] = bytes.substr(at[r], sizes[r]);
    return all;
  }
  std::vector<uint64_t> AllReduceMax(const std::vector<uint64_t>& v) override {
    MaybeDie();
    std::vector<uint64_t> out(v.size());
    MPI_Allreduce(v.data(), out.data(), Count(v.size()), MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
    return out;
  }
  FixedSum AllReduceSum(const FixedSum& mine) override {
    MaybeDie();
    uint64_t in[2], out[2];
    mine.ToWords(in);
    MPI_Allreduce(in, out, 1, fixed_, sum_, MPI_COMM_WORLD);
    return FixedSum::FromWords(out);
  }
  std::vector<uint64_t> ExclusiveScanSum(const std::vector<uint64_t>& v) override {
    std::vector<uint64_t> out(v.size(), 0);
    MPI_Exscan(v.data(), out.data(), Count(v.size()), MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    if (rank_ == 0) std::fill(out.begin(), out.end(), 0);  // MPI leaves rank 0's undefined
    return out;
  }
  // Pairwise, step k sending to rank + k and receiving from rank - k, so no two ranks wait on each
  // other and each rank holds at most one step's messages in flight.
  std::vector<std::string> AllToAll(std::vector<std::string>&& out) override {
    if (static_cast<int>(out.size()) != size_)
      throw std::logic_error("MpiCommunicator::AllToAll: one message per rank");
    std::vector<std::string> in(static_cast<size_t>(size_));
    for (int k = 1; k < size_; ++k) {
      const int to = (rank_ + k) % size_, from = (rank_ - k + size_) % size_;
      Send(to, std::move(out[static_cast<size_t>(to)]));
      in[static_cast<size_t>(from)] = Recv(from);
      Flush();
    }
    return in;
  }

 private:
  struct Pending {
    std::string bytes;
    uint64_t length = 0;
    std::vector<MPI_Request> requests;
  };
  static void SumFixed(void* in, void* inout, int* len, MPI_Datatype*) {
    const uint64_t* a = static_cast<const uint64_t*>(in);
    uint64_t* b = static_cast<uint64_t*>(inout);
    for (int i = 0; i < *len; ++i) {
      FixedSum s = FixedSum::FromWords(b + 2 * i);
      s.Add(FixedSum::FromWords(a + 2 * i));
      s.ToWords(b + 2 * i);
    }
  }
  static int Count(size_t n) {
    if (n > static_cast<size_t>(INT_MAX)) throw std::length_error("an MPI count over 2^31");
    return static_cast<int>(n);
  }
  void MaybeDie() {
    if (kill_at_ > 0 && ++reductions_ == kill_at_) raise(SIGKILL);
  }
  // A new send on the link to `to`: completed ones released first; with kDepth in flight, the
  // oldest waited for.
  Pending& Start(int32_t to) {
    std::deque<Pending>& link = pending_[to];
    while (!link.empty()) {
      Pending& p = link.front();
      int done = 0;
      MPI_Testall(static_cast<int>(p.requests.size()), p.requests.data(), &done,
                  MPI_STATUSES_IGNORE);
      if (!done && link.size() < kDepth) break;
      if (!done)
        MPI_Waitall(static_cast<int>(p.requests.size()), p.requests.data(), MPI_STATUSES_IGNORE);
      link.pop_front();
    }
    link.emplace_back();
    return link.back();
  }
  void Isend(Pending& p, const void* data, size_t n, int32_t to, int tag) {
    p.requests.emplace_back();
    MPI_Isend(data, static_cast<int>(n), MPI_BYTE, to, tag, MPI_COMM_WORLD, &p.requests.back());
  }

  int rank_ = 0, size_ = 1;
  int kill_at_ = 0, reductions_ = 0;
  MPI_Datatype fixed_;
  MPI_Op sum_;
  std::map<int32_t, std::deque<Pending>> pending_;  // sends in flight, by link
};

}  // namespace meshreuse::cli
