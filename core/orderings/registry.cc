// The registry: list.h expanded twice, once to declare the functions and once to build the table.
#include "core/orderings/registry.h"

#include <stdexcept>

#include "core/orderings/common.h"

namespace meshreuse {

#define MESHREUSE_ORDERING(fn, ...) Permutation fn(const Mesh&, const OrderingContext&);
#include "core/orderings/list.h"
#undef MESHREUSE_ORDERING

const std::vector<OrderingInfo>& Orderings() {
  static const std::vector<OrderingInfo> kTable = {
#define MESHREUSE_ORDERING(fn, name, arg, desc, ref) {name, fn, OrderingArgument(arg), desc, ref},
#include "core/orderings/list.h"
#undef MESHREUSE_ORDERING
  };
  return kTable;
}

const OrderingInfo* FindOrdering(const std::string& name) {
  for (const OrderingInfo& o : Orderings())
    if (name == o.name) return &o;
  return nullptr;
}

std::string OrderingNames() {
  std::string s;
  for (const OrderingInfo& o : Orderings())
    s += (s.empty() ? "" : ", ") + std::string(o.name) +
         (o.argument == kArgument           ? ":ARG"
          : o.argument == kOptionalArgument ? "[:ARG]"
                                            : "");
  return s;
}

void CheckOrderingSpec(const std::string& spec) {
  const size_t colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  const OrderingInfo* o = FindOrdering(name);
  if (!o)
    throw std::invalid_argument("unknown ordering '" + spec + "' (known: " + OrderingNames() + ")");
  const std::string arg = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (o->argument == kArgument && arg.empty())
    throw std::invalid_argument("ordering '" + name + "' needs an argument: " + name + ":ARG");
  if (o->argument == kNoArgument && colon != std::string::npos)
    throw std::invalid_argument("ordering '" + name + "' takes no argument");
  if (name == "metis") orderings::ParseMetisPartBytes(arg);
}

Permutation ComputeOrdering(const std::string& spec, const Mesh& m, uint64_t seed) {
  const size_t colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  const OrderingInfo* o = FindOrdering(name);
  if (!o)
    throw std::invalid_argument("unknown ordering '" + name + "' (known: " + OrderingNames() + ")");
  OrderingContext ctx;
  ctx.seed = seed;
  if (colon != std::string::npos) ctx.argument = spec.substr(colon + 1);
  if (o->argument == kArgument && ctx.argument.empty())
    throw std::invalid_argument("ordering '" + name + "' needs an argument: " + name + ":ARG");
  if (o->argument == kNoArgument && colon != std::string::npos)
    throw std::invalid_argument("ordering '" + name + "' takes no argument");
  Permutation p = o->fn(m, ctx);
  if (p.size() != m.NumVertices())
    throw std::logic_error("ordering '" + name + "' returned a permutation of the wrong size");
  return p;
}

}  // namespace meshreuse
