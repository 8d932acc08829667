"""A study spread over a Dask LocalCluster equals the one-process study."""

import pytest
from dask.distributed import Client, LocalCluster

import flexopt
import flexopt.dask


@pytest.fixture(scope="module")
def client():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as c:
        yield c


def test_ranges_cover_the_starts_once():
    assert flexopt.dask.ranges(10, 3) == [(0, 3), (3, 6), (6, 10)]
    assert flexopt.dask.ranges(2, 5) == [(0, 1), (1, 2)]


def test_a_sharded_study_on_two_workers_equals_one_process(wei2017, study, client):
    assert len(client.nthreads()) == 2
    spread = flexopt.dask.run(wei2017, starts=300, client=client, shards=7)
    assert spread.objective.hex() == study.objective.hex()
    assert [v.hex() for v in spread.design_si] == [v.hex() for v in study.design_si]
    counts = lambda s: [(z["rank"], z["count"]) for z in s.zones()["zones"]]
    assert counts(spread) == counts(study)
    assert spread.zones() == study.zones()
    workers = {w for w in client.run(lambda: 1)}
    assert len(workers) == 2


def without_timings(value):
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if k != "seconds"}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def test_fe_checks_of_many_designs_on_the_cluster_equal_one_process(wei2017, study, client):
    designs = [study.design, dict(study.design, l3=study.design["l3"] + 0.5)]
    spread = flexopt.dask.verify_many(wei2017, designs, client, max_dofs=20000)
    assert len(spread) == 2
    for design, report in zip(designs, spread):
        assert without_timings(report) == without_timings(wei2017.verify(design, max_dofs=20000))
    assert spread[0]["design"] == study.design
