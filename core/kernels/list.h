// The kernel registry's one table. Adding a kernel: write core/kernels/NAME.cc defining
//   template <class Sink> SmoothResult FUNCTION(Mesh&, const SmoothOptions&, Sink&);
//   MESHREUSE_KERNEL_ENTRIES(FUNCTION)
//   std::vector<uint64_t> FUNCTIONRefs(const Mesh&, const SmoothOptions&);  // {} when unknown
// (MESHREUSE_KERNEL_ENTRIES_WITH_SETUP and a FUNCTIONSetup instead where its untimed set-up can be
// shared by runs on one input: kernel.h, KernelSetup)
// with its definition, reference and access sequence at its head, and add one line here (the build
// picks the file up by itself):
//   MESHREUSE_KERNEL(FUNCTION, "name", unit, jacobi, threads, moves, fixed, "measure",
//                    "parallel form", "description", "reference")
// Every test that loops over the registry picks it up. (No include guard: included twice.)
MESHREUSE_KERNEL(KernelLaplacian, "laplacian", VisitUnit::kVertex, true, true, true, false,
                 "global quality (mean vertex quality, shortest/longest edge)",
                 "the interior list split as schedule(static); neighbours moved by another "
                 "thread are read as they are (the paper's races)",
                 "the paper's Algorithm 1: each interior vertex to the average of its neighbours "
                 "(core/smoother.h)",
                 "Aupy, Park, Raghavan, Algorithm 1; Mesquite's LaplacianSmoother")
MESHREUSE_KERNEL(KernelSmartLaplacian, "smart-laplacian", VisitUnit::kVertex, false, true, true,
                 false, "global quality (as laplacian)",
                 "as laplacian (Gauss-Seidel in place, races at the chunks' borders)",
                 "constrained Laplacian: the move to the neighbours' average is kept only if the "
                 "smallest quality of the vertex's triangles does not drop",
                 "Freitag, Jones and Plassmann 1995 (smart Laplacian)")
MESHREUSE_KERNEL(KernelLocalOpt, "local-opt", VisitUnit::kVertex, false, true, true, false,
                 "global quality (as laplacian)",
                 "as laplacian (Gauss-Seidel in place, races at the chunks' borders)",
                 "optimisation-based smoothing: per vertex two steepest-descent steps with "
                 "backtracking on the sum of its triangles' inverse mean ratios",
                 "Knupp 2000; Freitag and Knupp 2002; Mesquite's local-patch solvers")
MESHREUSE_KERNEL(KernelUntangle, "untangle", VisitUnit::kVertex, false, true, true, false,
                 "share of triangles not turned over (1 - inverted/T)",
                 "as laplacian (Gauss-Seidel in place, races at the chunks' borders)",
                 "mesh untangling: the input tangled on purpose (5% of interior vertices moved "
                 "past a neighbour), then per vertex a Newton step on the untangle-beta objective",
                 "Freitag and Plassmann 2000; Mesquite's untangle-beta metric")
MESHREUSE_KERNEL(KernelEdgeSwap, "edge-swap", VisitUnit::kEdge, false, false, true, false,
                 "1 - flips / interior edges in the sweep (1: every edge locally Delaunay)",
                 "none: two flips sharing a triangle would race",
                 "mesh swapping: the input jittered on purpose (valid, no longer Delaunay), then "
                 "Lawson flips of every edge not locally Delaunay, triangles in storage order",
                 "Lawson 1977; Freitag and Ollivier-Gooch 1997 (edge swapping)")
MESHREUSE_KERNEL(KernelAssembly, "assembly", VisitUnit::kTriangle, false, false, false, true,
                 "the assembled matrix's trace",
                 "none yet: triangles sharing a vertex add to the same entries (a colouring or "
                 "an owner-computes split is not built)",
                 "element loop: the P1 Laplace stiffness matrix assembled into CSR by "
                 "scatter-add, from zero every sweep",
                 "any FEM text (Ciarlet); the element-centric kernel of Strout and Hovland 2004")
MESHREUSE_KERNEL(KernelSpmv, "spmv", VisitUnit::kRow, false, true, false, true,
                 "x^T A x (the mesh's area, for x the coordinate function)",
                 "the rows split as schedule(static); each thread writes its own rows",
                 "row loop: y = A x with the P1 stiffness matrix and x the vertices' x "
                 "coordinates",
                 "the row-centric kernel of FEM codes; Strout and Hovland 2004")
