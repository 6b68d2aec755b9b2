// The partition directory (core/ranks/part_directory.h) on threads, against what a rank holding the
// whole partition computes: each rank's ids, any ids' parts, every vertex's part; at P = 1..5, over
// meshes of fewer ids than ranks' worth of work (ranges of one id), with parts left empty; and the
// all-to-all under them delivers each list, empty lists included, to its rank.
#include "core/ranks/part_directory.h"

#include <gtest/gtest.h>

#include <mutex>
#include <random>

#include "core/ranks/rank_neighbourhood.h"
#include "core/ranks/thread_communicator.h"

namespace meshreuse {
namespace {

TEST(PartDirectory, AllToAllDeliversEveryList) {
  for (int32_t P = 1; P <= 5; ++P) {
    std::vector<std::vector<std::vector<int64_t>>> got(P);
    auto list = [](int32_t from, int32_t to) {  // empty for some pairs
      std::vector<int64_t> l;
      for (int32_t k = 0; k < (from * 3 + to) % 4; ++k)
        l.push_back(int64_t{from} * 1000 + to * 10 + k);
      return l;
    };
    ThreadCommunicator::Run(P, [&](Communicator& tx) {
      std::vector<std::vector<int64_t>> out(P);
      for (int32_t q = 0; q < P; ++q) out[q] = list(tx.rank(), q);
      got[tx.rank()] = AllToAll(tx, out);
    });
    for (int32_t r = 0; r < P; ++r)
      for (int32_t p = 0; p < P; ++p) EXPECT_EQ(got[r][p], list(p, r)) << P << " " << r << " " << p;
  }
}

TEST(PartDirectory, OwnedIdsAndPartsAreThoseOfTheWholePartition) {
  std::mt19937_64 rng(11);
  for (int64_t n : {1, 2, 5, 17, 1000})
    for (int32_t P = 1; P <= std::min<int64_t>(5, n); ++P)
      for (int trial = 0; trial < 3; ++trial) {
        std::vector<int32_t> part(static_cast<size_t>(n));
        const int32_t used = trial == 2 && P > 1 ? P - 1 : P;  // trial 2: the last part empty
        for (int32_t& q : part) q = static_cast<int32_t>(rng() % used);
        std::vector<std::vector<int64_t>> owned(P), asked(P);
        std::vector<std::vector<int32_t>> answers(P), every(P);
        for (int32_t r = 0; r < P; ++r)  // each rank asks for a random increasing set of ids
          for (int64_t v = 0; v < n; ++v)
            if (rng() % 3 == 0) asked[r].push_back(v);
        std::mutex mu;
        ThreadCommunicator::Run(P, [&](Communicator& tx) {
          const int32_t r = tx.rank();
          const std::vector<int32_t> mine(part.begin() + RangeFirst(r, n, P),
                                          part.begin() + RangeFirst(r + 1, n, P));
          std::vector<int64_t> o = GatherOwnedIds(tx, n, mine);
          std::vector<int32_t> a = LookUpParts(tx, n, mine, asked[r]);
          std::vector<int32_t> e = AllParts(tx, n, mine);
          std::lock_guard<std::mutex> lock(mu);
          owned[r] = std::move(o), answers[r] = std::move(a), every[r] = std::move(e);
        });
        for (int32_t r = 0; r < P; ++r) {
          std::vector<int64_t> want;
          for (int64_t v = 0; v < n; ++v)
            if (part[v] == r) want.push_back(v);
          EXPECT_EQ(owned[r], want) << n << " " << P << " " << r;
          std::vector<int32_t> parts;
          for (int64_t v : asked[r]) parts.push_back(part[v]);
          EXPECT_EQ(answers[r], parts) << n << " " << P << " " << r;
          EXPECT_EQ(every[r], part);
        }
      }
}

}  // namespace
}  // namespace meshreuse
