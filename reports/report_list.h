// The report's one table of outputs: every table, data file and figure, declared once. Adding a
// table: write reports/outputs/NAME.cc defining
//   ReportPart FUNCTION(const ReportData&);   (report_outputs.h)
// and add one line here (the build picks the file up; the README, run.json, manifest.json, the
// plotting script and the checker all read this table):
//   MESHREUSE_REPORT_TABLE(FUNCTION, "name", "paper's reference", "README title", "LaTeX caption")
//       tables/NAME.{csv,md,tex} and a README section (an empty title: no section)
//   MESHREUSE_REPORT_DATA(FUNCTION, "file")          data/FILE, a figure's input
//   MESHREUSE_REPORT_FIGURE("name", "paper's reference", "plot_X.py[:VARIANT]", "inputs", "when",
//                           "title")
//       figures/NAME.{png,pdf}, drawn from its inputs (paths in the folder, space-separated) when
//       they were all written and `when` holds ("" always, "scale" for a scale run);
//       {figure1_mesh}, {profile_mesh}, {profile_sweeps} in the title are the configuration's.
// (No include guard: included several times.)
MESHREUSE_REPORT_TABLE(ReportTable1, "table1", "Table 1", "Table 1: meshes",
                       "Input mesh configuration (the paper's Table 1)")
MESHREUSE_REPORT_TABLE(ReportTable2, "table2", "Table 2",
                       "Table 2: reuse distances of the first sweep",
                       "Reuse distances of the first sweep (element stream, distinct vertices): "
                       "quantiles and accesses (the paper's Table 2)")
MESHREUSE_REPORT_TABLE(ReportTable3, "table3", "Table 3",
                       "Table 3: estimated misses and capacities",
                       "Estimated misses per sweep ($\\times 10^3$) and the inverse model's "
                       "capacities ($\\times 10^3$ elements; lines) (the paper's Table 3)")
MESHREUSE_REPORT_TABLE(ReportMisses, "misses", "Figure 9 (data)", "",
                       "Misses of the last traced sweep per level (simulated unless measured)")
MESHREUSE_REPORT_TABLE(ReportMissReduction, "miss_reduction", "text, \"Cache Performance\"",
                       "Fewer misses than ORI and BFS",
                       "Fewer misses per level than ORI and BFS (mean over the meshes, \\%), one "
                       "thread")
MESHREUSE_REPORT_TABLE(ReportTime, "time", "Figure 8 (data)", "Execution time",
                       "Execution time to convergence on one thread, and the speedups against ORI "
                       "and BFS")
MESHREUSE_REPORT_TABLE(ReportSpeedup, "speedup", "text, \"Serial execution\"",
                       "Speedup against ORI and BFS (one thread)",
                       "Mean one-thread speedup over the meshes against ORI and BFS")
MESHREUSE_REPORT_TABLE(ReportScaling, "scaling", "Figures 10, 12, 13 (data)", "",
                       "Speedup(p) = $T_{ori}(1)/T_{ord}(p)$ and Gain(p) against ORI and BFS")
MESHREUSE_REPORT_TABLE(ReportScalingMean, "scaling_mean", "Figures 10, 12, 13 (means)",
                       "Speedup(p) and Gain(p)", "Mean Speedup(p) and Gain(p) over the meshes")
MESHREUSE_REPORT_TABLE(ReportReorderCost, "reorder_cost", "text, \"Discussion on reordering cost\"",
                       "Reordering cost",
                       "Cost of reordering in ORI sweeps (one thread): computing the ordering and "
                       "applying it")
MESHREUSE_REPORT_TABLE(ReportMachineMisses, "machine_misses", "Figure 11 (data)",
                       "Many cores: misses per level on the simulated machine",
                       "Simulated misses of the warm sweep per level on the many-core machine "
                       "($\\times 10^3$, mean over the meshes), by placement and thread count")
MESHREUSE_REPORT_TABLE(ReportPredictedSpeedup, "predicted_speedup",
                       "Figures 10, 12, 13; text, \"Parallel execution\"",
                       "Many cores: Speedup(p) and Gain(p) predicted",
                       "Speedup(p) and Gain(p) predicted by the many-core simulator's cost model "
                       "(mean over the meshes), beside the measured speedup and the paper's claims")
MESHREUSE_REPORT_TABLE(
    ReportPrefetch, "prefetch", "Table 3 (measured)",
    "A next-line prefetcher against the paper's measured misses",
    "One-thread misses ($\\times 10^3$) without and with a next-line prefetcher, "
    "beside the paper's PAPI measurements")
MESHREUSE_REPORT_TABLE(ReportKernels, "kernels", "conclusion (conjecture)", "",
                       "Other mesh kernels per mesh: time per sweep, speedup against ORI, gain "
                       "against BFS, simulated misses of the warm sweep and their floor, line "
                       "reuse-distance quantiles")
MESHREUSE_REPORT_TABLE(ReportKernelsMean, "kernels_mean", "conclusion (conjecture)",
                       "Other mesh kernels: the paper's conjecture",
                       "Other mesh kernels, means over the meshes: speedup against ORI, gain "
                       "against BFS, misses per 1000 accesses and over the floor, q90")
MESHREUSE_REPORT_DATA(ReportHistogramData, "histogram.csv")
MESHREUSE_REPORT_DATA(ReportProfileData, "profile.csv")
MESHREUSE_REPORT_DATA(ReportCapacitiesData, "capacities.csv")
MESHREUSE_REPORT_DATA(ReportFigure1Data, "figure1.csv")
MESHREUSE_REPORT_DATA(ReportFigure1Summary, "figure1_summary.csv")
MESHREUSE_REPORT_DATA(ReportMissesData, "misses.csv")
MESHREUSE_REPORT_DATA(ReportCompareJson, "compare.json")
MESHREUSE_REPORT_DATA(ReportMeshDrawing, "meshes.csv")
MESHREUSE_REPORT_DATA(ReportSmoothingWindow, "smoothing.csv")
MESHREUSE_REPORT_DATA(ReportOrderPositions, "order_positions.csv")
MESHREUSE_REPORT_DATA(ReportMachineData, "machine.csv")
MESHREUSE_REPORT_FIGURE("figure1", "Figure 1", "plot_figure1.py",
                        "data/figure1.csv data/figure1_summary.csv", "",
                        "reuse distance of every access of the first sweep on {figure1_mesh} "
                        "(random, ORI, BFS)")
MESHREUSE_REPORT_FIGURE("profile", "Figure 6", "plot_profile.py", "data/profile.csv", "",
                        "reuse-distance profile over {profile_sweeps} sweeps of {profile_mesh}, "
                        "one panel per ordering")
MESHREUSE_REPORT_FIGURE("histograms", "-", "plot_histograms.py",
                        "data/histogram.csv data/capacities.csv", "",
                        "first-sweep reuse-distance histograms with the cache capacities")
MESHREUSE_REPORT_FIGURE("miss-rates", "Figure 9", "plot_misses.py", "data/misses.csv", "",
                        "L1/L2/L3 misses per access (global rates) of the warm sweep, per mesh and "
                        "ordering")
MESHREUSE_REPORT_FIGURE("time", "Figure 8", "plot_time.py", "tables/time.csv", "",
                        "execution time to convergence per mesh and ordering, one thread")
MESHREUSE_REPORT_FIGURE("speedup", "Figure 10", "plot_speedup.py:speedup", "tables/scaling.csv", "",
                        "Speedup(p) = T_ori(1) / T_ord(p) per mesh")
MESHREUSE_REPORT_FIGURE("speedup-mean", "Figure 12", "plot_speedup.py:mean",
                        "tables/scaling.csv tables/scaling_mean.csv", "",
                        "mean Speedup(p) over the meshes")
MESHREUSE_REPORT_FIGURE("gain", "Figure 13", "plot_speedup.py:gain",
                        "tables/scaling.csv tables/scaling_mean.csv", "",
                        "Gain(p) against ORI and BFS per mesh")
MESHREUSE_REPORT_FIGURE("meshes", "Figure 7", "plot_meshes.py", "data/meshes.csv", "",
                        "the meshes: boundaries and a sample of the vertices")
MESHREUSE_REPORT_FIGURE("smoothing", "-", "plot_smoothing.py", "data/smoothing.csv", "",
                        "a window of {figure1_mesh} before and after smoothing, triangles coloured "
                        "by quality")
MESHREUSE_REPORT_FIGURE("orderings", "-", "plot_orderings.py", "data/order_positions.csv", "",
                        "each ordering as a picture: {figure1_mesh}'s vertices coloured by their "
                        "position in the ordering")
MESHREUSE_REPORT_FIGURE("figure11", "Figure 11", "plot_machine.py:figure11", "data/machine.csv", "",
                        "accesses served by L2, L3 and memory against the cores on the simulated "
                        "machine (ORI, BFS, RDR; compact solid, scatter dashed)")
MESHREUSE_REPORT_FIGURE("machine-misses", "-", "plot_machine.py:misses",
                        "tables/machine_misses.csv", "",
                        "simulated misses per level against the cores, mean over the meshes, both "
                        "placements")
MESHREUSE_REPORT_FIGURE("predicted-speedup", "Figure 12", "plot_machine.py:speedup",
                        "tables/predicted_speedup.csv", "",
                        "Speedup(p) predicted on the simulated machine (both placements, latency "
                        "range shaded) beside the measured speedups and the paper's claim")
MESHREUSE_REPORT_FIGURE("scale", "-", "plot_scale.py",
                        "tables/table1.csv tables/time.csv data/misses.csv", "scale",
                        "time per vertex per sweep and simulated misses per access vs size")
MESHREUSE_REPORT_FIGURE("kernels", "conclusion (conjecture)", "plot_kernels.py",
                        "tables/kernels_mean.csv", "",
                        "speedup per sweep against ORI of each kernel, mean over the meshes")
