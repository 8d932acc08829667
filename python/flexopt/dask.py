"""Studies, and finite-element checks of many designs, spread over a Dask cluster.

A study's starts are cut into index ranges, each solved by ``Problem.run(start_range=...)``
on a worker, and the shards merged (``flexopt.merge``): the result is the one-process study's
to the last bit, as every start draws from its own seeded stream.
"""

from __future__ import annotations

from typing import Any, Iterable, List, Optional, Tuple

from ._flexopt import Problem, Study, merge

__all__ = ["run", "verify_many", "ranges"]


def ranges(starts: int, shards: int) -> List[Tuple[int, int]]:
    """`starts` cut into `shards` contiguous ranges of sizes differing by at most one."""
    shards = max(1, min(shards, starts))
    bounds = [starts * k // shards for k in range(shards + 1)]
    return [(bounds[k], bounds[k + 1]) for k in range(shards)]


def _shard(problem: Problem, starts: int, seed: Optional[int], solver: Optional[str],
           threads: int, start_range: Tuple[int, int]) -> Study:
    return problem.run(starts=starts, seed=seed, solver=solver, threads=threads,
                       start_range=start_range)


def run(problem: Problem, starts: Optional[int] = None, client: Any = None, *,
        seed: Optional[int] = None, solver: Optional[str] = None, shards: Optional[int] = None,
        threads: int = 1) -> Study:
    """The study of `problem` with its starts spread over `client`'s workers (a
    ``dask.distributed.Client``; the current one when None): `shards` ranges (default: four
    per worker thread), each solved on `threads` threads of its worker."""
    from dask.distributed import default_client

    client = client or default_client()
    if starts is None:
        starts = problem.search["starts"]
    if shards is None:
        shards = 4 * max(1, sum(client.nthreads().values()))
    futures = [client.submit(_shard, problem, starts, seed, solver, threads, r, pure=False)
               for r in ranges(starts, shards)]
    return merge(problem, client.gather(futures))


def verify_many(problem: Problem, designs: Iterable[Any], client: Any = None,
                **settings: Any) -> List[Any]:
    """`Problem.verify` of each design (the finite-element check of its part), one task a
    design, in the designs' order."""
    from dask.distributed import default_client

    client = client or default_client()
    futures = [client.submit(problem.verify, d, pure=False, **settings) for d in designs]
    return client.gather(futures)
