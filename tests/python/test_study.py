"""Seed ensembles and sweeps of the repose test from Python (the study layer the CLI shares), on
the golden CLI test's tiny trough: about a second per run."""
import json
import math
import os
import pathlib

import numpy as np
import pytest

import aggpack

pytestmark = pytest.mark.skipif(not aggpack.has_sim, reason="built without Bullet")

SOURCE = pathlib.Path(os.environ.get("AGGPACK_SOURCE_DIR", "."))
TROUGH_FILE = SOURCE / "tests/cli/cases/repose/trough.toml"
TROUGH = TROUGH_FILE.read_text()


@pytest.fixture(scope="module")
def ensemble():
    return aggpack.repose(TROUGH, seeds="2,1")


def test_ensemble_summary_is_the_statistics_of_its_seeds(ensemble):
    seeds = ensemble["seeds"]
    assert [s["seed"] for s in seeds] == [2, 1]
    assert all(s["is_valid"] and s["error"] == "" for s in seeds)
    angles = [s["angle_degrees"] for s in seeds]
    assert np.array_equal(ensemble["angles"], angles)
    assert angles[0] != angles[1]  # different seeds, different piles
    st = ensemble["statistics"]
    assert st["seeds_used"] == 2 and st["seeds_failed"] == 0 and st["seeds_total"] == 2
    assert ensemble["angle_degrees"] == st["mean_angle_degrees"]
    assert ensemble["angle_degrees"] == pytest.approx(sum(angles) / 2, rel=1e-14)
    sd = abs(angles[0] - angles[1]) / math.sqrt(2)
    assert st["std_dev_degrees"] == pytest.approx(sd, rel=1e-12)
    assert st["t_quantile"] == pytest.approx(12.7062047, abs=1e-6)
    half = st["t_quantile"] * sd / math.sqrt(2)
    assert st["ci_lower_degrees"] == pytest.approx(st["mean_angle_degrees"] - half, rel=1e-12)
    assert st["ci_upper_degrees"] == pytest.approx(st["mean_angle_degrees"] + half, rel=1e-12)
    assert ensemble["is_cancelled"] is False


def test_a_seed_is_its_own_single_run(ensemble):
    first = ensemble["seeds"][0]
    alone = aggpack.repose(TROUGH, [f"particle.seed={first['seed']}"])
    assert alone["angle_degrees"] == first["angle_degrees"]
    assert alone["particle_count"] == first["particle_count"]


def test_ensemble_is_the_clis_ensemble_json(ensemble, cli, tmp_path):
    out = tmp_path / "out"
    run = cli("repose", str(TROUGH_FILE), "--seeds", "2,1", "-o", str(out), "--width", "64",
              "--progress", "none")
    assert run.returncode == 0, run.stderr
    cli_json = json.loads((out / "ensemble.json").read_text())
    assert [s["seed"] for s in cli_json["seeds"]] == [2, 1]
    assert [s["angle_degrees"] for s in cli_json["seeds"]] == list(ensemble["angles"])
    for key, value in cli_json["statistics"].items():
        assert ensemble["statistics"][key] == value, key
    own = json.loads((out / "seed-1" / "repose.json").read_text())
    assert own["fit"]["angle_degrees"] == ensemble["seeds"][1]["angle_degrees"]


def test_seeds_as_a_count_with_progress_per_seed(ensemble):
    seen = []
    by_count = aggpack.repose(TROUGH, seeds=2, progress=seen.append)
    assert [s["seed"] for s in by_count["seeds"]] == [1, 2]
    assert list(by_count["angles"]) == list(ensemble["angles"])[::-1]
    assert sorted(p["done"] for p in seen) == [1, 2] and {p["total"] for p in seen} == {2}
    assert sorted(p["seed"] for p in seen) == [1, 2]
    assert {p["angle_degrees"] for p in seen} == set(ensemble["angles"])


def test_progress_returning_false_cancels():
    calls = []

    def stop(progress):
        calls.append(progress)
        return False

    result = aggpack.repose(TROUGH, seeds=8, progress=stop)
    assert len(calls) == 1  # no call after the cancel
    ran = len(result["seeds"])
    assert ran >= 1 and result["is_cancelled"] == (ran < 8)
    if (os.cpu_count() or 1) < 8:
        assert result["is_cancelled"] and ran < 8
    assert result["statistics"]["seeds_total"] == ran


def test_exception_in_progress_propagates():
    class Stop(Exception):
        pass

    def fail(progress):
        raise Stop("enough")

    with pytest.raises(Stop, match="enough"):
        aggpack.repose(TROUGH, seeds=[1, 2], progress=fail)


def test_bad_seeds_name_the_keyword():
    for bad in (0, "5-2", [1, 1], [-1], "x", True, 1.5):
        with pytest.raises(aggpack.InvalidInput) as caught:
            aggpack.repose(TROUGH, seeds=bad)
        assert caught.value.field == "seeds", bad
    with pytest.raises(aggpack.InvalidInput) as caught:
        aggpack.repose(TROUGH, progress=print)
    assert caught.value.field == "progress"


SWEEP = ["sweep.alphas=[0.5]", "sweep.frictions=[0.2, 0.4]"]


def test_sweep_cases_are_single_runs_and_report_progress():
    seen = []
    rows = aggpack.sweep(TROUGH, SWEEP, progress=seen.append)
    assert [(r["alpha"], r["friction"]) for r in rows] == [(0.5, 0.2), (0.5, 0.4)]
    assert sorted(p["done"] for p in seen) == [1, 2]
    alone = aggpack.repose(TROUGH, ["physics.friction=0.4"])
    assert rows[1]["angle_degrees"] == alone["angle_degrees"]
    assert rows[1]["particle_count"] == alone["particle_count"]


def test_sweep_with_seeds_gives_each_case_its_ensemble(ensemble):
    # The trough's own case (alpha 0.5, mu_s 0.3) with the fixture's seeds.
    rows = aggpack.sweep(TROUGH, ["sweep.alphas=[0.5]", "sweep.frictions=[0.3]"], seeds=[2, 1])
    assert len(rows) == 1
    row = rows[0]
    assert row["seed_count"] == 2 and row["seeds_used"] == 2
    assert row["angle_degrees"] == ensemble["angle_degrees"]
    assert row["ci_upper_degrees"] == ensemble["statistics"]["ci_upper_degrees"]


def test_merge_of_two_workers_is_the_ensemble(ensemble, cli, tmp_path):
    out = tmp_path / "parts"
    for worker in ("1", "2"):
        run = cli("repose", str(TROUGH_FILE), "--seeds", "2,1", "--case", worker, "--of", "2",
                  "-o", str(out), "--width", "64", "--progress", "none")
        assert run.returncode == 0, run.stderr
    merged = aggpack.merge(str(out))
    assert [s["seed"] for s in merged["seeds"]] == [2, 1]
    assert np.array_equal(merged["angles"], ensemble["angles"])
    assert merged["statistics"] == ensemble["statistics"]
    assert not (out / "ensemble.json").exists()  # merge() writes nothing
    # Without worker 2's record the merge names the missing seed and its worker.
    assert sorted(p.name for p in (out / "runs").glob("*.json")) == ["seed-1.json", "seed-2.json"]
    (out / "runs" / "seed-1.json").unlink()
    with pytest.raises(aggpack.InvalidInput) as caught:
        aggpack.merge(str(out))
    assert caught.value.field == f"merge {out}"
    assert "missing seed 1 (run 2)" in str(caught.value)


def test_merge_of_a_sweep_in_parts_is_the_sweep(cli, tmp_path):
    out = tmp_path / "sweep"
    for worker in ("1", "2"):
        run = cli("sweep", str(TROUGH_FILE), *[f"--set={s}" for s in SWEEP], "--case", worker,
                  "--of", "2", "-o", str(out), "--no-plot", "--progress", "none")
        assert run.returncode == 0, run.stderr
    rows = aggpack.merge(str(out))
    assert [(r["alpha"], r["friction"]) for r in rows] == [(0.5, 0.2), (0.5, 0.4)]
    alone = aggpack.repose(TROUGH, ["physics.friction=0.2"])
    assert rows[0]["angle_degrees"] == alone["angle_degrees"]
    with pytest.raises(aggpack.InvalidInput):
        aggpack.merge(str(tmp_path / "nothing-here"))


def test_python_workers_leave_records_that_merge_into_the_ensemble(ensemble, cli, tmp_path):
    out = tmp_path / "py-parts"
    first = aggpack.repose(TROUGH, seeds="2,1", share=(1, 2), records=str(out))
    assert [s["seed"] for s in first["seeds"]] == [2]  # seed 2 is run 1 of the list: worker 1's
    assert sorted(p.name for p in (out / "runs").glob("*.json")) == ["seed-2.json"]
    aggpack.repose(TROUGH, seeds="2,1", share=(2, 2), records=str(out))
    merged = aggpack.merge(str(out))
    assert np.array_equal(merged["angles"], ensemble["angles"])
    assert merged["statistics"] == ensemble["statistics"]
    # The CLI merges the same records into the single-process ensemble.json.
    run = cli("merge", str(out), "--width", "64")
    assert run.returncode == 0, run.stderr
    cli_json = json.loads((out / "ensemble.json").read_text())
    assert [s["angle_degrees"] for s in cli_json["seeds"]] == list(ensemble["angles"])
    # Another configuration may not add records to the folder.
    with pytest.raises(aggpack.InvalidInput) as caught:
        aggpack.repose(TROUGH, ["physics.friction=0.5"], seeds="2,1", share=(1, 2),
                       records=str(out))
    assert caught.value.field == "records"


def test_a_sweep_share_returns_its_runs_and_records_them(tmp_path):
    out = tmp_path / "sweep-parts"
    rows = aggpack.sweep(TROUGH, SWEEP, share=(2, 2), records=str(out))
    assert [(r["alpha"], r["friction"]) for r in rows] == [(0.5, 0.4)]
    assert [p.name for p in (out / "runs").glob("*.json")] == ["alpha0.50_mu0.40.json"]
    with pytest.raises(aggpack.InvalidInput) as caught:
        aggpack.merge(str(out))
    assert "missing alpha 0.5 mu_s 0.2" in str(caught.value)


def test_bad_shares_and_records_name_the_keyword(tmp_path):
    for bad in ((0, 2), (3, 2), (1,), "1/2", (1.0, 2), (True, 2)):
        with pytest.raises(aggpack.InvalidInput) as caught:
            aggpack.repose(TROUGH, seeds=2, share=bad, records=str(tmp_path / "r"))
        assert caught.value.field == "share", bad
    with pytest.raises(aggpack.InvalidInput) as caught:
        aggpack.repose(TROUGH, seeds=2, share=(1, 2))  # a share without records
    assert caught.value.field == "share"
    with pytest.raises(aggpack.InvalidInput) as caught:
        aggpack.repose(TROUGH, records=str(tmp_path / "r"))  # one run has no records
    assert caught.value.field == "records"
    with pytest.raises(aggpack.InvalidInput) as caught:
        aggpack.sweep(TROUGH, SWEEP, records="")
    assert caught.value.field == "records"
    # A configuration the run would refuse is refused before records= makes its folder.
    with pytest.raises(aggpack.Error):
        aggpack.repose(TROUGH, ["particle.radius=10"], seeds=2, records=str(tmp_path / "r"))
    assert not (tmp_path / "r").exists()


def test_former_particles_table_is_read_with_a_future_warning():
    # The note comes when the configuration is read, before the run (which the bad friction
    # stops at once).
    with pytest.warns(FutureWarning, match=r"\[particles\] is now \[particle\]"):
        with pytest.raises(aggpack.ConfigError) as caught:
            aggpack.repose({"particles": {"seed": 3}}, ["physics.friction=-1"])
    assert caught.value.key == "physics.friction"
