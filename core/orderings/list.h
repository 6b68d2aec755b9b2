// The ordering registry's one table. Adding an ordering: write core/orderings/NAME.cc defining
//   Permutation FUNCTION(const Mesh&, const OrderingContext&);
// and add one line here (the build picks the file up by itself):
//   MESHREUSE_ORDERING(FUNCTION, "name", argument, seeded, check, "description", "reference")
// argument: false (none), true (required, name:ARG) or kOptionalArgument; seeded: whether --seed
// changes the order (then every output records the seed); check: a function that checks the
// argument without the mesh (throws UsageError), or nullptr.
// Every test that loops over the registry picks it up. (No include guard: included twice.)
MESHREUSE_ORDERING(OrderOri, "ori", false, false, nullptr,
                   "identity: the generator's own numbering (Triangle's, for the shipped shapes)",
                   "the paper's ORI")
MESHREUSE_ORDERING(OrderRandom, "random", false, true, nullptr,
                   "uniform random shuffle, seeded by --seed", "Fisher-Yates with SplitMix64")
MESHREUSE_ORDERING(OrderBfs, "bfs", false, false, nullptr,
                   "breadth-first visit order from vertex 0, neighbours by increasing id; each "
                   "further component from its lowest unvisited id",
                   "Strout and Hovland 2004")
MESHREUSE_ORDERING(OrderRbfs, "rbfs", false, false, nullptr, "the BFS visit order reversed",
                   "Munson and Hovland (reversed BFS)")
MESHREUSE_ORDERING(OrderRcm, "rcm", false, false, nullptr,
                   "reverse Cuthill-McKee by Boost.Graph's cuthill_mckee_ordering: per component "
                   "from Boost's pseudo-peripheral vertex, the BFS order reversed",
                   "Cuthill and McKee 1969; George and Liu 1981; Boost.Graph")
MESHREUSE_ORDERING(OrderRdr, "rdr", false, false, nullptr,
                   "the paper's Algorithm 2: from the worst interior vertex, append unordered "
                   "neighbours by increasing quality, continue from the worst unprocessed one",
                   "Aupy, Park, Raghavan, Algorithm 2")
MESHREUSE_ORDERING(
    OrderHilbert, "hilbert", false, false, nullptr,
    "vertices sorted along a Hilbert curve over a 2^16 x 2^16 grid of the bounding box",
    "Hilbert 1891; space-filling curve orderings")
MESHREUSE_ORDERING(OrderRdrFrontier, "rdr-frontier", false, false, nullptr,
                   "Algorithm 2, but a dead-ended chain restarts from the worst placed, "
                   "unprocessed vertex (the frontier), the global quality order only when none",
                   "Aupy, Park, Raghavan, Algorithm 2, restart rule changed")
MESHREUSE_ORDERING(OrderRdrWave, "rdr-wave", false, false, nullptr,
                   "a wavefront: BFS from the worst interior vertex, unplaced neighbours "
                   "enqueued by increasing quality; the next wave from the worst unplaced one",
                   "BFS with the paper's quality order as tie-break")
MESHREUSE_ORDERING(
    OrderMorton, "morton", false, false, nullptr,
    "vertices sorted along a Z-order (Morton) curve over a 2^16 x 2^16 grid of the bounding box",
    "Morton 1966")
MESHREUSE_ORDERING(OrderMetis, "metis", kOptionalArgument, true, orderings::CheckMetisPartBytes,
                   "METIS k-way parts sized to a cache (metis:BYTES, default 256K = L2), parts "
                   "by BFS over the part graph, BFS inside each part; seeded",
                   "Karypis and Kumar 1998 (METIS_PartGraphKway)")
MESHREUSE_ORDERING(OrderMetisWave, "metis-wave", kOptionalArgument, true,
                   orderings::CheckMetisWaveBytes,
                   "metis's parts and part order (metis-wave:BYTES, default 256K), each part by a "
                   "wavefront from its vertices next to the parts placed before it; seeded",
                   "METIS_PartGraphKway; a multi-source BFS continuing the wave")
MESHREUSE_ORDERING(OrderGridWave, "grid-wave", kOptionalArgument, false,
                   orderings::CheckGridWaveBytes,
                   "metis-wave's layout on the cells of a uniform grid holding about BYTES each "
                   "(grid-wave:BYTES, default 256K): parts by BFS over the cell graph, each by a "
                   "wavefront from its vertices next to the cells placed before it",
                   "a multi-source BFS continuing the wave through grid cells")
MESHREUSE_ORDERING(OrderWaveBlocks, "wave-blocks", kOptionalArgument, false,
                   orderings::CheckWaveBlockBytes,
                   "BFS levels grouped into bands of up to BAND bytes, each cut along the front "
                   "into blocks of about BLOCK bytes, each block by a local BFS "
                   "(wave-blocks:BLOCK[/BAND], default 32K/128K: L1, half the paper's L2)",
                   "BFS (Strout and Hovland 2004) blocked for L1 inside an L2-sized wavefront")
MESHREUSE_ORDERING(OrderNd, "nd", false, true, nullptr,
                   "METIS nested dissection (separators last, recursively); seeded",
                   "Karypis and Kumar 1998 (METIS_NodeND); George 1973")
MESHREUSE_ORDERING(OrderFile, "file", true, false, nullptr,
                   "file:PATH, a user's permutation: one 0-based vertex id per line, in new order",
                   "")
