// The one message layer of every distributed algorithm here (the halo exchange of the distributed
// smoother and refinement, the partition directory, the chunk relay and reductions of the
// distributed analysis; ../shared/scale-out.md): ranks 0..size-1 that only move bytes. Two
// implementations: P ranks as P threads of one process (thread_communicator.h: the tests, and
// `--threads`/`smooth-ranks` without MPI) and MPI (cli/mpi_communicator.h, the only file that
// includes mpi.h), so the libraries stay MPI-free. Invariants every implementation keeps:
//   - messages from one rank to another arrive in the order they were sent;
//   - a Send may return before delivery, but waits while kDepth earlier messages on its link are
//     undelivered, so a fast sender's memory stays bounded (the LRU stack streamed rank to rank);
//     every algorithm here sends at most kDepth messages on a link before its receiver reads one
//     or a collective intervenes, so the wait never deadlocks;
//   - collectives are called by every rank in the same order;
//   - a rank that fails makes every rank blocked in the network fail too (never a hang).
// The collectives a user of the interface needs have defaults built on AllGather and Send/Recv;
// the MPI implementation overrides them with MPI's own.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/fixed_sum.h"

namespace meshreuse {

class Communicator {
 public:
  static constexpr size_t kDepth = 4;  // messages in flight on one link before a send waits

  virtual ~Communicator() = default;
  virtual int32_t rank() const = 0;
  virtual int32_t size() const = 0;

  // Point to point: a message of any length (0 included).
  virtual void Send(int32_t to, std::string&& bytes) = 0;
  virtual std::string Recv(int32_t from) = 0;
  // A message whose length both ends know (ghost values): `data` stays untouched until Flush(),
  // so an implementation may send it without a copy. Received with RecvValues of the same length.
  virtual void SendValues(int32_t to, const void* data, size_t bytes) {
    Send(to, std::string(static_cast<const char*>(data), bytes));
  }
  virtual void RecvValues(int32_t from, void* data, size_t bytes) {
    const std::string b = Recv(from);
    if (b.size() != bytes) throw std::logic_error("Communicator: message length mismatch");
    if (bytes) std::memcpy(data, b.data(), bytes);
  }
  virtual void Flush() {}  // every SendValues delivered: its data may change again

  // Collectives. Every rank's bytes, by rank, on every rank.
  virtual std::vector<std::string> AllGather(const std::string& mine) = 0;
  // Rank 0 gets every rank's bytes (by rank); the others an empty vector.
  virtual std::vector<std::string> Gather(const std::string& mine);
  virtual std::vector<uint64_t> AllReduceMax(const std::vector<uint64_t>& v);
  virtual FixedSum AllReduceSum(const FixedSum& mine);  // exact: the sum over all ranks
  // Element-wise sums of the ranks before this one (rank 0: zeros).
  virtual std::vector<uint64_t> ExclusiveScanSum(const std::vector<uint64_t>& v);
  // out[j] to rank j, for every j but this rank; returns in[j], from rank j (in[rank()] empty).
  virtual std::vector<std::string> AllToAll(std::vector<std::string>&& out);
  void Barrier() { AllGather(std::string()); }

  // Ranks that share one address space may hand an object over instead of its encoding (the
  // resolved chunks of the distributed analysis): where SharesMemory(), SendObject/RecvObject
  // move it, in order with the link's other messages; elsewhere they are not called.
  virtual bool SharesMemory() const { return false; }
  virtual void SendObject(int32_t to, std::shared_ptr<void> object);
  virtual std::shared_ptr<void> RecvObject(int32_t from);
};

// A rank's vector of fixed-width values as bytes and back (the messages of the algorithms above).
template <class T>
std::string PackValues(const T* v, size_t n) {
  return std::string(reinterpret_cast<const char*>(v), n * sizeof(T));
}
template <class T>
std::vector<T> UnpackValues(const std::string& b) {
  if (b.size() % sizeof(T)) throw std::logic_error("Communicator: a message of partial values");
  std::vector<T> v(b.size() / sizeof(T));
  if (!v.empty()) std::memcpy(v.data(), b.data(), b.size());
  return v;
}

}  // namespace meshreuse
