// The one message layer on threads (core/ranks/thread_communicator.h): bytes between ranks in the
// order sent, whatever the receivers' order; the collectives equal naive ones, in rounds; the
// all-to-all delivers every message to its rank; a failing rank ends the run with its own error,
// every blocked rank released (no hang).
#include "core/ranks/thread_communicator.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace meshreuse {
namespace {

TEST(ThreadCommunicator, BytesAndCollectives) {
  const int p = 5;
  std::vector<std::vector<uint64_t>> max(p), scan(p);
  std::vector<std::string> at0;
  ThreadCommunicator::Run(p, [&](Communicator& tx) {
    const int r = tx.rank();
    for (int round = 0; round < 3; ++round) {  // collectives in a row reuse the slots
      const std::vector<uint64_t> v = {uint64_t(r * (round + 1)), uint64_t(7 - r), 1};
      max[r] = tx.AllReduceMax(v);
      scan[r] = tx.ExclusiveScanSum(v);
      uint64_t s0 = 0, s1 = 0;
      for (int q = 0; q < r; ++q) s0 += uint64_t(q * (round + 1)), s1 += uint64_t(7 - q);
      EXPECT_EQ(scan[r], (std::vector<uint64_t>{s0, s1, uint64_t(r)})) << "rank " << r;
      EXPECT_EQ(max[r], (std::vector<uint64_t>{uint64_t((p - 1) * (round + 1)), 7, 1}));
    }
    if (r != 0) {
      tx.Send(0, std::string(static_cast<size_t>(r) * 1000, char('a' + r)));
      tx.Send(0, "second " + std::to_string(r));
    } else {
      for (int q = p - 1; q >= 1; --q) {  // any order of senders
        at0.push_back(tx.Recv(q));
        at0.push_back(tx.Recv(q));
      }
    }
  });
  ASSERT_EQ(at0.size(), 8u);
  for (int q = p - 1, i = 0; q >= 1; --q, i += 2) {
    EXPECT_EQ(at0[i], std::string(static_cast<size_t>(q) * 1000, char('a' + q)));
    EXPECT_EQ(at0[i + 1], "second " + std::to_string(q));
  }
}

TEST(ThreadCommunicator, AllToAllDeliversEachMessageToItsRank) {
  // Every rank sends a different message to every other (empty ones among them), twice in a row,
  // then a plain message after: each arrives at its rank from its sender, in order.
  for (int p = 1; p <= 5; ++p) {
    std::vector<std::vector<std::string>> got(static_cast<size_t>(p));
    std::vector<std::string> after(static_cast<size_t>(p));
    auto message = [](int from, int to, int round) {
      return (from + to + round) % 3 == 0
                 ? std::string()
                 : std::to_string(from) + ">" + std::to_string(to) + "#" + std::to_string(round) +
                       std::string(static_cast<size_t>(from * 100 + to), 'x');
    };
    ThreadCommunicator::Run(p, [&](Communicator& tx) {
      const int r = tx.rank();
      for (int round = 0; round < 2; ++round) {
        std::vector<std::string> out(static_cast<size_t>(p));
        for (int j = 0; j < p; ++j)
          if (j != r) out[static_cast<size_t>(j)] = message(r, j, round);
        const std::vector<std::string> in = tx.AllToAll(std::move(out));
        ASSERT_EQ(in.size(), static_cast<size_t>(p));
        for (int j = 0; j < p; ++j)
          EXPECT_EQ(in[static_cast<size_t>(j)], j == r ? std::string() : message(j, r, round))
              << "p " << p << " rank " << r << " from " << j << " round " << round;
      }
      if (r != 0) tx.Send(0, "after " + std::to_string(r));
      if (r == 0)
        for (int j = 1; j < p; ++j) after[static_cast<size_t>(j)] = tx.Recv(j);
    });
    for (int j = 1; j < p; ++j)
      EXPECT_EQ(after[static_cast<size_t>(j)], "after " + std::to_string(j));
  }
}

TEST(ThreadCommunicator, AFailingRankEndsTheRunWithItsOwnError) {
  // Rank 2 fails while the others wait on it: in a collective, for ids, for bytes. Run returns
  // (no hang) and rethrows rank 2's error, not another rank's "another rank failed".
  for (int where = 0; where < 3; ++where) {
    std::atomic<int> released{0};
    try {
      ThreadCommunicator::Run(4, [&](Communicator& tx) {
        if (tx.rank() == 2) throw std::invalid_argument("rank 2 broke");
        try {
          if (where == 0) tx.AllReduceMax({1});
          if (where == 1 && tx.rank() == 3) {
            tx.Recv(2);  // rank 2's stack, as the chunk relay receives it
          }
          if (where == 1 && tx.rank() != 3) tx.AllReduceMax({1});
          if (where == 2) tx.Recv(2);
        } catch (const RankThreadsFailed&) {
          ++released;
          throw;
        }
      });
      FAIL() << "no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "rank 2 broke");
    }
    EXPECT_EQ(released.load(), 3) << "where " << where;
  }
}

}  // namespace
}  // namespace meshreuse
