// Vertex orderings: each maps a mesh to a Permutation (new -> old). One file per ordering under
// core/orderings/, one line per ordering in list.h; this header is how everything else finds them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/permutation.h"

namespace meshreuse {

struct OrderingContext {
  uint64_t seed = 1;     // for randomised orderings; reported in every output
  std::string argument;  // the part after ':' in "name:argument" (file:PATH, metis:BYTES)
};

// Whether "name:argument" is refused, required or accepted (list.h's third column).
enum OrderingArgument { kNoArgument = 0, kArgument = 1, kOptionalArgument = 2 };

using OrderingFn = Permutation (*)(const Mesh&, const OrderingContext&);

struct OrderingInfo {
  const char* name;
  OrderingFn fn;
  OrderingArgument argument;
  const char* description;
  const char* reference;
  bool takes_argument() const { return argument == kArgument; }  // required
};

const std::vector<OrderingInfo>& Orderings();
const OrderingInfo* FindOrdering(const std::string& name);  // nullptr when unknown
std::string OrderingNames();                                // "ori, random, ..."

// Checks "name" or "name:argument" without computing anything (for option checking before a long
// run): the name, the argument's presence, and the argument itself where it can be checked
// without the mesh (metis:BYTES). Throws std::invalid_argument.
void CheckOrderingSpec(const std::string& spec);

// Computes "name" or "name:argument". Throws std::invalid_argument for an unknown name or a
// missing/unexpected argument, and whatever the ordering throws (file: InputError).
Permutation ComputeOrdering(const std::string& spec, const Mesh& m, uint64_t seed = 1);

}  // namespace meshreuse
