// The registry: list.h expanded twice, once to declare the functions and once to build the table;
// and the one spec parser.
#include "core/orderings/registry.h"

#include <stdexcept>

#include "core/error.h"
#include "core/orderings/common.h"

namespace meshreuse {

#define MESHREUSE_ORDERING(fn, ...) Permutation fn(const Mesh&, const OrderingContext&);
#include "core/orderings/list.h"
#undef MESHREUSE_ORDERING

const std::vector<OrderingInfo>& Orderings() {
  static const std::vector<OrderingInfo> kTable = {
#define MESHREUSE_ORDERING(fn, name, arg, seeded, check, desc, ref) \
  {name, fn, OrderingArgument(arg), seeded, check, desc, ref},
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

OrderingSpec ParseOrderingSpec(const std::string& text) {
  OrderingSpec s;
  s.text = text;
  std::string body = text;
  // LABEL=spec: a label is a plain name (no ':' before the '='; a path may hold '=' later).
  const size_t eq = text.find('='), colon = text.find(':');
  if (eq != std::string::npos && (colon == std::string::npos || eq < colon)) {
    s.label = text.substr(0, eq);
    body = text.substr(eq + 1);
    if (s.label.empty()) throw UsageError("ordering '" + text + "': an empty label before '='");
  }
  const size_t c = body.find(':');
  s.name = body.substr(0, c);
  s.info = FindOrdering(s.name);
  if (!s.info) throw UsageError("unknown ordering '" + text + "' (known: " + OrderingNames() + ")");
  s.argument = c == std::string::npos ? "" : body.substr(c + 1);
  if (s.info->argument == kArgument && s.argument.empty())
    throw UsageError("ordering '" + s.name + "' needs an argument: " + s.name + ":ARG");
  if (s.info->argument == kNoArgument && c != std::string::npos)
    throw UsageError("ordering '" + s.name + "' takes no argument");
  if (s.info->check) s.info->check(s.argument);
  if (s.label.empty()) s.label = body;
  return s;
}

OrderingSpec::OrderingSpec(const std::string& t) : OrderingSpec(ParseOrderingSpec(t)) {}

std::vector<OrderingSpec> ParseOrderingSpecs(const std::vector<std::string>& texts) {
  return std::vector<OrderingSpec>(texts.begin(), texts.end());
}

Permutation ComputeOrdering(const OrderingSpec& s, const Mesh& m, uint64_t seed) {
  OrderingContext ctx;
  ctx.seed = seed;
  ctx.argument = s.argument;
  Permutation p = s.info->fn(m, ctx);
  if (p.size() != m.NumVertices())
    throw std::logic_error("ordering '" + s.name + "' returned a permutation of the wrong size");
  return p;
}

std::vector<std::pair<std::string, uint64_t>> SeededOrderings(
    const std::vector<OrderingSpec>& specs, uint64_t seed) {
  std::vector<std::pair<std::string, uint64_t>> out;
  for (const OrderingSpec& s : specs) {
    if (s.info->seeded) out.emplace_back(s.label, seed);
  }
  return out;
}

}  // namespace meshreuse
