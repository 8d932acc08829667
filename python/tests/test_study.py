"""Studies: the file's study as `flexopt run` finds it, and shards merged into it."""

import json
import pickle

import pytest

import flexopt
from conftest import ROOT, WEI2017


def test_run_finds_the_optimum_and_the_zones_of_flexopt_run(study, cli, tmp_path):
    assert round(study.objective, 7) == 12.8979355
    assert study.converged and study.feasible and not study.interrupted
    assert len(study) == 300 and study.start_range == (0, 300)
    done = cli("run", "problems/wei2017.toml", "--quiet", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    assert study.zones() == json.loads((tmp_path / "zones.json").read_text())
    assert study.starts_report() == json.loads((tmp_path / "starts.json").read_text())
    optimum = json.loads((tmp_path / "optimum.json").read_text())
    assert study.optimum() == optimum
    assert study.design == optimum["design"]


def test_records_are_flat_rows_of_every_start(study):
    records = study.to_records()
    assert [r["start"] for r in records] == list(range(300))
    first = records[0]
    assert {"objective", "status", "zone", "start_l2", "end_t4"} <= set(first)
    assert all(not isinstance(v, (dict, list)) for v in first.values())
    converged = sum(r["status"] == "converged" for r in records)
    assert converged == study.optimum()["ends"]["converged"]


def test_shards_merged_in_any_order_equal_the_whole_study(wei2017, study):
    shards = [wei2017.run(start_range=r) for r in [(200, 300), (0, 13), (13, 200)]]
    assert [s.start_range for s in shards] == [(200, 300), (0, 13), (13, 200)]
    merged = flexopt.merge(wei2017, shards)
    assert merged.objective.hex() == study.objective.hex()
    assert [v.hex() for v in merged.design_si] == [v.hex() for v in study.design_si]
    assert merged.zones() == study.zones()
    assert merged.starts_report() == study.starts_report()


def test_a_shard_pickles_as_its_runs(wei2017):
    shard = wei2017.run(starts=40, start_range=(10, 30))
    again = pickle.loads(pickle.dumps(shard))
    assert again.start_range == (10, 30) and again.starts == 40
    assert again.starts_report() == shard.starts_report()
    assert again.zones() == shard.zones()


def test_shards_that_do_not_make_one_study_raise(wei2017):
    a = wei2017.run(starts=6, start_range=(0, 3))
    with pytest.raises(flexopt.FlexoptError) as e:
        flexopt.merge(wei2017, [a])
    assert e.value.key == "shards"
    assert str(e.value).endswith("the shards' start ranges end at 3, not at the study's 6 starts")
    other = wei2017.run(starts=6, seed=1, start_range=(3, 6))
    with pytest.raises(flexopt.FlexoptError, match="the shards are of different studies"):
        flexopt.merge(wei2017, [a, other])


def test_shards_of_other_problems_do_not_merge(wei2017, tmp_path):
    """Shards carry their problem's content hash and model: a shard of another file (same
    model, another objective), of a network, or shards merged into another problem raise;
    a copy of the same file elsewhere is the same problem."""
    root = WEI2017.parent
    min_stress = flexopt.Problem.load(root / "wei2017_min_stress.toml")
    network = flexopt.Problem.load(root / "wei2017_network.toml")
    a = wei2017.run(starts=6, start_range=(0, 3))
    b = wei2017.run(starts=6, start_range=(3, 6))
    for problem, shards, other in [
        (wei2017, [a, min_stress.run(starts=6, start_range=(3, 6))], "model bridge"),
        (wei2017, [a, network.run(starts=6, start_range=(3, 6))], "model network"),
        (min_stress, [a, b], "model bridge"),
    ]:
        with pytest.raises(flexopt.FlexoptError) as e:
            flexopt.merge(problem, shards)
        assert e.value.key == "shards"
        assert "is of another problem (" + other in str(e.value)
    copy = tmp_path / "copy.toml"
    copy.write_text(WEI2017.read_text())
    merged = flexopt.merge(flexopt.Problem.load(copy), [b, a])
    assert merged.objective.hex() == flexopt.merge(wei2017, [a, b]).objective.hex()


def test_run_releases_the_gil(wei2017):
    """While a study solves, another Python thread runs: the main thread's clock readings
    taken while the study's thread is inside `run` span most of the run (were the GIL held,
    they would fall in one switch interval at its ends)."""
    import threading
    import time

    span = {}

    def work():
        span["begin"] = time.perf_counter()
        wei2017.run(starts=1000, threads=1)
        span["end"] = time.perf_counter()

    t = threading.Thread(target=work)
    readings = []
    t.start()
    while t.is_alive():
        readings.append(time.perf_counter())
    t.join()
    inside = [r for r in readings if span["begin"] < r < span["end"]]
    assert inside, "no reading while the study ran"
    assert inside[-1] - inside[0] > 0.5 * (span["end"] - span["begin"])
