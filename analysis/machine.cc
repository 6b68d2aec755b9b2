// Machines and thread placement; see machine.h.
#include "analysis/machine.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "analysis/cache_sim.h"
#include "core/error.h"
#include "core/text_file.h"

namespace meshreuse {

size_t Machine::private_levels() const {
  size_t n = 0;
  while (n < levels.size() && !levels[n].shared) ++n;
  return n;
}

namespace {

Machine WestmereEx() {
  Machine m;
  m.name = m.text = "westmere-ex";
  m.sockets = 4, m.cores_per_socket = 8;
  const CacheSpec c = ParseCacheSpec("westmere-ex");
  for (size_t i = 0; i < c.levels.size(); ++i) {
    MachineLevel l;
    l.cache = c.levels[i];
    l.shared = i == 2;
    l.inclusive = i == 2;
    m.levels.push_back(l);
  }
  m.memory_local = c.memory.low, m.memory_remote = c.memory.high;
  return m;
}

void Check(const Machine& m, const std::function<void(const std::string&)>& fail) {
  if (m.sockets < 1 || m.sockets > 8 || m.cores_per_socket < 1 || m.cores() > 64)
    fail("a machine has 1..8 sockets and 1..64 cores (sockets x cores per socket)");
  if (m.line_bytes == 0 || (m.line_bytes & (m.line_bytes - 1)) || m.line_bytes > 4096)
    fail("the line size must be a power of two up to 4096");
  if (m.levels.empty() || m.levels.size() > Machine::kMaxLevels)
    fail("a machine has 1.." + std::to_string(Machine::kMaxLevels) + " cache levels");
  bool seen_shared = false;
  for (const MachineLevel& l : m.levels) {
    if (!l.shared && seen_shared)
      fail("private level " + l.cache.name + " after a shared one: private levels come first");
    seen_shared = seen_shared || l.shared;
    if (l.cache.ways == 0) fail("level " + l.cache.name + " needs its ways (e.g. 32K/8)");
    if (l.cache.bytes % (uint64_t{m.line_bytes} * l.cache.ways) != 0)
      fail("level " + l.cache.name + ": the size must be a multiple of ways x line size");
    if (l.cache.bytes / m.line_bytes > SetAssociativeCache::kMaxLines)
      fail("level " + l.cache.name + ": " + std::to_string(l.cache.bytes / m.line_bytes) +
           " lines of " + std::to_string(m.line_bytes) + " B; a level holds at most " +
           std::to_string(SetAssociativeCache::kMaxLines) + " lines");
    if (l.inclusive && !l.shared) fail("only a shared level can be inclusive");
    if (!l.cache.latency.known()) fail("level " + l.cache.name + " needs its latency (@CYCLES)");
  }
  if (!(m.memory_local > 0) || !(m.memory_remote > 0)) fail("memory needs its latencies");
}

}  // namespace

std::string CanonicalMachine(const std::string& spec) {
  return spec == "westmere" ? "westmere-ex" : spec;
}

Machine ParseMachine(const std::string& spec) {
  if (spec == "westmere-ex" || spec == "westmere") return WestmereEx();
  if (spec.find('/') == std::string::npos && spec.find('.') == std::string::npos)
    throw UsageError(
        "--machine: '" + spec +
        "' is neither westmere-ex (alias westmere) nor a machine file (a path with a / or a .)");
  TextFile f(spec);
  Machine m;
  m.name = spec, m.text = spec;
  std::string_view line, tok[4];
  std::vector<std::string> prefetch;
  while (f.NextDataLine(&line)) {
    const int n = Tokens(line).Split(tok, 4);
    const std::string key(tok[0]);
    auto need = [&](int k) {
      if (n != k) f.Fail("'" + key + "' takes " + std::to_string(k - 1) + " value(s)");
    };
    auto count = [&](std::string_view t, int64_t lo, int64_t hi) {
      const int64_t v = f.ParseInt(t, key.c_str());
      if (v < lo || v > hi)
        f.Fail(key + " must be " + std::to_string(lo) + ".." + std::to_string(hi));
      return v;
    };
    if (key == "name") {
      need(2);
      m.name = std::string(tok[1]);
      for (char c : m.name)  // it goes into tables, CSV and terminals as it is
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == ',' || c == '"')
          f.Fail(
              "the name holds a control character, a comma or a quote (it goes into tables "
              "and CSV as it is)");
    } else if (key == "sockets") {
      need(2);
      m.sockets = static_cast<int>(count(tok[1], 1, 64));
    } else if (key == "cores") {
      need(2);
      m.cores_per_socket = static_cast<int>(count(tok[1], 1, 64));
    } else if (key == "line") {
      need(2);
      m.line_bytes = static_cast<uint32_t>(count(tok[1], 1, 4096));
    } else if (key == "memory") {
      need(3);
      m.memory_local = f.ParseDouble(tok[1], "the local memory latency");
      m.memory_remote = f.ParseDouble(tok[2], "the remote memory latency");
      if (!(m.memory_local > 0 && m.memory_remote > 0 && std::isfinite(m.memory_local) &&
            std::isfinite(m.memory_remote)))
        f.Fail("memory latencies must be positive numbers of cycles");
    } else if (key == "numa") {
      need(2);
      if (tok[1] == "first-touch")
        m.numa = Numa::kFirstTouch;
      else if (tok[1] == "interleave")
        m.numa = Numa::kInterleave;
      else
        f.Fail("numa is first-touch or interleave");
    } else if (key == "coherence") {
      need(2);
      if (tok[1] != "invalidate" && tok[1] != "none") f.Fail("coherence is invalidate or none");
      m.coherence = tok[1] == "invalidate";
    } else if (key == "private" || key == "shared") {
      if (n < 2 || n > 3) f.Fail("'" + key + "' takes a level, NAME=SIZE/WAYS@CYCLES");
      if (n == 3 && (key != "shared" || tok[2] != "inclusive"))
        f.Fail("only 'inclusive' may follow a shared level");
      CacheSpec one;
      try {
        one = ParseCacheSpec(std::string(tok[1]));
      } catch (const UsageError& e) {
        f.Fail(e.what());
      }
      if (one.levels.size() != 1) f.Fail("one level per line");
      MachineLevel l;
      l.cache = one.levels[0];
      l.shared = key == "shared";
      l.inclusive = n == 3;
      m.levels.push_back(l);
    } else if (key == "prefetch") {
      need(2);
      prefetch.emplace_back(tok[1]);
    } else {
      f.Fail("unknown key '" + key +
             "' (name, sockets, cores, line, memory, numa, coherence, private, shared, prefetch)");
    }
  }
  for (const std::string& p : prefetch) {
    bool found = false;
    for (MachineLevel& l : m.levels)
      if (l.cache.name == p) l.prefetch = found = true;
    if (!found) throw InputError(spec, 0, "prefetch names level " + p + ", which is not defined");
  }
  Check(m, [&](const std::string& why) { throw InputError(spec, 0, why); });
  return m;
}

void SetPrefetch(Machine* m, const std::string& levels) {
  if (levels.empty()) return;
  if (levels == "none") {
    for (MachineLevel& l : m->levels) l.prefetch = false;
    return;
  }
  size_t at = 0;
  while (at <= levels.size()) {
    const size_t comma = std::min(levels.find(',', at), levels.size());
    const std::string name = levels.substr(at, comma - at);
    bool found = false;
    for (MachineLevel& l : m->levels)
      if (l.cache.name == name) l.prefetch = found = true;
    if (!found)
      throw UsageError("--prefetch: the machine has no level '" + name + "' (levels: " + [&] {
        std::string s;
        for (const MachineLevel& l : m->levels) s += (s.empty() ? "" : ", ") + l.cache.name;
        return s;
      }() + "; or none)");
    at = comma + 1;
  }
}

Placement ParsePlacement(const std::string& s) {
  if (s == "compact" || s == "close") return Placement::kCompact;
  if (s == "scatter" || s == "spread") return Placement::kScatter;
  throw UsageError("--placement: '" + s + "' (compact or scatter)");
}

const char* PlacementName(Placement p) { return p == Placement::kCompact ? "compact" : "scatter"; }

std::vector<int> PlaceThreads(const Machine& m, int threads, Placement p) {
  if (threads < 1 || threads > m.cores())
    throw UsageError("--threads " + std::to_string(threads) + ": the machine " + m.name + " has " +
                     std::to_string(m.cores()) + " cores");
  std::vector<int> core(threads);
  for (int t = 0; t < threads; ++t) {
    if (p == Placement::kCompact) {
      core[t] = t;
    } else {  // socket t % S, the next free core there
      const int s = t % m.sockets, k = t / m.sockets;
      core[t] = s * m.cores_per_socket + k;
    }
  }
  return core;
}

}  // namespace meshreuse
