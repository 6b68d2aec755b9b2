// Vertex orderings: each maps a mesh to a Permutation (new -> old). One file per ordering under
// core/orderings/, one line per ordering in list.h; this header is how everything else finds them.
// An ordering is named by a spec: "name", "name:argument" (file:PATH, metis:BYTES), optionally
// labelled "LABEL=name[:argument]" so tables show LABEL (e.g. xsort=file:perms/x.perm). One
// parser (ParseOrderingSpec) checks every spec, before any work, for every command.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/permutation.h"

namespace meshreuse {

struct OrderingContext {
  uint64_t seed = 1;     // for seeded orderings (OrderingInfo::seeded); recorded in every output
  std::string argument;  // the part after ':' in "name:argument" (file:PATH, metis:BYTES)
};

// Whether "name:argument" is refused, required or accepted (list.h's third column).
enum OrderingArgument { kNoArgument = 0, kArgument = 1, kOptionalArgument = 2 };

using OrderingFn = Permutation (*)(const Mesh&, const OrderingContext&);
// Checks an argument without the mesh (throws UsageError), for option checking before a long run.
using ArgumentCheck = void (*)(const std::string& argument);

struct OrderingInfo {
  const char* name;
  OrderingFn fn;
  OrderingArgument argument;
  bool seeded;          // the order depends on --seed (random, metis, nd)
  ArgumentCheck check;  // nullptr: any argument the function accepts
  const char* description;
  const char* reference;
  bool takes_argument() const { return argument == kArgument; }  // required
};

const std::vector<OrderingInfo>& Orderings();
const OrderingInfo* FindOrdering(const std::string& name);  // nullptr when unknown
std::string OrderingNames();                                // "ori, random, ..."

// A parsed spec. Built from its text (a std::string or a literal) it parses it, so a list of specs
// reads as {"ori", "bfs"}; the runners hold their orderings parsed once, as specs.
struct OrderingSpec {
  OrderingSpec() = default;
  OrderingSpec(const std::string& text);  // NOLINT: ParseOrderingSpec (UsageError)
  OrderingSpec(const char* text) : OrderingSpec(std::string(text)) {}  // NOLINT
  std::string text;                                                    // as given
  std::string label;     // what tables call it: LABEL when given, else the spec without it
  std::string name;      // the registered name
  std::string argument;  // after ':' ("" when none)
  const OrderingInfo* info = nullptr;
  std::string spec() const {
    return argument.empty() && info->argument != kArgument ? name : name + ":" + argument;
  }
};
// Parses and checks a spec: the name is registered, the argument present when required, absent
// when refused, and valid where it can be checked without the mesh. Throws UsageError.
OrderingSpec ParseOrderingSpec(const std::string& text);
inline void CheckOrderingSpec(const std::string& text) { ParseOrderingSpec(text); }

// Computes a spec ("name", "name:argument", "LABEL=..."). Throws UsageError for a bad spec and
// whatever the ordering throws (file: InputError).
Permutation ComputeOrdering(const OrderingSpec& spec, const Mesh& m, uint64_t seed = 1);
// Each text parsed (UsageError for the first that is not a spec).
std::vector<OrderingSpec> ParseOrderingSpecs(const std::vector<std::string>& texts);

// The seeds that matter for these specs: {label: seed} for each seeded ordering among them
// (run.json, .perm headers).
std::vector<std::pair<std::string, uint64_t>> SeededOrderings(
    const std::vector<OrderingSpec>& specs, uint64_t seed);

}  // namespace meshreuse
