// A multi-core machine for the simulator (analysis/multicore_sim.h): sockets x cores per socket,
// cache levels each private to a core or shared by a socket's cores (an inclusive shared level
// evicts what it drops from the private levels above it), a line size, memory latencies local and
// remote (NUMA), write-invalidate coherence on or off, and a next-line prefetcher per level.
// "westmere-ex" is the paper's machine (Aupy, Park, Raghavan, section "Experimental Setup"): four
// Xeon E7-8837 sockets of eight cores, 32 KiB/8 and 256 KiB/8 private, 24 MiB/24 shared and
// inclusive per socket, 64-byte lines; latencies of Molka et al. 2009 ("Memory performance and
// cache coherency effects on an Intel Nehalem multiprocessor system", PACT), the paper's source:
// L1 4, L2 10, L3 38-170, memory 175 (local) to 290 (remote) cycles.
// A machine file (the way drcachesim names each cache, its scope and its inclusion):
//   # comment
//   name my-machine
//   sockets 2
//   cores 4                      (per socket)
//   line 64
//   memory 175 290               (cycles: local, remote)
//   numa first-touch             (or interleave: 4 KiB pages dealt over the sockets)
//   coherence invalidate         (or none)
//   private L1=32K/8@4           (the level syntax of --cache: NAME=SIZE/WAYS[/POLICY][@CYCLES])
//   private L2=256K/8@10
//   shared L3=24M/24@38-170 inclusive
//   prefetch L2                  (a next-line prefetcher at that level)
// Private levels come first, then shared ones. At most 8 sockets, 64 cores, 8 levels.
// Placement of OpenMP threads on cores: compact (proc_bind(close), KMP_AFFINITY=compact: fill
// socket 0 first, as the paper ran) or scatter (proc_bind(spread): thread t on socket t % sockets).
// NUMA: the mesh is read and built by one thread, so with first-touch every page lives on socket
// 0's memory (a miss from another socket is remote); interleave deals pages round-robin.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "analysis/cache_model.h"

namespace meshreuse {

struct MachineLevel {
  CacheLevel cache;        // name, bytes, ways, policy, latency of a hit here
  bool shared = false;     // by the cores of a socket; else private to a core
  bool inclusive = false;  // shared levels only: evicting a line removes it above
  bool prefetch = false;   // next-line prefetcher: a miss of line L brings L+1 into this level
};

enum class Numa { kFirstTouch, kInterleave };
enum class Placement { kCompact, kScatter };

struct Machine {
  static constexpr size_t kMaxLevels = 8;  // cache levels a machine may have (Check)
  std::string name;
  int sockets = 1, cores_per_socket = 1;
  uint32_t line_bytes = 64;
  std::vector<MachineLevel> levels;
  double memory_local = 0, memory_remote = 0;  // cycles
  Numa numa = Numa::kFirstTouch;
  bool coherence = true;
  std::string text;  // as given (a preset's name or the file's path), for tables
  int cores() const { return sockets * cores_per_socket; }
  size_t private_levels() const;
};

// "westmere-ex" (alias "westmere"), or a machine file as above. Throws UsageError (a preset or
// option) or InputError (a file, naming the line).
Machine ParseMachine(const std::string& name_or_file);
// The name a built-in machine goes by ("westmere" -> "westmere-ex"); a file's path as given.
std::string CanonicalMachine(const std::string& name_or_file);
// Turns the prefetcher on at the named levels ("L1,L2"; "" leaves the machine's own).
void SetPrefetch(Machine* m, const std::string& levels);

Placement ParsePlacement(const std::string& s);  // compact, scatter
const char* PlacementName(Placement p);
// The core of each of `threads` threads (UsageError beyond the machine's cores).
std::vector<int> PlaceThreads(const Machine& m, int threads, Placement p);

}  // namespace meshreuse
