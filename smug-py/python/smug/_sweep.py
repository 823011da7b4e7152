"""Sweeps: configs × seeds × a grid of overrides, one row per run, on any executor.

The runs, their ids and their rows are made by the library exactly as ``smug sweep``
makes them, so a run gives the same row from the CLI and from Python (its timing
columns aside). Executors: threads in this process (the default: planning releases the
GIL), any :class:`concurrent.futures.Executor`, ``"ray"`` or ``"dask"``; each run plans
on one thread of its own, so runs side by side share the cores.
"""

from __future__ import annotations

import concurrent.futures
import importlib
import json
import os
import warnings
from typing import Any, Callable, Dict, Iterable, Iterator, List, Mapping, NamedTuple, Optional, Sequence, Union

from . import _smug
from ._smug import ConfigError, InputError, SmugError

PathLike = Union[str, "os.PathLike[str]"]
Seeds = Union[int, str, Iterable[int]]
Executor = Union[None, str, concurrent.futures.Executor]

#: The columns that measure time: two runs of one spec differ in these only.
TIMING_COLUMNS = ("stage_times_s", "total_time_s")

#: The columns whose values are maps (``{name: seconds}``, ``{objective: cost}``).
_MAPS = ("stage_times_s",)
_METRICS_MAPS = ("costs",)


class _Run(NamedTuple):
    run_id: str
    config: str
    overrides: List[str]
    seed: int


def sweep_task(config: PathLike, seed: int, overrides: Any = None) -> Dict[str, Any]:
    """Plans one run of a sweep and returns its row: what ``smug sweep`` writes for the
    same config, seed and overrides (``{"key": value}`` or ``["key=value", ...]``).

    A plain top-level function, so any engine can ship it to its workers (Ray,
    Dask, a process pool). The run plans on one thread of its own; a run that fails
    (bad plugin parameter, unreachable target, ...) is a row with its ``status`` and
    ``error``, not an exception.
    """
    from . import _overrides

    return json.loads(_smug.sweep_task(os.fspath(config), int(seed), _overrides(overrides), 1))


def sweep(
    configs: Union[PathLike, Sequence[PathLike]],
    seeds: Seeds = 1,
    grid: Optional[Mapping[str, Any]] = None,
    executor: Executor = None,
    out: Optional[PathLike] = "sweep.parquet",
    resume: bool = True,
) -> "pyarrow.Table":  # noqa: F821
    """Runs every config × every combination of ``grid`` × every seed, one row per run,
    as ``smug sweep`` does, and returns the rows as a :class:`pyarrow.Table` (also
    written to ``out``).

    ``seeds``: an iterable of seeds, one seed, or ``"1..10"`` / ``"1,4,9"`` as
    ``smug sweep --seeds``. ``grid``: ``{"planner.params.max_stall": [2, 3]}``, each
    key's values (one value alone fixes the key; a list value is a TOML array, so write
    ``[[1, 2]]`` for one array). ``executor``: ``None`` (threads in this process, one
    per core), a :class:`concurrent.futures.Executor` (a process pool, or a Dask
    client's ``get_executor()``), ``"ray"`` (Ray tasks, on the cluster ``ray.init``
    joined) or ``"dask"`` (the current ``distributed`` client). ``out``: a ``.parquet``
    or ``.jsonl`` file (``None``: write nothing); with ``resume``, runs whose id it
    already holds are skipped and its rows kept, so a sweep stopped half-way goes on
    where it stopped. The rows done are written even when the sweep is interrupted.

    Raises :class:`ConfigError` before running anything when a config does not load
    with a combination (unknown key, bad value), or the seeds or grid are malformed.
    """
    pa = _require("pyarrow", "smug.sweep", "sweep")
    run_rows = _executor_rows(executor)
    out_path = None if out is None else os.fspath(out)
    if out_path is not None and not out_path.endswith((".parquet", ".jsonl")):
        raise InputError(f"out {out_path}: expected a .parquet or .jsonl file")
    runs = [
        _Run(*run)
        for run in _smug.sweep_runs(_config_list(configs), _seed_list(seeds), _grid_axes(grid))
    ]
    done = None
    if resume and out_path is not None and os.path.exists(out_path):
        done = _read_table(pa, out_path)
    done_ids = set() if done is None else set(done.column("run_id").to_pylist())
    todo = [run for run in runs if run.run_id not in done_ids]
    rows: Dict[str, Dict[str, Any]] = {}
    try:
        if todo:
            for row in run_rows(todo):
                rows[row["run_id"]] = row
    finally:
        new = _table(pa, [rows[run.run_id] for run in todo if run.run_id in rows])
        table = new if done is None else pa.concat_tables([done, new])
        if out_path is not None:
            _write_table(pa, table, out_path)
    return table


def sweep_rows(table: "pyarrow.Table") -> List[Dict[str, Any]]:  # noqa: F821
    """The rows of a sweep table as dicts: each what :func:`sweep_task` returned and
    ``smug sweep`` wrote for its run."""
    rows = table.to_pylist()
    for row in rows:
        for key in _MAPS:
            row[key] = _as_dict(row[key])
        if row.get("metrics") is not None:
            for key in _METRICS_MAPS:
                row["metrics"][key] = _as_dict(row["metrics"][key])
    return rows


# --- executors ------------------------------------------------------------------------


def _executor_rows(executor: Executor) -> Callable[[List[_Run]], Iterator[Dict[str, Any]]]:
    """How ``executor`` runs a list of runs: a generator of their rows as they finish."""
    if executor is None:
        return _thread_rows
    if isinstance(executor, concurrent.futures.Executor):
        return lambda runs: _futures_rows(executor, runs)
    if executor == "ray":
        ray = _require("ray", "executor='ray'", "ray")
        return lambda runs: _ray_rows(ray, runs)
    if executor == "dask":
        client = _dask_client(_require("distributed", "executor='dask'", "dask"))
        return lambda runs: _dask_rows(client, runs)
    raise TypeError(
        f"executor: expected None, a concurrent.futures.Executor, 'ray' or 'dask', got {executor!r}"
    )


def _thread_rows(runs: List[_Run]) -> Iterator[Dict[str, Any]]:
    workers = min(len(runs), os.cpu_count() or 1)
    with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
        yield from _futures_rows(pool, runs)


def _futures_rows(pool: concurrent.futures.Executor, runs: List[_Run]) -> Iterator[Dict[str, Any]]:
    futures = {pool.submit(sweep_task, run.config, run.seed, run.overrides): run for run in runs}
    try:
        for future in concurrent.futures.as_completed(futures):
            yield _row_of(future.result, futures[future])
    finally:
        for future in futures:
            future.cancel()


def _ray_rows(ray: Any, runs: List[_Run]) -> Iterator[Dict[str, Any]]:
    # One CPU per task: each run plans on a one-thread pool of its own (sweep_task), so
    # no runtime_env is needed for RAYON_NUM_THREADS (one would start fresh workers).
    task = ray.remote(num_cpus=1, max_retries=0)(sweep_task)
    pending = {task.remote(run.config, run.seed, run.overrides): run for run in runs}
    try:
        while pending:
            ready, _ = ray.wait(list(pending), num_returns=1)
            for ref in ready:
                yield _row_of(lambda: ray.get(ref), pending.pop(ref))
    finally:
        for ref in pending:
            ray.cancel(ref)


def _dask_client(distributed: Any) -> Any:
    """The current Dask client."""
    try:
        return distributed.get_client()
    except ValueError:
        raise SmugError(
            "executor='dask' runs on the current Dask client and there is none: start one "
            "first, e.g. `distributed.Client(distributed.LocalCluster())`"
        ) from None


def _dask_rows(client: Any, runs: List[_Run]) -> Iterator[Dict[str, Any]]:
    import distributed

    futures = {
        client.submit(sweep_task, run.config, run.seed, run.overrides, pure=False): run
        for run in runs
    }
    try:
        for future in distributed.as_completed(list(futures)):
            yield _row_of(future.result, futures[future])
    finally:
        client.cancel([f for f in futures if not f.done()])


def _row_of(result: Callable[[], Dict[str, Any]], run: _Run) -> Dict[str, Any]:
    """A task's row, or an ``error`` row when the task itself failed (a worker died)."""
    try:
        return result()
    except Exception as err:  # the engine's error becomes the run's row
        text = _smug.sweep_failed_row(run.config, run.seed, run.overrides, f"{type(err).__name__}: {err}")
        return json.loads(text)


def _require(module: str, what: str, extra: str) -> Any:
    try:
        return importlib.import_module(module)
    except ImportError as err:
        raise ImportError(
            f"{what} needs the `{module}` package: pip install 'smug[{extra}]' ({err})"
        ) from None


# --- arguments ------------------------------------------------------------------------


def _config_list(configs: Union[PathLike, Sequence[PathLike]]) -> List[str]:
    if isinstance(configs, (str, os.PathLike)):
        return [os.fspath(configs)]
    return [os.fspath(config) for config in configs]


def _seed_list(seeds: Seeds) -> List[int]:
    if isinstance(seeds, str):
        return _smug.sweep_seeds(seeds)
    items = [seeds] if _is_integer(seeds) else list(seeds)
    for seed in items:
        if not _is_integer(seed) or int(seed) < 0:
            raise ConfigError(f"seeds: {seed!r} is not a seed (a whole number ≥ 0)")
    return [int(seed) for seed in items]


def _is_integer(value: Any) -> bool:
    return hasattr(value, "__index__") and not isinstance(value, bool)


def _grid_axes(grid: Optional[Mapping[str, Any]]) -> List[Any]:
    from . import _toml_value

    if grid is None:
        return []
    axes = []
    for key, values in grid.items():
        items = values if isinstance(values, (list, tuple)) else [values]
        axes.append((str(key), [_toml_value(value) for value in items]))
    return axes


# --- tables ---------------------------------------------------------------------------


def _schema(pa: Any) -> Any:
    """The columns of a sweep table: one per field of a row, in the row's order."""
    seconds = pa.map_(pa.string(), pa.float64())
    metrics = pa.struct(
        [
            ("objective", pa.string()),
            ("length_m", pa.float64()),
            ("climb_m", pa.float64()),
            ("costs", pa.map_(pa.string(), pa.float64())),
            ("traversability_min", pa.float64()),
            ("traversability_mean", pa.float64()),
            ("risky_length_m", pa.float64()),
        ]
    )
    return pa.schema(
        [
            ("run_id", pa.string()),
            ("config", pa.string()),
            ("overrides", pa.list_(pa.string())),
            ("seed", pa.uint64()),
            ("status", pa.string()),
            ("error", pa.string()),
            ("cost", pa.float64()),
            ("length_m", pa.float64()),
            ("targets", pa.uint64()),
            ("skipped_targets", pa.list_(pa.string())),
            ("deadline_reached", pa.bool_()),
            ("paths_planned", pa.uint64()),
            ("validity_queries", pa.uint64()),
            ("metrics", metrics),
            ("stage_times_s", seconds),
            ("total_time_s", pa.float64()),
            ("smug_version", pa.string()),
        ]
    )


def _table(pa: Any, rows: List[Dict[str, Any]]) -> Any:
    """Rows as a table of :func:`_schema`'s columns."""
    columns = []
    for row in rows:
        row = dict(row)
        for key in _MAPS:
            row[key] = list(row[key].items())
        if row.get("metrics") is not None:
            row["metrics"] = dict(row["metrics"])
            for key in _METRICS_MAPS:
                row["metrics"][key] = list(row["metrics"][key].items())
        columns.append(row)
    return pa.Table.from_pylist(columns, schema=_schema(pa))


def _as_dict(value: Any) -> Any:
    return None if value is None else dict(value)


def _read_table(pa: Any, path: str) -> Any:
    """The rows ``path`` holds (a sweep's parquet or JSON lines)."""
    if path.endswith(".jsonl"):
        rows, unreadable = [], 0
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.strip():
                    try:
                        rows.append(json.loads(line))
                    except json.JSONDecodeError:
                        unreadable += 1
        if unreadable:
            warnings.warn(f"{path}: {unreadable} lines are not rows; their runs run again")
        return _table(pa, [row for row in rows if isinstance(row, dict) and "run_id" in row])
    import pyarrow.parquet as pq

    table = pq.read_table(path)
    if not table.schema.equals(_schema(pa)):
        raise InputError(
            f"{path}: its columns are not those of this smug version's sweep rows; "
            "pass another `out`, or resume=False to replace it"
        )
    return table


def _write_table(pa: Any, table: Any, path: str) -> None:
    """Writes ``table`` to ``path`` whole (a temporary file renamed over it)."""
    partial = path + ".partial"
    if path.endswith(".jsonl"):
        with open(partial, "w", encoding="utf-8") as f:
            for row in sweep_rows(table):
                f.write(json.dumps(row) + "\n")
    else:
        import pyarrow.parquet as pq

        pq.write_table(table, partial)
    os.replace(partial, path)
