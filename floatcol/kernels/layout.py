"""Layouts of the flat arrays that cross the Python/kernel boundary."""

# View parameter vector ``vp`` (float64), built by view.View.params().
VP_ORTHO = 0      # 1.0 orthographic, 0.0 perspective
VP_CA = 1         # cos(alpha)
VP_SA = 2         # sin(alpha)
VP_CB = 3         # cos(beta)
VP_SB = 4         # sin(beta)
VP_D1 = 5         # viewpoint-to-screen distance (ERRATA 1)
VP_D3 = 6         # viewpoint-to-origin distance, d1 + d2
VP_SCALE = 7      # pixels per unit on the screen plane (the paper's Ratio)
VP_W = 8          # image width in pixels
VP_H = 9          # image height in pixels
VP_CU = 10        # world point at the screen origin: u
VP_CV = 11        # ... v
VP_CW = 12        # ... w
VP_UA = 13        # domain u in [UA, UB], v in [VA, VB]
VP_UB = 14
VP_VA = 15
VP_VB = 16
VP_WLO = 17       # estimated range of w (perspective pre-check only)
VP_WHI = 18
VP_T0 = 19        # first sampling plane t = T0 (relative to the centre)
VP_T1 = 20        # last sampling plane
VP_DT = 21        # distance between sampling planes
VP_LX = 22        # unit vector toward a directional light, screen coordinates;
VP_LY = 23        # all zero = light at the viewpoint (the reference model)
VP_LZ = 24
VP_FLO = 25       # min and max of f on the fitting grid (where perspective samples
VP_FHI = 26       # search for the surface when Newton fails)
VP_PAPER = 27     # 1.0: perspective samples at the paper's eq. (9) point, off Pi
# Artifact corrections (Gordon section 5, App. A.2 Problem() / Problem_Correction())
VP_FIX_RIDGE = 28  # what corrects a ridge: FIX_NONE, FIX_SPLINE, FIX_SUPER, FIX_ADAPTIVE
VP_FIX_SHADE = 29  # what corrects an intensity jump or a bump: FIX_NONE/SUPER/ADAPTIVE
VP_DETECT = 30    # bit mask of DETECT_* tests
VP_JUMP = 31      # intensity-jump threshold (the paper: 1/16 of the maximal intensity)
VP_RATE = 32      # supersampling rate (the paper: 16); adaptive: the finest subdivision
VP_SPLINE_TOL = 33  # iterate the spline while |V.N| at its extremum exceeds this; 0: once
VP_AA = 34        # 1.0: coverage antialiasing along columns (section 6.4), into ebuf
VP_XOFF = 35      # sub-column offset in pixels (antialiasing across columns)
VP_ADAPT = 36     # 1.0: locally adaptive planes (section 6.3)
VP_QNEAR = 37     # perspective: the nearest depth z + d3, where the step is a pixel
VP_BATCH = 38     # 1.0: the uniform planes are evaluated in batches by fb (SIMD code)
VP_INV_D1 = 39    # 1 / d1 (perspective; 0 in orthographic)
# The hole map (perspective, a surface with holes; view.hole_map): n x n cells over
# the box u in [U0, U0 + n / SU], v in [V0, V0 + n / SV], where f may be finite or is
# NaN all around (as far as a grid saw), stored after the vector as the summed-area
# table of the former: vp[VP_SIZE + i * (n + 1) + k] = how many of the cells below row
# i (along v) and left of column k (along u) may hold finite values (sample.py's
# finite_cells; the fallback scan of a perspective sample skips f where none).
VP_HOLE_N = 40    # n; 0: no map
VP_HOLE_U0 = 41
VP_HOLE_V0 = 42
VP_HOLE_SU = 43   # cells per unit of u
VP_HOLE_SV = 44   # ... of v
VP_CLIP = 45      # 1.0: a perspective column skips the planes it surely misses
                  # (column.py's _pass_planes; 0.0 only to test that it changes nothing)
VP_KEEP_TOP = 46  # 1.0: an antialiased run keeps its top pixel's coverage in its state
                  # until the next span (column.py's _fill; 0.0 only to test that it
                  # changes nothing)
VP_FOLD = 47      # 1.0: a perspective column whose curve folds back in t is traced
                  # (fold.py); 0.0 for the paper's placement, and where f's partials
                  # are central differences (render), which tilt a normal at a jump of
                  # f as a fold would
VP_PASS_HIDDEN = 48  # 1.0: a height field's span that surely lies inside the floating
                  # interval is not cut at its cell edges (column.py's _hidden_cells;
                  # 0.0 only to test that it changes nothing)
VP_WORG = 49      # the G-buffer's w is stored from this (layout's G_W): 0, or the
                  # view's centre where f lies far from 0 against its spread (View)
VP_SIZE = 50

FIX_NONE = 0
FIX_SPLINE = 1
FIX_SUPER = 2
FIX_ADAPTIVE = 3

DETECT_RIDGE = 1      # V.N_Pi changes sign between successive samples
DETECT_JUMP = 2       # |I1 - I0| above VP_JUMP
DETECT_BUMP = 4       # (L x N_Pi)0 . (L x N_Pi)1 < 0  (section 5.3)
DETECT_WALL = 8       # a discontinuity: a screen-y jump the slopes cannot explain (end of 5)

# Surface kinds
SURF_FUNCTION = 0
SURF_HEIGHTFIELD = 1

# A surface's parameter vector ``hfp`` (float64, Surface.hfp). A function surface
# reads its time t from HFP_T; a height field its extent from HFP_T to 3. Every
# kernel call of a function surface's f is c f(u iu, v iv, t), with its partials
# c iu f_u and c iv f_v: the box scaling of render's ``aspect`` (Surface.scaled;
# 1, 1, 1 for true proportions, which leaves every value as it was).
HFP_T = 0
HFP_IU = 4        # iu: u of the picture's box -> u of f
HFP_IV = 5        # iv: likewise v
HFP_CW = 6        # c: w of f -> w of the box
HFP_SIZE = 7

# The column pass's buffers are tiled: tiles of TILE neighbouring columns, each tile's
# rows in order, so that a column's pixels lie TILE pixels apart (one thread renders a
# tile's columns one after another, through the same cache lines and pages) and the
# finishing pass reads a tile's row as one run of memory.
TILE = 4
# The column kernel's threads take GROUP_TILES tiles at a time, their columns in order:
# a column's perspective Newton iterations start from the ones before it in its group
# (column.py guesses_for), so the picture is the same for any number of threads, and a
# poster's bands start at whole groups (cluster.py)
GROUP_TILES = 4
GROUP = TILE * GROUP_TILES

# G-buffer channels, gbuf shape (n_tiles, H, TILE, G_SIZE) float32, rows counted from
# the BOTTOM: column c is gbuf[c // TILE, :, c % TILE]. Written only where a surface
# is seen (ebuf's E_SEEN plane says where): it is never cleared, so a render moves
# only the memory of the pixels it paints.
G_DEPTH = 0       # screen z of the seen point (larger = farther)
G_U = 1           # u and v of the seen point from the view's centre (vp's VP_CU, VP_CV),
G_V = 2           # as G_T: float32 keeps its 24 bits for the picture's own extent however
                  # far from 0 its coordinates lie (a DEM in UTM metres: 0.5 m steps at
                  # 4e6 absolute); its readers add the centre back in float64
G_W = 3           # w less vp's VP_WORG (0 unless f lies far from 0 against its spread:
                  # 1e6 + sin u cos v in float32 came in 32 colours), its readers add
                  # it back in float64
G_NX = 4          # unit upper-side normal in screen coordinates, eq. (11)
G_NY = 5
G_NZ = 6
G_I = 7           # lambert intensity interpolated between samples (iis)
G_T = 8           # t of the seen point (relative to the centre)
G_SIZE = 9

# Per-sample attribute vector (column.py, correct.py)
A_Y = 0      # screen row from the bottom (float)
A_Z = 1      # screen depth
A_U = 2
A_V = 3
A_W = 4
A_NX = 5
A_NY = 6
A_NZ = 7
A_I = 8
A_T = 9
A_VN = 10    # V.N / |V| (correct.probe; filled only when corrections are on)
A_BUMP = 11  # n_Pi . (L x N)
A_SLOPE = 12  # dY/dt in pixels per unit of t along the curve in Pi
A_SIZE = 13

# Edge buffer ebuf (n_tiles, E_SIZE, H, TILE) float32, column c at
# ebuf[c // TILE, :, :, c % TILE]: which side is seen at each pixel's centre (E_SEEN,
# always), and for the coverage antialiasing (section 6.4) how much of each pixel the
# surface at its centre covers, and a second surface that shares the pixel (the one
# reappearing above a ridge, or beside a silhouette). Channel-major per tile. A column
# clears only its E_SEEN row: the coverage planes hold a pixel's values only where
# E_SEEN carries E_FLAG (a pixel that a surface covers in part, or that an edge surface
# shares; kernels/coverage.py); elsewhere they are implied (E_COV0 1 where a surface is
# seen, else 0; E_COV 0) and neither written nor read, so most of the buffer's memory
# is never touched.
E_SEEN = 0        # +1 upper side, -1 lower side at the centre; 0 nothing (no G-buffer);
                  # + E_FLAG where the coverage planes hold the pixel's values
E_COV0 = 1        # coverage of the pixel by the G-buffer's surface (its centre's)
E_COV = 2         # coverage by the edge surface (0: none); the edge surface's
E_NX = 3          # unit normal, w, intensity, side and depth
E_NY = 4
E_NZ = 5
E_W = 6           # (less VP_WORG, as G_W)
E_I = 7
E_SIDE = 8
E_DEPTH = 9
E_U = 10          # ... and its u, v (a texture's colour, passes/colour.py; from the
                  # view's centre, as G_U)
E_V = 11
E_SIZE = 12
E_FLAG = 8.0      # added to E_SEEN where E_COV0 and E_COV are kept

# The material vector mp (float64), one per layer (material.py Material.table): what
# the finishing, sub-column and layer kernels light and colour a surface with. A new
# material field is a slot here, filled in Material.table and read by its kernel.
M_ALPHA = 0       # opacity
M_INTERP = 1      # shade.py's INTERP_*
M_AMBIENT = 2
M_SPECULAR = 3
M_SHININESS = 4
M_WLO = 5         # the colour table's heights: w_lo and w_hi - w_lo (the lut's span)
M_SPAN = 6
M_LOWER = 7       # the lower side's colour: r, g, b in slots 7-9
M_SIZE = 10

# Sample status
S_OK = 0
S_HOLE = 1        # f is NaN, infinite or complex there
S_OUTSIDE = 2     # outside the domain rectangle
S_BEHIND = 3      # in front of the screen plane (perspective, ERRATA 1)
