// The partition directory (part_directory.h): an all-to-all of ids over a Communicator.
#include "core/ranks/part_directory.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "core/ranks/rank_neighbourhood.h"

namespace meshreuse {

std::vector<std::vector<int64_t>> AllToAll(Communicator& tx,
                                           const std::vector<std::vector<int64_t>>& out) {
  const int32_t P = tx.size(), me = tx.rank();
  if (static_cast<int32_t>(out.size()) != P) throw std::logic_error("AllToAll: one list per rank");
  std::vector<std::string> bytes(static_cast<size_t>(P));
  for (int32_t q = 0; q < P; ++q)
    if (q != me) bytes[q] = PackValues(out[q].data(), out[q].size());
  std::vector<std::vector<int64_t>> in(static_cast<size_t>(P));
  std::vector<std::string> got = tx.AllToAll(std::move(bytes));
  for (int32_t p = 0; p < P; ++p) in[p] = p == me ? out[p] : UnpackValues<int64_t>(got[p]);
  return in;
}

std::vector<int64_t> GatherOwnedIds(Communicator& tx, int64_t vertices,
                                    const std::vector<int32_t>& part) {
  const int32_t P = tx.size();
  const int64_t first = RangeFirst(tx.rank(), vertices, P);
  if (static_cast<int64_t>(part.size()) != RangeFirst(tx.rank() + 1, vertices, P) - first)
    throw std::logic_error("GatherOwnedIds: parts for another range");
  std::vector<std::vector<int64_t>> out(static_cast<size_t>(P));
  for (size_t i = 0; i < part.size(); ++i) {
    if (part[i] < 0 || part[i] >= P) throw std::logic_error("GatherOwnedIds: a part out of range");
    out[part[i]].push_back(first + static_cast<int64_t>(i));
  }
  // Ranges increase with the rank and each list is increasing: concatenated in rank order, sorted.
  std::vector<int64_t> mine;
  for (const std::vector<int64_t>& from : AllToAll(tx, out))
    mine.insert(mine.end(), from.begin(), from.end());
  return mine;
}

std::vector<int32_t> LookUpParts(Communicator& tx, int64_t vertices,
                                 const std::vector<int32_t>& part,
                                 const std::vector<int64_t>& ids) {
  const int32_t P = tx.size();
  const int64_t first = RangeFirst(tx.rank(), vertices, P);
  std::vector<std::vector<int64_t>> ask(static_cast<size_t>(P));
  for (size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] < 0 || ids[i] >= vertices || (i && ids[i] <= ids[i - 1]))
      throw std::logic_error("LookUpParts: ids out of range or not increasing");
    ask[RangeOwner(ids[i], vertices, P)].push_back(ids[i]);
  }
  const std::vector<std::vector<int64_t>> asked = AllToAll(tx, ask);
  std::vector<std::vector<int64_t>> answer(static_cast<size_t>(P));
  for (int32_t p = 0; p < P; ++p)
    for (int64_t v : asked[p]) {
      const int64_t i = v - first;
      if (i < 0 || i >= static_cast<int64_t>(part.size()))
        throw std::logic_error("LookUpParts: asked for an id outside this rank's range");
      answer[p].push_back(part[i]);
    }
  const std::vector<std::vector<int64_t>> got = AllToAll(tx, answer);
  // Ids increase with the rank that holds them: the answers in rank order are in the ids' order.
  std::vector<int32_t> parts;
  parts.reserve(ids.size());
  for (int32_t q = 0; q < P; ++q) {
    if (got[q].size() != ask[q].size()) throw std::logic_error("LookUpParts: a short answer");
    for (int64_t v : got[q]) parts.push_back(static_cast<int32_t>(v));
  }
  return parts;
}

std::vector<int32_t> AllParts(Communicator& tx, int64_t vertices,
                              const std::vector<int32_t>& part) {
  const int32_t P = tx.size();
  const std::vector<std::string> all =
      tx.AllGather(std::string(reinterpret_cast<const char*>(part.data()), 4 * part.size()));
  std::vector<int32_t> every(static_cast<size_t>(vertices));
  for (int32_t p = 0; p < P; ++p) {
    const int64_t a = RangeFirst(p, vertices, P), b = RangeFirst(p + 1, vertices, P);
    if (all[p].size() != 4 * static_cast<size_t>(b - a))
      throw std::logic_error("AllParts: parts for another range");
    if (b > a) std::memcpy(every.data() + a, all[p].data(), all[p].size());
  }
  for (int32_t q : every)
    if (q < 0 || q >= P) throw std::logic_error("AllParts: a part out of range");
  return every;
}

}  // namespace meshreuse
