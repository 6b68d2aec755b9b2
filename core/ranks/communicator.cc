// The collectives' defaults (communicator.h), built on AllGather and Send/Recv: what the threads
// implementation uses; MPI's overrides give the same results.
#include "core/ranks/communicator.h"

#include <algorithm>

namespace meshreuse {

namespace {

std::vector<std::vector<uint64_t>> GatherWords(Communicator& c, const std::vector<uint64_t>& v) {
  std::vector<std::vector<uint64_t>> all;
  for (const std::string& b : c.AllGather(PackValues(v.data(), v.size()))) {
    all.push_back(UnpackValues<uint64_t>(b));
    if (all.back().size() != v.size()) throw std::logic_error("Communicator: lengths differ");
  }
  return all;
}

}  // namespace

std::vector<std::string> Communicator::Gather(const std::string& mine) {
  if (rank() != 0) {
    Send(0, std::string(mine));
    return {};
  }
  std::vector<std::string> all(static_cast<size_t>(size()));
  all[0] = mine;
  for (int32_t r = 1; r < size(); ++r) all[r] = Recv(r);
  return all;
}

std::vector<uint64_t> Communicator::AllReduceMax(const std::vector<uint64_t>& v) {
  std::vector<uint64_t> m = v;
  for (const std::vector<uint64_t>& x : GatherWords(*this, v))
    for (size_t i = 0; i < m.size(); ++i) m[i] = std::max(m[i], x[i]);
  return m;
}

std::vector<uint64_t> Communicator::ExclusiveScanSum(const std::vector<uint64_t>& v) {
  const std::vector<std::vector<uint64_t>> all = GatherWords(*this, v);
  std::vector<uint64_t> s(v.size(), 0);
  for (int32_t r = 0; r < rank(); ++r)
    for (size_t i = 0; i < s.size(); ++i) s[i] += all[r][i];
  return s;
}

FixedSum Communicator::AllReduceSum(const FixedSum& mine) {
  uint64_t w[2];
  mine.ToWords(w);
  FixedSum sum;
  for (const std::string& b : AllGather(PackValues(w, 2))) {
    const std::vector<uint64_t> x = UnpackValues<uint64_t>(b);
    if (x.size() != 2) throw std::logic_error("Communicator: a malformed sum");
    sum.Add(FixedSum::FromWords(x.data()));
  }
  return sum;
}

// Every message sent, then every one received: one message per link, within kDepth.
std::vector<std::string> Communicator::AllToAll(std::vector<std::string>&& out) {
  const int32_t p = size(), r = rank();
  if (static_cast<int32_t>(out.size()) != p)
    throw std::logic_error("Communicator::AllToAll: one message per rank");
  for (int32_t k = 1; k < p; ++k)
    Send((r + k) % p, std::move(out[static_cast<size_t>((r + k) % p)]));
  std::vector<std::string> in(static_cast<size_t>(p));
  for (int32_t k = 1; k < p; ++k) in[static_cast<size_t>((r - k + p) % p)] = Recv((r - k + p) % p);
  return in;
}

void Communicator::SendObject(int32_t, std::shared_ptr<void>) {
  throw std::logic_error("Communicator: objects move only between ranks that share memory");
}

std::shared_ptr<void> Communicator::RecvObject(int32_t) {
  throw std::logic_error("Communicator: objects move only between ranks that share memory");
}

}  // namespace meshreuse
