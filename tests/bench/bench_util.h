// What the benchmark files share (defined in bench_main.cc): the mesh every benchmark runs on
// (--mesh, or a synthetic one of about 330k vertices), medians, ratios measured pair by pair.
#pragma once

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "core/mesh.h"

namespace meshreuse {

const Mesh& BaseMesh();
double Median(std::vector<double> v);
// Ratios measured pair by pair (both of a pair in the same iteration): their median as `name`,
// and their range as name_min, name_max.
void PutRatios(benchmark::State& state, const std::string& name, std::vector<double> r);
// kernel_bench.cc: Kernel/NAME for every kernel but the Laplacian.
void RegisterKernelBenchmarks();

}  // namespace meshreuse
