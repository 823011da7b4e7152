"""End-to-end tests of sweeps from Python: `smug.sweep` on threads, on a local Ray
cluster and on a local Dask cluster (both bound to 127.0.0.1) gives the rows
`smug sweep` writes, timing columns aside; resume skips the runs done; `Plan` pickles.
"""

from __future__ import annotations

import concurrent.futures
import json
import os
import pickle
import shutil
import sys
import tempfile
from pathlib import Path
from typing import Any, Dict, List

import numpy as np
import pyarrow.parquet as pq
import pytest

import smug
from smug._sweep import TIMING_COLUMNS
from test_smug import REPO, run_cli

GRID = {"planner.params.max_stall": [2, 3]}
SEEDS = [1, 2]


def write_configs(dir: Path) -> List[str]:
    """Two small configs: lunar with 3 stones × 3 PoIs, and the flat demo."""
    lunar = dir / "lunar-small.toml"
    lunar.write_text(
        f"include = {json.dumps(str(REPO / 'configs' / 'lunar.toml'))}\n"
        '[world]\ntype = "lunar"\nparams = { targets = 3, pois_per_target = 3 }\n'
    )
    flat = dir / "flat.toml"
    flat.write_text(f"include = {json.dumps(str(REPO / 'configs' / 'flat-demo.toml'))}\n")
    return [str(lunar), str(flat)]


@pytest.fixture(scope="module")
def swept(tmp_path_factory) -> Dict[str, Any]:
    """The configs, and the rows `smug sweep` wrote for them (2 configs × 2 seeds × 2)."""
    dir = tmp_path_factory.mktemp("sweep")
    configs = write_configs(dir)
    out = dir / "cli.jsonl"
    result = run_cli(
        "sweep", *configs, "--seeds", "1..2", "--grid", "planner.params.max_stall=2,3",
        "--jobs", "2", "--out", str(out),
    )
    assert result.returncode == 0, result.stderr
    rows = [json.loads(line) for line in out.read_text().splitlines()]
    assert len(rows) == 8 and all(row["status"] == "ok" for row in rows), rows
    return {"dir": dir, "configs": configs, "cli_rows": rows, "cli_out": out}


def untimed(rows: List[Dict[str, Any]]) -> Dict[str, Dict[str, Any]]:
    """Rows by run id without their timing columns."""
    return {
        row["run_id"]: {k: v for k, v in row.items() if k not in TIMING_COLUMNS} for row in rows
    }


class CountingExecutor(concurrent.futures.ThreadPoolExecutor):
    """A thread pool that counts the tasks it was given."""

    def __init__(self) -> None:
        super().__init__(max_workers=2)
        self.submitted = 0

    def submit(self, *args, **kwargs):
        self.submitted += 1
        return super().submit(*args, **kwargs)


def test_sweep_on_threads_gives_the_cli_rows_and_resumes(swept, tmp_path):
    out = tmp_path / "sweep.parquet"
    table = smug.sweep(swept["configs"], SEEDS, grid=GRID, out=out)
    assert table.num_rows == 8
    rows = smug.sweep_rows(table)
    assert untimed(rows) == untimed(swept["cli_rows"])
    cli_row = swept["cli_rows"][0]
    assert list(table.column_names) == list(cli_row.keys())
    assert table.schema.field("metrics").type.num_fields == len(cli_row["metrics"])
    assert smug.sweep_rows(pq.read_table(out)) == rows

    # Resume: every run is in the file, nothing runs, the rows stay.
    with CountingExecutor() as executor:
        again = smug.sweep(swept["configs"], SEEDS, grid=GRID, executor=executor, out=out)
    assert executor.submitted == 0
    assert smug.sweep_rows(again) == rows

    # A third seed runs only its own 4 runs.
    with CountingExecutor() as executor:
        more = smug.sweep(swept["configs"], [1, 2, 3], grid=GRID, executor=executor, out=out)
    assert executor.submitted == 4
    assert more.num_rows == 12 and len(set(more.column("run_id").to_pylist())) == 12


def test_the_cli_rows_file_resumes_from_python(swept, tmp_path):
    out = tmp_path / "runs.jsonl"
    out.write_text(swept["cli_out"].read_text())
    with CountingExecutor() as executor:
        table = smug.sweep(swept["configs"], "1..2", grid=GRID, executor=executor, out=out)
    assert executor.submitted == 0
    assert untimed(smug.sweep_rows(table)) == untimed(swept["cli_rows"])


def test_sweep_task_is_one_row_of_the_cli(swept):
    cli = next(r for r in swept["cli_rows"] if r["config"].endswith("flat.toml") and r["seed"] == 2)
    overrides = {"planner.params.max_stall": int(cli["overrides"][0].split("=")[1])}
    row = smug.sweep_task(cli["config"], 2, overrides)
    assert untimed([row]) == untimed([cli])
    assert pickle.loads(pickle.dumps(smug.sweep_task)) is smug.sweep_task


def loopback_env(home: Path) -> Dict[str, str]:
    """What keeps a local Ray cluster to this machine: its node address stays 127.0.0.1
    (Ray otherwise swaps a loopback address for the machine's outward one, where its
    servers then listen), no usage reports, no auth tokens, a temporary HOME."""
    return {
        "HOME": str(home),
        "RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER": "0",
        "RAY_AUTH_MODE": "disabled",
        "RAY_USAGE_STATS_ENABLED": "0",
        "RAY_DISABLE_DOCKER_CPU_WARNING": "1",
        # The workers inherit it (each run plans on a one-thread pool of its own anyway).
        "RAYON_NUM_THREADS": "1",
    }


def test_sweep_on_a_local_ray_cluster_gives_the_same_rows(swept, tmp_path, monkeypatch):
    for key, value in loopback_env(tmp_path / "home").items():
        monkeypatch.setenv(key, value)
    (tmp_path / "home").mkdir()
    import ray
    from ray._private import ray_constants

    # Ray reads the switch when it is first imported: make sure it holds here too.
    monkeypatch.setattr(ray_constants, "ENABLE_RAY_CLUSTER", False)
    # Ray's sockets live under its temporary folder: a short path keeps them within the
    # 107 bytes a Unix socket path may hold.
    ray_dir = tempfile.mkdtemp(prefix="ray-", dir="/tmp")
    ray.init(
        num_cpus=2,
        include_dashboard=False,
        _node_ip_address="127.0.0.1",
        _temp_dir=ray_dir,
        log_to_driver=False,
    )
    try:
        assert ray.util.get_node_ip_address() == "127.0.0.1"
        table = smug.sweep(
            swept["configs"], SEEDS, grid=GRID, executor="ray", out=tmp_path / "ray.parquet"
        )
    finally:
        ray.shutdown()
        shutil.rmtree(ray_dir, ignore_errors=True)
    assert untimed(smug.sweep_rows(table)) == untimed(swept["cli_rows"])


def test_sweep_on_a_local_dask_cluster_gives_the_same_rows(swept, tmp_path, monkeypatch):
    import distributed

    monkeypatch.setenv("RAYON_NUM_THREADS", "1")  # the workers inherit it
    with distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        host="127.0.0.1",
        dashboard_address=None,
        local_directory=str(tmp_path / "dask"),
    ) as cluster, distributed.Client(cluster):
        table = smug.sweep(swept["configs"], SEEDS, grid=GRID, executor="dask", out=None)
    assert untimed(smug.sweep_rows(table)) == untimed(swept["cli_rows"])


@pytest.mark.parametrize(
    "kwargs, error, culprit",
    [
        ({"configs": ["missing.toml"]}, smug.ConfigError, "missing.toml: cannot read"),
        ({"grid": {"robot.lenght": [1, 2]}}, smug.ConfigError, "robot.lenght"),
        ({"grid": {"seed": [1, 2]}}, smug.ConfigError, "seeds, not the grid"),
        ({"seeds": "3..1"}, smug.ConfigError, "seeds `3..1`"),
        ({"seeds": [-1]}, smug.ConfigError, "-1 is not a seed"),
        ({"executor": "spark"}, TypeError, "'spark'"),
        ({"out": "rows.csv"}, smug.InputError, "rows.csv"),
    ],
)
def test_bad_sweeps_are_errors_naming_the_culprit(swept, tmp_path, kwargs, error, culprit):
    args = {"configs": swept["configs"][1:], "seeds": [1], "out": str(tmp_path / "x.parquet")}
    args.update(kwargs)
    with pytest.raises(error) as raised:
        smug.sweep(**args)
    assert culprit in str(raised.value)
    assert not (tmp_path / "x.parquet").exists()


def test_a_missing_engine_is_a_clear_error(swept, monkeypatch):
    monkeypatch.setitem(sys.modules, "ray", None)
    with pytest.raises(ImportError, match=r"pip install 'smug\[ray\]'"):
        smug.sweep(swept["configs"][1:], [1], executor="ray", out=None)


def test_a_plan_pickles_through_its_json(swept):
    plan = smug.plan(swept["configs"][1], seed=1)
    back = pickle.loads(pickle.dumps(plan))
    assert back.to_json() == plan.to_json()
    np.testing.assert_array_equal(back.waypoints, plan.waypoints)
    np.testing.assert_array_equal(back.world.elevation, plan.world.elevation)
    assert back.world.mission == plan.world.mission
    assert back.world.bounds == plan.world.bounds
