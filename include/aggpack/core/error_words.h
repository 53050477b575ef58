#pragma once
// The sentences of aggpack's error messages, each declared once with its English words, so that a
// front end can word an error in its own language from the error's parts instead of parsing its
// text (aggpack-gui's catalogues have one entry per sentence; a missing one fails its test). An
// error's Wording is a sentence and the values ("{}" in order) that fill it.
//
// Three uses: the allowed part of InvalidInput, LimitExceeded and ConfigError ("finite and >= 0",
// ">= {} = {}"), the whole message of IoError and FormatError ("cannot read {}: no such
// file"), and a configuration key's rule beside its range and default words (config/schema.h
// Key::note and Key::default_text: the panel's tooltips and field errors). kText is a free-form
// English text (its one value): errors not yet given a sentence.
// Values that name an options field ("shape.edge_length_ratio") are renamed to configuration
// keys by with_key_names (config/schema.h); so a field name is a value, never a sentence's word.
// A value may be a sentence of its own (a damaged file's reason, the first skipped mesh file's):
// the error marks it (Error::worded_values, core/error.h), and its English is the value's text.
//
// No include guard on the list: AGGPACK_ERROR_SENTENCES(X) calls X(Name, "english") per sentence.

#include <string>
#include <vector>

// clang-format off
#define AGGPACK_ERROR_SENTENCES(X)                                                              \
  X(Text, "{}")                                                                                 \
  /* allowed values: rules of one value */                                                      \
  X(FiniteAtLeastZero, "finite and >= 0")                                                       \
  X(FinitePositive, "finite and > 0")                                                           \
  X(FiniteAtLeastZeroRelative, "finite and >= 0 (0 = relative, use {})")                       \
  /* rules between keys */                                                                      \
  X(AtLeastKey, ">= {} = {}")                                                                   \
  X(AtLeastKeyMetres, ">= {} = {} m")                                                           \
  X(AboveKey, "> {} = {}")                                                                      \
  X(AboveKeyMetres, "> {} = {} m")                                                              \
  X(EdgeLengthLattice,                                                                          \
    "> 0 with packer.kind = lattice; 0 = relative edge length exists only for the random "      \
    "packer")                                                                                   \
  X(SieveNeeded,                                                                                \
    "grading.kind = \"sieve\" needs grading.sieve = [[size_m, percent_passing], ...] (at "     \
    "least 2 rows)")                                                                            \
  X(BelowHalfExtent, "< half the smallest container extent ({} m)")                             \
  X(PeriodicRoom,                                                                               \
    "periodic extents > 2 x the largest enclosing radius + gap = {} m ({} = {} m)")            \
  X(PeriodicUnsupported, "{} ({} does not take periodic containers yet)")                      \
  X(LatticeSpacing, "0 (= 2 radius + gap) or > radius + gap")                                   \
  X(LatticeSpacingAbove, "0 (= 2 radius + gap) or > radius + gap = {}")                         \
  X(RadiusFitsContainer,                                                                        \
    "small enough that a particle of diameter 2 R fits in the container (minus wall gaps)")     \
  X(RadiusOneSite, "small enough that at least one site fits in the container")                 \
  X(LatticeSites, "a radius giving at most 10^8 lattice sites (gives {})")                      \
  X(DensifyGapAtMostFill, "[0, {}], at most the fill's gap")                                    \
  X(FillRandomWhenFixed,                                                                        \
    "random with densify.mode = fixed and densify.target_fraction = {} > 0 (to compress a "     \
    "lattice packing: aggpack pack it, then aggpack densify it; or set "                        \
    "densify.target_fraction = 0)")                                                             \
  X(CountUnsetWhenFixed,                                                                        \
    "unset with densify.mode = fixed and densify.target_fraction = {} > 0 (use "                \
    "packer.target_fraction: the fill's fraction)")                                             \
  X(FillBelowTarget,                                                                            \
    "(0, {}), below densify.target_fraction: the fill runs in the container enlarged by "       \
    "(densify.target_fraction / packer.target_fraction)^(1/3) and is compressed into the "      \
    "given one")                                                                                \
  X(SieveRows, "at least 2 rows (size, percent passing)")                                       \
  X(SieveSizesIncrease, "> previous size {} (sizes strictly increasing)")                       \
  X(SievePassingRises, ">= previous {} (percent passing non-decreasing)")                       \
  X(SieveLastPassesAll, "100 (the largest sieve passes everything)")                            \
  X(SieveFirstRetains, "< 100 (some material must be retained on the smallest sieve)")          \
  X(LibraryNeedsRelativeLength,                                                                 \
    "0 when {} > 0 (a library rescales shapes, so L must be relative: set {} = 0 and use {})")  \
  X(LibrarySizeWithFiles, "0 when {} is given (shapes come from the files)")                   \
  X(VerticesNeeded, "a value needing at most {} = {} vertices (needs about {})")                \
  X(EdgeLengthForVertexCap,                                                                     \
    ">= about {} m for radius {} m: may need up to {} vertices, max_vertices is {}")            \
  X(VertexCapReached,                                                                           \
    "a larger cap or a longer edge_length (growth still had edges of {} m > L = {} m)")         \
  X(CountAtMostLibrary, "at most the library's {} shapes when {} = true")                       \
  X(LibraryShapesForSites,                                                                      \
    "at most the library's {} shapes for the lattice's {} sites (a smaller container, or a "    \
    "larger {})")                                                                               \
  X(LibraryReachesFraction,                                                                     \
    "a library whose {} shapes, each used once, reach {} = {} (they reach {})")                 \
  X(FractionReachable, "a target reachable with 10^8 particles")                                \
  X(FractionParticles, "a target needing at most 10^8 particles (needs more than {})")         \
  X(GradingFitsInterior, "particles that fit in the container's interior ({} m across)")       \
  X(SmallestSize, "smallest size {} m")                                                         \
  /* configuration keys: the rule beside a range (Key::note), a default's words */              \
  X(AtLeast, ">= {}")                                                                           \
  X(Below, "< {}")                                                                              \
  X(Above, "> {}")                                                                              \
  X(ZeroOrAtLeast, "0 or >= {}")                                                                \
  X(ZeroOnlyWith, "0 only with {} = {}")                                                        \
  X(BelowHalfSmallestExtent, "< half the smallest extent")                                      \
  X(SieveTableRule,                                                                             \
    ">= 2 rows [size, percent passing]; sizes increasing, percents [0, 100] non-decreasing, "   \
    "last 100")                                                                                 \
  X(NonEmptyPath, "a non-empty path")                                                           \
  X(NonEmptyPathList, "a non-empty path or an array of them")                                   \
  X(DefaultNone, "(none)")                                                                      \
  X(DefaultUnset, "(unset)")                                                                    \
  /* whole messages: reading a file */                                                          \
  X(ReadNoSuchFile, "cannot read {}: no such file")                                             \
  X(ReadFolder, "cannot read {}: it is a folder")                                               \
  X(ReadPermission, "cannot read {}: permission denied")                                        \
  X(ReadSystemError, "cannot read {}: {}")                                                      \
  X(NotHdf5, "{}: not an HDF5 file (expected an aggpack packing, format {})")                   \
  X(Hdf5Unreadable, "{}: cannot open as HDF5 ({}; the file is truncated or corrupted)")         \
  X(NoFormatName, "{}: not an aggpack packing (no format_name attribute; expected {})")         \
  X(WrongFormatName, "{}: /format_name = {}: not an aggpack packing (expected \"{}\")")         \
  X(WrongFormatVersion,                                                                         \
    "{}: /format_version = {}: format version {} is not supported (this aggpack {} reads "      \
    "version {})")                                                                              \
  X(FieldCorrupt, "{}: {}: {} ({}; the file is truncated or corrupted)")                        \
  X(FieldInvalid, "{}: {}: {}")                                                                 \
  /* a damaged native packing file: the field and reason of FieldInvalid and FieldCorrupt */    \
  X(NativeShapeRows, "{} (shape {}, rows {}-{})")                                               \
  X(NativeMissingGroup, "missing group")                                                        \
  X(NativeMissingAttribute, "missing attribute")                                                \
  X(NativeMissingDataset, "missing dataset")                                                    \
  X(NativeStoredAsNotString, "stored as {}, expected a string")                                 \
  X(NativeStoredAsNotInteger, "stored as {}, expected an integer")                              \
  X(NativeStoredAs, "stored as {}, expected {}")                                                \
  X(NativeTypeString, "a string")                                                               \
  X(NativeTypeCompound, "a compound type")                                                      \
  X(NativeTypeArray, "an array type")                                                           \
  X(NativeTypeEnum, "an enum")                                                                  \
  X(NativeTypeNonNumeric, "a non-numeric type")                                                 \
  X(NativeTypeUnknown, "an unknown type")                                                       \
  X(NativeNotScalarString, "not a single string (the dataspace is not scalar)")                 \
  X(NativeVariableString,                                                                       \
    "cannot read the variable-length string (corrupted global heap?): HDF5 {}")                 \
  X(NativeStringBytes, "declares a {}-byte string in a {}-byte file")                           \
  X(NativeNulByte,                                                                              \
    "contains a NUL byte at position {} followed by more text; allowed: text without NUL "      \
    "bytes")                                                                                    \
  X(NativeNotSingleNumber, "not a single number")                                               \
  X(NativeNotFinite, "not finite")                                                              \
  X(NativeNegative, "negative, expected >= 0")                                                  \
  X(NativeRank, "rank {}, expected {}")                                                         \
  X(NativeColumns, "{} columns, expected {}")                                                   \
  X(NativeDeclaresValues, "declares {} {} values in a {}-byte file")                            \
  X(NativeDeclaresStored,                                                                       \
    "declares {} {} values ({} bytes) but {} bytes are stored in a {}-byte file")               \
  X(NativeDeclaresStoredCompressed,                                                             \
    "declares {} {} values ({} bytes) but {} bytes are stored compressed in a {}-byte file")    \
  X(NativeTooLarge, "too large to load ({} values)")                                            \
  X(NativeStoredOutside, "stored outside the file (external or virtual dataset)")               \
  X(NativeUnknownKind, "unknown kind (expected {})")                                            \
  X(NativePeriodicWord, "not a box's periodic axes (expected {})")                              \
  X(NativeOffsetsEmpty, "empty (it holds S + 1 values)")                                        \
  X(NativeValuesButHas, "{} values, but {} has {}")                                             \
  X(NativeRowsButHas, "{} rows, but {} has {}")                                                 \
  X(NativeOffsetsRun, "runs from {} to {}, expected 0 to {} (the rows of {})")                  \
  X(NativeOffsetsDecrease, "offsets must not decrease")                                         \
  X(NativeNotPolyhedron, "not a polyhedron: {}")                                                \
  /* a polyhedron's own refusal (geom/convex_polyhedron.cpp), and a refused value quoted */   \
  X(PolyhedronVertexCount, "{} vertices")                                                       \
  X(PolyhedronTriangleCount, "{} triangles")                                                    \
  X(PolyhedronVertexIndex, "vertex index {}")                                                   \
  X(PolyhedronEdge, "edge {}-{}")                                                               \
  X(PolyhedronEdgeTwice, "each edge shared by exactly two oppositely oriented triangles")       \
  X(InvalidValue, "invalid {} = {} (allowed: {})")                                              \
  X(LimitValue, "limit exceeded for {} = {} (allowed: {})")                                     \
  X(Hdf5LookUp, "cannot look it up")                                                            \
  X(Hdf5OpenGroup, "cannot open the group")                                                     \
  X(Hdf5OpenAttribute, "cannot open the attribute")                                             \
  X(Hdf5ReadAttribute, "cannot read the attribute")                                             \
  X(Hdf5AttributeType, "cannot read the attribute's type")                                      \
  X(Hdf5OpenDataset, "cannot open the dataset")                                                 \
  X(Hdf5DatasetType, "cannot read the dataset's type")                                          \
  X(Hdf5DatasetSize, "cannot read the dataset's size")                                          \
  X(Hdf5ReadDataset, "cannot read the dataset")                                                 \
  X(Hdf5DatasetProperties, "cannot read the dataset's properties")                              \
  X(NativeWallGapHalf, "not below half the smallest container extent; allowed: [0, {}) m")      \
  X(NativeTooFewParts,                                                                          \
    "{} vertices and {} triangles, a closed polyhedron needs at least 4 of each")               \
  X(NativeVertexMagnitude, "vertex {} has a coordinate of magnitude {}, outside {} m")          \
  X(NativeRepeatsVertex, "triangle {} repeats a vertex ({}, {}, {}): degenerate")               \
  X(NativeEdgeOpen, "edge {}-{} belongs to only triangle {}: the surface is not closed")        \
  X(NativeEdgeShared,                                                                           \
    "edge {}-{} is shared by {} triangles: not a 2-manifold (each edge needs exactly 2)")       \
  X(NativeEdgeSameWay,                                                                          \
    "edge {}-{} runs the same way in triangles {} and {}: not consistently oriented (a "        \
    "flipped triangle)")                                                                        \
  X(NativeUnusedVertex, "vertex {} is in no triangle")                                          \
  X(NativeEuler, "V - E + F = {}, expected 2: not one closed surface without holes")            \
  X(NativeCollapsed, "the shape's extent is {} m, below {} m (collapsed)")                      \
  X(NativeZeroArea, "triangle {} has zero area (degenerate)")                                   \
  X(NativeInsideOut,                                                                            \
    "volume {} m^3 is not positive: the triangles turn clockwise seen from outside (inside "    \
    "out, e.g. mirrored)")                                                                      \
  X(NativeNotConvex,                                                                            \
    "vertex {} lies {} m outside the plane of triangle {}: not convex (tolerance {} m)")        \
  X(NativeNoSuchShape, "no such shape (the file has {})")                                       \
  X(NativeOutsideMetres, "outside {} m")                                                        \
  X(NativeOutside, "outside {}")                                                                \
  X(NativeNotUnitQuaternion, "|q|^2 = {}, not a unit quaternion (tolerance {})")                \
  X(NativeScaleSize,                                                                            \
    "makes shape {} {} m across with coordinates up to {} m; allowed: at least {} m "           \
    "across, coordinates up to {} m")                                                           \
  X(NativeContainerNeeds, "outside {} m (a {} needs it > 0)")                                   \
  /* phrases: a value that is one of these words is worded too (library_words.cpp) */           \
  X(PhraseDirectory, "directory")                                                               \
  X(PhraseCharacterDevice, "character device")                                                  \
  X(PhraseBlockDevice, "block device")                                                          \
  X(PhraseFifo, "FIFO")                                                                         \
  X(PhraseSocket, "socket")                                                                     \
  X(PhraseSymbolicLink, "symbolic link")                                                        \
  X(PhraseSpecialFile, "special file")                                                          \
  X(PhrasePhysicalMemory, "physical memory")                                                    \
  X(PhraseCgroupMemory, "the cgroup memory limit")                                              \
  X(PhraseAddressSpace, "the address-space limit (ulimit -v)")                                  \
  X(PhraseUseLargerParticles, "use larger particles or a smaller container")                    \
  X(PhraseUseLibrarySize, "use shape.library_size, larger particles or a smaller container")    \
  X(PhraseUseLargerRadius, "use a larger radius or edge length, or a smaller container")        \
  X(PhraseNonFiniteCoordinate, "non-finite coordinate")                                         \
  X(PhraseFiniteNumbers, "finite numbers")                                                      \
  /* whole messages: writing a file */                                                          \
  X(OutputPathEmpty, "output path is empty")                                                    \
  X(WriteNameTooLong, "cannot write {}: file name too long (a name of {} bytes, at most {})")   \
  X(WritePathTooLong, "cannot write {}: file name too long ({} bytes, at most {})")             \
  X(WriteFileExists, "cannot write {}: file exists (use {} to replace it)")                     \
  X(ReplaceNotRegular, "refusing to replace {}: not a regular file ({})")                       \
  X(ReplaceMissingLink, "refusing to replace {}: symbolic link to a missing file")              \
  X(ReplaceLinkNotRegular, "refusing to replace {}: not a regular file (symbolic link to a {})")\
  X(ResolveLink, "cannot resolve symbolic link {}: {}")                                         \
  X(WriteNoFolder, "cannot write {}: folder {} does not exist")                                 \
  X(WriteNoPermission, "cannot write {}: no permission to write in folder {}")                  \
  X(WriteCannotCreate, "cannot write {}: cannot create a file in folder {} ({})")               \
  X(WriteCannotCreateTemporary,                                                                 \
    "cannot write {}: cannot create a temporary file in folder {} ({})")                        \
  X(WriteChanged, "cannot write {}: it changed while it was being written")                     \
  X(RenameFailed, "cannot rename {} to {}: {}")                                                 \
  X(WriteDiskFull, "cannot write {}: disk full")                                                \
  X(WriteQuota, "cannot write {}: disk quota exceeded")                                         \
  X(WriteTooLarge, "cannot write {}: file too large (file size limit)")                         \
  X(WriteError, "cannot write {}: write error")                                                 \
  X(WriteSystemError, "cannot write {}: {}")                                                    \
  X(WriteStreamError, "write error (disk full or file size limit?)")                            \
  X(WriteHdf5Failed, "cannot write {}: {} ({})")                                                \
  X(TemporaryFolder, "cannot create a temporary folder beside {}: {}")                          \
  X(ReplaceByFolder, "refusing to replace {} by a folder: it is not a folder")                  \
  X(ReplaceLinkByFolder,                                                                        \
    "refusing to replace {} by a folder: it is not a folder (symbolic link)")                   \
  X(FolderExists, "cannot write {}: it exists (use {} to replace it)")                          \
  X(ReplaceFailed, "cannot replace {}: {}")                                                     \
  X(RenameInto, "cannot rename into {}: {}")                                                    \
  X(PngEncode, "cannot encode PNG {}")                                                          \
  /* limits of a run (pack/resources.cpp) and of the packers */                                 \
  X(SizesFrom, "sizes from {} m")                                                               \
  X(PositiveVolume, "sizes whose grown particles have a positive, finite volume ({} m^3 here)") \
  X(RadiusPositiveVolume,                                                                       \
    "a radius whose grown particles have a positive, finite volume ({} m^3 here)")              \
  X(ContainerCapacity,                                                                          \
    "at most ~{} particles of this grading and shape: the container ({} m^3) holds at most a "  \
    "solid fraction of {}, and {} particles of ~{} m^3 each would need {} times its volume")    \
  X(MemoryRunSet,                                                                               \
    "a run that fits in memory: ~{} particles at ~{} each need ~{}, more than the memory "      \
    "limit of {} ({}={}); {}")                                                                  \
  X(MemoryRunShare,                                                                             \
    "a run that fits in memory: ~{} particles at ~{} each need ~{}, more than the memory "      \
    "limit of {} (80% of {} {}; {} overrides it); {}")                                          \
  X(LibraryHeadroom,                                                                            \
    "at most {} ({} x the ~{} particles this target needs, at least {}): every library shape "  \
    "is grown before placement, so the run would need ~{} and ~{} s, mostly for shapes it "     \
    "never uses")                                                                               \
  X(MemorySize, "a size in bytes, optionally with K, M, G or T (e.g. 8G)")                      \
  X(GrewBadShape,                                                                               \
    "random packer: draw {} (size {} m) grew a shape of volume {} m^3; stopped (sizes out of "  \
    "range?)")                                                                                  \
  /* particle.library: the mesh files */                                                        \
  X(LibraryTooManyFiles, "at most 10^6 mesh files")                                             \
  X(LibraryList, "cannot list {}: {}")                                                          \
  X(LibraryFolderEmpty, "a folder holding .stl, .obj or .ply files (it holds none)")            \
  X(LibraryFileExtension, "a folder, or a file ending in .stl, .obj or .ply")                   \
  X(LibraryPathMissing, "an existing folder, or a .stl, .obj or .ply file")                     \
  X(LibraryPathEmpty, "a folder or a .stl, .obj or .ply file")                                  \
  X(LibraryNamedTwice, "paths naming each mesh file once ({} is named twice)")                  \
  X(LibraryAllSkipped, "at least one usable mesh (all {} were skipped; first: {})")             \
  X(MeshOutOfMemory, "{}: out of memory while reading it")                                      \
  X(MeshProblem, "{}: {}")                                                                      \
  X(ReadNotRegular, "cannot read {}: not a regular file")                                       \
  X(OpenFailed, "cannot open {}")                                                               \
  X(ReadChanged, "cannot read {}: it changed while being read")                                 \
  X(FileSize, "{} size")                                                                        \
  X(Bytes, "{} bytes")                                                                          \
  X(AtMostBytes, "at most {} bytes")                                                            \
  X(UnknownMeshFormat, "{}: unknown mesh format")                                               \
  /* the mesomodel (mesh/mesomodel.cpp) */                                                      \
  X(ParticlesPair, "particles {} and {}")                                                       \
  X(ParticleNumber, "particle {}")                                                              \
  X(ApartItzMeet, "{} apart, their ITZ layers ({} thick) meet ({} such pairs)")                 \
  X(ApartTouch, "{} apart (aggregates must not touch) ({} such pairs)")                         \
  X(PackWithGapItz,                                                                             \
    "pack with {} >= {} (2 x the layers' farthest corner reach, {} x the ITZ thickness, plus "  \
    "the mesher's margin)")                                                                     \
  X(PackWithGap, "pack with {} >= {} (the mesher's margin)")                                    \
  X(FromAWall, "{} from a wall")                                                                \
  X(WallClearance,                                                                              \
    "> {} (pack with {} > 0, e.g. 1e-4 m: the mesomodel's aggregates must not touch the "       \
    "walls)")                                                                                   \
  X(MesomodelMesh, "mesomodel mesh")                                                            \
  X(TetGenMovedPoint, "TetGen moved an input point of particle {}")                             \
  X(ComplexTetGenKeeps, "a complex TetGen keeps")                                               \
  X(PeriodicNoItz,                                                                                \
    "0 with container.periodic (a periodic box has no ITZ layer "                                 \
    "or cohesive ITZ yet)")                                                                       \
  X(PeriodicLinear, "linear elements (the periodic ties join the corner nodes only)")             \
  X(FromAPeriodicFace, "{} m from a periodic face")                                               \
  X(PeriodicFaceClearance,                                                                        \
    "> {} m or across it (a vertex this close leaves a sliver: "                                  \
    "pack with another seed)")                                                                    \
  X(PeriodicNodeNoPartner, "node {} on a periodic face has no partner")                           \
  X(APeriodicMesh, "a periodic mesh")                                                             \
  X(PeriodicPointNoPartner, "a point on a periodic face without a partner on the opposite face")  \
  X(VoxelsTilePeriodic,                                                                           \
    "a count that cuts every periodic extent into whole voxels "                                  \
    "(the image of a periodic box must tile)")                                                  \
  X(DatStepSet, "step {}, set {}")                                                                \
  X(PeriodicDatTotals, "the totals of the periodic deck's six steps")                             \
  X(ItzFolds, "an ITZ layer that folds at particle {} (its prisms overlap by {} of its volume)")\
  X(ThinnerItz, "a thinner ITZ for this packing's sharpest corners")                            \
  X(DegreesInMesh, "{} degrees in the mesh")                                                    \
  X(MinDihedral,                                                                                \
    ">= {} degrees (lower the bound, or raise the ITZ thickness or the gap: thin shells make "  \
    "flat tetrahedra)")                                                                         \
  X(InTheMesh, "{} in the mesh")                                                                \
  X(AtMost, "<= {}")                                                                            \
  X(TetGenCanMesh,                                                                              \
    "a packing TetGen can mesh (a larger {} or {} helps with nearly touching surfaces)")        \
  X(TetGenWorker, "TetGen {}")                                                                  \
  X(TetGenErrorCode, "TetGen error code {}")                                                    \
  X(TetGenFacetsIntersect, "TetGen error code {} (facets intersect)")                           \
  X(TetGenOutOfMemory, "TetGen error code {} (out of memory)")                                  \
  X(TetGenNoTetrahedra, "TetGen made no tetrahedra")                                            \
  X(WorkerMalformed, "malformed result from the worker process")                                \
  X(TetGenIntersecting, "{}; TetGen finds these surfaces intersecting: {}")                     \
  X(SurfaceWall, "wall {}")                                                                     \
  X(SurfaceAggregate, "aggregate {}")                                                           \
  X(SurfaceItzLayer, "ITZ layer of particle {}")                                                \
  X(SurfaceList, "{}, {}")                                                                      \
  /* solver decks and export limits */                                                          \
  X(PoissonRange, "(-1, 0.5)")                                                                  \
  X(MaterialName, "a letter, then letters, digits or _, at most 32 characters")                 \
  X(DeckField, "deck")                                                                          \
  X(EmptyPacking, "an empty packing")                                                           \
  X(AtLeastOneParticle, "at least one particle")                                                \
  X(BehindBaffle, ">= {} m (the particles' largest x: they start behind the baffle)")           \
  X(BeyondBaffle, "> {} m (from the trough's start at x = {} m to beyond the baffle)")          \
  X(BinaryStlTriangles, "binary STL triangles")                                                 \
  X(BinaryStlLimit, "<= 2^32-1 (use ASCII STL or {})")                                          \
  X(ParticleCount, "particle count")                                                            \
  X(OpenGlTexels, "<= {} for this OpenGL driver")                                               \
  /* mesh files (STL, OBJ) */                                                                   \
  X(StlNotStl, "{}: not an STL file (binary size mismatch and no 'solid' header)")              \
  X(StlExpectedFacet, "{}: expected 'facet', found '{}'")                                       \
  X(StlFacetNormal, "{}: malformed facet normal line")                                          \
  X(StlOuterLoop, "{}: expected 'outer loop'")                                                  \
  X(StlVertexLine, "{}: malformed vertex line")                                                 \
  X(StlFacetTruncated, "{}: malformed facet (truncated?)")                                      \
  X(StlNoEnd, "{}: missing 'endsolid' (truncated file)")                                        \
  X(ObjCoordinate, "{}:{}: vertex coordinate '{}' is not a finite number")                      \
  X(ObjFaceIndex, "{}:{}: face index '{}' is not a vertex number")                              \
  X(ObjFaceNoVertex, "{}:{}: face index {} names no vertex ({} read so far)")                   \
  X(ObjFaceSmall, "{}:{}: face with fewer than 3 vertices")                                     \
  X(ObjStatement,                                                                               \
    "{}:{}: unsupported OBJ statement '{}' (a particle is read from v and f lines)")            \
  X(ObjNoFaces, "{}: OBJ file has no faces ('f' lines)")                                        \
  /* mesh files (PLY) */                                                                        \
  X(PlyTruncated, "{}: PLY data ends early (truncated)")                                        \
  X(PlyValue, "{}: PLY value '{}' is not a number")                                             \
  X(PlyNotPly, "{}: not a PLY file (no 'ply' ... 'end_header' header)")                         \
  X(PlyFormatWithoutName, "{}: PLY header line {}: format without a name")                      \
  X(PlyUnknownFormat, "{}: PLY header line {}: unknown format '{}'")                            \
  X(PlyElementLine, "{}: PLY header line {}: expected 'element NAME COUNT'")                    \
  X(PlyPropertyFirst, "{}: PLY header line {}: property before any element")                    \
  X(PlyListTypes, "{}: PLY header line {}: bad list types '{}'")                                \
  X(PlyUnknownType, "{}: PLY header line {}: unknown type '{}'")                                \
  X(PlyPropertyLine,                                                                            \
    "{}: PLY header line {}: expected 'property TYPE NAME' or 'property list COUNT ITEM "       \
    "NAME'")                                                                                    \
  X(PlyUnknownKeyword, "{}: PLY header line {}: unknown keyword '{}'")                          \
  X(PlyNoFormat, "{}: PLY header has no format line")                                           \
  X(PlyElementCount, "{}: PLY element '{}' declares {} entries, more than the file holds")      \
  X(PlyVertexAxes, "{}: PLY vertex element lacks an x, y or z property")                        \
  X(PlyFaceList, "{}: PLY face element has no vertex_indices list")                             \
  X(PlyListCount, "{}: PLY list of {} items in '{}' entry {}")                                  \
  X(PlyFaceIndex, "{}: PLY face {} has index {}")                                               \
  X(PlyFaceSmall, "{}: PLY face {} has fewer than 3 vertices")                                  \
  X(PlyVertexFinite, "{}: PLY vertex {} has a non-finite coordinate")                           \
  X(PlyNeedsElements, "{}: PLY file needs a vertex and a face element")                         \
  X(PlyFaceVertex, "{}: PLY face names vertex {} of {}")                                        \
  /* a mesh that cannot be a particle (geom/triangle_mesh.cpp, shape/shape_library.cpp) */      \
  X(MeshFileSize, "{}: limit exceeded for {} size = {} bytes (allowed: at most {} bytes)")      \
  X(MeshTriangleCount, "{}: mesh has {} triangles (a closed particle needs at least 4)")        \
  X(MeshNonFinite, "{}: mesh has a non-finite vertex coordinate")                               \
  X(MeshTriangleVertex, "{}: mesh triangle {} names vertex {} of {}")                           \
  X(MeshRepeatedVertex, "{}: mesh triangle {} repeats a vertex (zero-area triangle)")           \
  X(MeshZeroArea, "{}: mesh triangle {} has zero area (degenerate)")                            \
  X(MeshOpen, "{}: mesh is open: edge ({}, {}) belongs to triangle {} only (a hole)")           \
  X(MeshEdgeShared, "{}: mesh is non-manifold: edge ({}, {}) is shared by {} triangles")        \
  X(MeshOrientation,                                                                            \
    "{}: mesh is inconsistently oriented: triangles {} and {} run edge ({}, {}) the same "      \
    "way")                                                                                      \
  X(MeshVertexSurfaces,                                                                         \
    "{}: mesh is non-manifold: vertex {} joins two surfaces that touch only there")             \
  X(MeshPieces, "{}: mesh has {} separate pieces (one particle per file)")                      \
  X(MeshNoHull,                                                                                 \
    "{}: mesh has no convex hull: invalid hull = Qhull error {} (allowed: points spanning a "   \
    "volume ({}))")                                                                             \
  X(MeshHullExcess, "{}: its convex hull adds {} % to its volume, above {} = {}")               \
  /* a worker process (core/isolated.cpp), OpenGL (render/renderer_setup.cpp), export ids */    \
  X(WorkerPipe, "cannot create a pipe for a worker process: {}")                                \
  X(WorkerStart, "cannot start a worker process: {}")                                           \
  X(WorkerWait, "cannot wait for worker processes: {}")                                         \
  X(WorkerSignal, "died of signal {} ({})")                                                     \
  X(WorkerExited, "exited with code {}")                                                        \
  X(WorkerStatus, "ended with status {}")                                                       \
  X(WorkerTimedOut, "timed out after {} s")                                                     \
  X(WorkerThrew, "threw: {}")                                                                   \
  X(OpenGlCompile, "OpenGL: shader compilation failed: {}")                                     \
  X(OpenGlLink, "OpenGL: shader link failed: {}")                                               \
  X(OpenGlVersion, "OpenGL: need a 3.3 core context, have {}")                                  \
  X(FormatIds, "{} ids")                                                                        \
  /* internal checks that only a bug reaches */                                                 \
  X(DensifyVerifyFailed, "densify: the final exact verification failed (a bug): {}")            \
  X(VerifyFromWalls, "particle {} is {} m from the walls (wall_gap {} m)")                      \
  X(VerifyApart, "particles {} and {} are {} m apart (gap {} m)")                               \
  X(StartPacking, "start packing")                                                              \
  X(OverlapFreeStart, "an overlap-free packing inside its container (gap {} m)")                \
  X(LibraryLoadedFirst, "a library loaded by the pipeline (pack()) before the packer runs")     \
  X(ShapeVolume, "shape {} volume")                                                             \
  X(ClosedConvexBody, "> 0 (a closed outward convex body)")                                     \
  X(MeshNoHullReason, "mesh has no convex hull: {}")                                            \
  X(BrokenAdjacency, "internal: broken adjacency in aggregate growth")                          \
  X(ParticleVolume, "particle volume")                                                          \
  X(QhullError, "Qhull error {}")                                                               \
  X(PointsSpanVolume, "points spanning a volume ({})")
// clang-format on

namespace aggpack {

/// One sentence of AGGPACK_ERROR_SENTENCES.
enum class Sentence {
#define AGGPACK_SENTENCE_ID(name, english) k##name,
  AGGPACK_ERROR_SENTENCES(AGGPACK_SENTENCE_ID)
#undef AGGPACK_SENTENCE_ID
      kCount
};

/// A sentence and its values, in order.
struct Wording {
  Sentence sentence = Sentence::kText;
  std::vector<std::string> values;
};

/// The sentence's English words with "{}" for each value ("finite and >= 0").
const char* english_words(Sentence sentence);

/// `words` with each "{}" replaced by the next of `values` (a missing value leaves "{}").
std::string fill_words(const char* words, const std::vector<std::string>& values);

/// Whether the wording says anything: false for kText of no value or of "" (a key without a
/// note or default words).
inline bool has_words(const Wording& wording) {
  return wording.sentence != Sentence::kText ||
         (!wording.values.empty() && !wording.values.front().empty());
}

/// The wording in English (the library's messages).
inline std::string english(const Wording& wording) {
  return fill_words(english_words(wording.sentence), wording.values);
}

}  // namespace aggpack
