"""Sweeps: one run for every combination of scene settings and seeds, on
any ``concurrent.futures`` executor, so that a study outgrows one machine
without a scheduler of its own.

>>> import rolypoly
>>> def heap_height(world):
...     world.step(600)
...     return float(world.balls.positions[:, 1].max())
>>> rows = rolypoly.sweep(heap_height, rolypoly.Scene.default(),
...                       {"balls.friction": [0.2, 0.8]}, seeds=[1, 2])

On a cluster, hand it Dask's executor (``distributed.Client(address)
.get_executor()``) or Ray's; by default it is a process pool on the
local machine. What goes to the workers is the scene (it pickles as its
text), the overrides, the seed and ``function`` (pickled as the executor
pickles functions: the standard library's pool wants one defined at a module's
top level, Dask's and Ray's take any).
"""

import itertools
from concurrent.futures import Executor, ProcessPoolExecutor
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence

from ._rolypoly import Scene, World


def runs(grid: Mapping[str, Sequence[Any]], seeds: Iterable[int]) -> List[Dict[str, Any]]:
    """Every combination of ``grid``'s values, each with every seed, in
    order: the first key varies slowest, the seed fastest."""
    keys = list(grid)
    seeds = list(seeds)
    out = []
    for values in itertools.product(*(list(grid[k]) for k in keys)):
        for seed in seeds:
            out.append({"overrides": dict(zip(keys, values)), "seed": seed})
    return out


def run_one(function: Callable[[World], Any], scene: Scene, overrides: Dict[str, Any], seed: int) -> Any:
    """One run: the world of ``scene`` with ``overrides`` and ``seed``,
    handed to ``function``. Runs in whichever process the executor chose."""
    if overrides:
        scene = Scene.parse(scene.to_toml(), overrides, name=scene.name)
    return function(World(scene, seed=seed))


def _progress(total: int):
    """A progress bar of runs done, where tqdm is installed."""
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return tqdm(total=total, unit="run", desc="sweep")


def sweep(
    function: Callable[[World], Any],
    scene: Scene,
    grid: Mapping[str, Sequence[Any]],
    seeds: Iterable[int],
    executor: Optional[Executor] = None,
):
    """Runs ``function(world)`` for every world made from ``scene`` with
    each combination of ``grid`` (scene keys to lists of values, as
    ``overrides`` takes them) and each seed, on ``executor`` (a process
    pool on the local machine when None).

    Returns one row per run, in the order of the combinations and then
    the seeds: the grid's keys with their values, ``seed``, ``result``
    (what ``function`` returned) and ``error`` (None, or the exception the
    run raised: a bad override is that run's ``ValueError``, naming it,
    and the other runs finish). A pandas DataFrame where pandas is
    installed, else a list of dicts.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a rolypoly.Scene, not {type(scene).__name__}")
    if not callable(function):
        raise TypeError("function must be callable: it is given each run's world")
    grid = dict(grid)
    todo = runs(grid, seeds)
    own = executor is None
    pool = ProcessPoolExecutor() if own else executor
    bar = _progress(len(todo))
    try:
        futures = [pool.submit(run_one, function, scene, r["overrides"], r["seed"]) for r in todo]
        rows = []
        for r, future in zip(todo, futures):
            error = future.exception()
            row = dict(r["overrides"])
            row["seed"] = r["seed"]
            row["result"] = None if error is not None else future.result()
            row["error"] = error
            rows.append(row)
            if bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()
        if own:
            pool.shutdown()
    try:
        import pandas
    except ImportError:
        return rows
    table = pandas.DataFrame(rows, columns=list(grid) + ["seed", "result", "error"])
    # What the runs returned and raised stay the Python objects they were
    # (None where there is none), not values pandas would convert.
    for column in ("result", "error"):
        table[column] = pandas.Series([row[column] for row in rows], dtype=object, index=table.index)
    return table
