# CTest labels for single discovered tests, read by ctest after the test lists that
# gtest_discover_tests writes (tests/CMakeLists.txt appends this file last).
#
# external-solver: the test's time goes into a full run of an external solver (ccx, yade) on a
# file our code wrote. The Release phase of CI runs them; the sanitized phase (scripts/test.sh
# --sanitize) leaves them out (ctest -LE external-solver): the solver is not instrumented, and the
# writing of each file stays under ASan + UBSan in the test named after it.
#   CalculixDeck.CcxRunsTheTroughTestOnASmallPile: the CalculiX deck writer runs in
#     GoldenCli/Case.Matches/export_decks (byte-compared deck).
#   YadeDeck.YadeRunsTheExportedScript: the YADE writer, also in GoldenCli/.../export_decks.
#   ReposeYadeCli.RunsTheSmallTroughEndToEnd: `repose --engine yade` (~20 s CPU of YADE); the
#     script writer and the fill it is given run in ReposeYade.TheScriptHoldsBulletsFill.
#   PaperPackingInCalculix.*: `aggpack pack` of the paper's case (PackCliTest.PapersCaseEndToEnd
#     ThenInfo) and `export --format inp` with the fan (AbaqusExport.*, C3D4 and C3D10) and TetGen
#     at the paper's scale (ExportTetGenCliTest.PaperPackingExportsAndReportsTheFallbacks).
#   PeriodicCcx.*: the periodic .inp (its ties and steps) is checked as text under the sanitizers
#     in PeriodicInp.EveryUpperFaceNodeIsTiedOnceToItsImage, the .dat reader in
#     PeriodicInp.StiffnessFromADatText.
# A name that matches no test is ignored by ctest (the test then simply runs in both phases).
set_tests_properties(
  CalculixDeck.CcxRunsTheTroughTestOnASmallPile
  YadeDeck.YadeRunsTheExportedScript
  ReposeYadeCli.RunsTheSmallTroughEndToEnd
  PaperPackingInCalculix.FanC3D4
  PaperPackingInCalculix.FanC3D10
  PaperPackingInCalculix.TetGenC3D4
  PaperPackingInCalculix.TetGenC3D4Seed4
  PaperPackingInCalculix.TetGenC3D10Seed4
  PeriodicCcx.MortarEverywhereGivesTheMortarsIsotropicStiffness
  PeriodicCcx.PackedBoxLiesBetweenTheReussAndVoigtTensors
  PROPERTIES LABELS external-solver)

# OpenMPI's own allocations at MPI_Init/Finalize (libmpi and its dlopened components) are reported
# as leaks by LeakSanitizer in the sanitized build; leak checking is off for the one test that
# runs `mpirun` (the sweep code it runs is leak-checked by the single-process sweep tests).
set_tests_properties(DistributedCli.MpirunWithTwoRanksGivesTheSingleProcessSweep
  PROPERTIES ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1")

# physics-trend: statistical checks of what the simulation measures (angles rise with friction,
# a pile at rest stays so), minutes under the sanitizers (144 s and 131 s of the sanitized phase's
# 722 s on 2026-12-05) for no code that cheaper tests do not run there. The Release phase runs
# them; the sanitized phase (ctest -LE 'external-solver|physics-trend') leaves them out, and its
# cover of the same code is named here:
#   Repose.AngleRisesWithFrictionAndAsAlphaFalls: run_sweep over alpha x friction with a lattice
#     fill runs in Ensemble.SweepWithSeedsGivesEachCaseTheEnsembleStatistics and
#     GoldenCli/Case.Matches/sweep; run_repose in Repose.WritesJsonCsvAndPng.
#   Repose.PileAtRestStaysAtRestWhenFollowedLonger: the follow-up code in
#     Repose.FollowUpIsMeasuredAndWritten (a small pile), the world's default physics options in
#     Settle.LatticeFallsToADenserPackingInsideItsContainer.
set_tests_properties(
  Repose.AngleRisesWithFrictionAndAsAlphaFalls
  Repose.PileAtRestStaysAtRestWhenFollowedLonger
  PROPERTIES LABELS physics-trend)

# COST: seconds a test took on the 2-core VM (ctest's CTestCostData.txt of the Release phase,
# 2026-12-06; the sanitized phase's where it is the larger). ctest -j starts the most costly tests
# first; a fresh clone has no cost data of its own, and without these hints a 170-s test could be
# started last and leave the other core idle to the end. Rough figures are enough: they only order.
set_tests_properties(CalculixDeck.CcxRunsTheTroughTestOnASmallPile PROPERTIES COST 170)
set_tests_properties(Repose.AngleRisesWithFrictionAndAsAlphaFalls PROPERTIES COST 85)
set_tests_properties(Repose.PileAtRestStaysAtRestWhenFollowedLonger PROPERTIES COST 55)
set_tests_properties(ReposeYadeCli.RunsTheSmallTroughEndToEnd PROPERTIES COST 45)
set_tests_properties(DistributedCli.MpirunWithTwoRanksGivesTheSingleProcessSweep
                     DensePacker.OverlapTolerantCompressionEndsOverlapFreeAndThreadIndependent
                     DistributedCli.TwoWorkersAndMergeGiveTheSingleProcessEnsemble
                     DistributedCli.ThreeWorkersAndMergeGiveTheSingleProcessSweep
                     PROPERTIES COST 40)
set_tests_properties(Settle.LatticeFallsToADenserPackingInsideItsContainer
                     PaperPackingInCalculix.TetGenC3D10Seed4
  PeriodicCcx.MortarEverywhereGivesTheMortarsIsotropicStiffness
  PeriodicCcx.PackedBoxLiesBetweenTheReussAndVoigtTensors
                     PaperPackingInCalculix.FanC3D10
                     DistributedCli.EnsembleSeedsKeyRunsTheEnsembleAndTheFlagOverridesIt
                     EnsembleCli.PerSeedResultsStatisticsAndThreadIndependence
                     DistributedCli.MergeRefusesMissingRunsOtherConfigurationsAndEditedRecords
                     Overlap.SupportShapeKeepsEverySupportValue
                     Voxelize.RandomParticlesMatchExactVolumesToTheResolution
                     PROPERTIES COST 20)
