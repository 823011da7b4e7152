"""End-to-end tests of the `smug` Python package (run by .ci/run after `pip install ./smug-py`).

The CLI comparison runs the `smug` binary the workspace built: `$SMUG_BIN`, else
`$CARGO_TARGET_DIR/release/smug`, else `target/release/smug` (build it with
`cargo build --release -p smug-cli`); a missing binary fails the test, it does not skip.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import threading
import time
from pathlib import Path
from typing import Dict

import numpy as np
import pytest

import smug

REPO = Path(__file__).resolve().parents[2]
LUNAR = REPO / "configs" / "lunar.toml"


def smug_bin() -> Path:
    if "SMUG_BIN" in os.environ:
        path = Path(os.environ["SMUG_BIN"])
    else:
        target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
        path = target / "release" / "smug"
    assert path.is_file(), (
        f"the smug CLI is not built at {path}: run `cargo build --release -p smug-cli` "
        "or set SMUG_BIN"
    )
    return path


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [str(smug_bin()), *args], capture_output=True, text=True, cwd=REPO, timeout=600
    )


# A 20 × 10 m flat world: start on the left, one target on the right.
RES = 0.1
NX, NY = 200, 100
MISSION = {
    "start": (2.0, 5.0, 0.0),
    "targets": [
        {"id": "far", "position": (18.0, 5.0), "pois": [(17.0, 5.0, 0.0), (18.0, 4.0, 1.57)]},
    ],
}


def flat_world(**kwargs) -> smug.World:
    return smug.World.from_arrays(
        np.zeros((NY, NX)), RES, (0.0, 0.0), mission=kwargs.pop("mission", MISSION), **kwargs
    )


def band(elevation: np.ndarray, resolution: float) -> np.ndarray:
    """Traversable everywhere but a band 8 m ≤ x ≤ 12 m, y ≤ 8 m (a gap at the top)."""
    ny, nx = elevation.shape
    x = (np.arange(nx) + 0.5) * resolution
    y = (np.arange(ny) + 0.5) * resolution
    xx, yy = np.meshgrid(x, y)
    t = np.ones_like(elevation)
    t[(xx >= 8.0) & (xx <= 12.0) & (yy <= 8.0)] = 0.0
    return t


# --- plan -----------------------------------------------------------------------------


def test_plan_from_python_equals_the_cli(tmp_path):
    plan = smug.plan(LUNAR, seed=2)
    cli = run_cli("plan", str(LUNAR), "--seed", "2", "--out", str(tmp_path))
    assert cli.returncode == 0, cli.stderr
    expected = json.loads((tmp_path / "plan.json").read_text())
    assert plan.cost == expected["cost"]  # bit for bit
    assert plan.sequence == expected["sequence"]
    assert plan.pois == expected["pois"]
    assert np.array_equal(plan.waypoints, np.array(expected["waypoints"], dtype=np.float64))
    assert plan.waypoints.shape == (len(expected["waypoints"]), 4)
    assert [s["path"] for s in plan.segments] == [s["path"] for s in expected["segments"]]
    # to_json is what the CLI writes (up to the timings in stats)
    ours = json.loads(plan.to_json())
    for data in (ours, expected):
        data["stats"].pop("stage_times_s")
        data["stats"].pop("breakdown")
    assert ours == expected


def test_plan_attributes_and_set_overrides():
    plan = smug.plan(LUNAR, set={"planner.params.max_stall": 2, "selector.type": "dp"}, seed=1)
    assert isinstance(plan.cost, float) and plan.cost > 0
    assert len(plan.sequence) == 13 and len(plan.pois) == 13
    assert plan.segments[0]["from"] == "start"
    assert plan.stats["paths_planned"] > 0
    assert plan.waypoints.dtype == np.float64
    assert plan.world.traversability is not None
    assert plan.world.elevation.shape == (290, 300)
    same = smug.plan(LUNAR, set=["planner.params.max_stall=2", "selector.type=\"dp\""], seed=1)
    assert same.cost == plan.cost
    assert "cost=" in repr(plan)


def test_plan_releases_the_gil():
    done = threading.Event()
    result = {}

    def worker():
        result["plan"] = smug.plan(LUNAR, set={"selector.type": "dp"}, seed=3)
        done.set()

    thread = threading.Thread(target=worker)
    spins = 0
    thread.start()
    started = time.perf_counter()
    while not done.is_set():
        spins += 1
        time.sleep(0.001)
    elapsed = time.perf_counter() - started
    thread.join()
    assert result["plan"].cost > 0
    # With the GIL held, this thread could not run while Rust plans.
    assert spins >= max(3, int(elapsed / 0.001) // 4), (spins, elapsed)


# --- worlds from arrays -----------------------------------------------------------------


def test_from_arrays_world_plans():
    world = flat_world(name="flat-20x10")
    assert world.elevation.shape == (NY, NX)
    assert world.bounds == (0.0, 0.0, 20.0, 10.0)
    assert world.mission["targets"][0]["pois"][1] == {"x": 18.0, "y": 4.0, "yaw": 1.57}
    plan = smug.plan(LUNAR, world=world)
    assert plan.sequence == ["far"]
    assert plan.world.name == "flat-20x10"
    start, end = plan.waypoints[0], plan.waypoints[-1]
    assert tuple(start[:2]) == (2.0, 5.0) and tuple(end[:2]) == (2.0, 5.0)
    # on flat ground straight there and back: about 2 × 15 m
    assert 29.9 < plan.metrics["length_m"] < 31.0


def test_from_arrays_occupancy_blocks_cells():
    occupancy = np.zeros((NY, NX), dtype=bool)
    occupancy[:, 95:105] = True  # a wall across the map at x ≈ 10 m
    world = flat_world(occupancy=occupancy)
    assert world.elevation[50, 100] == pytest.approx(2.0)
    with pytest.raises(smug.NoSolution, match="no safe path reaches target.*`far`"):
        smug.plan(LUNAR, world=world)


def test_from_arrays_traversability_layer_is_kept():
    world = flat_world(traversability=np.full((NY, NX), 0.5, dtype=np.float32))
    assert np.all(world.traversability == 0.5)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"elevation": np.zeros((4, 4, 2))}, r"elevation: expected a 2-D array .* got shape \(4, 4, 2\)"),
        ({"elevation": np.zeros((4, 4), dtype=np.int64)}, r"elevation: dtype int64 is not supported; use float32 or float64"),
        ({"elevation": [[0.0]]}, r"elevation: expected a numpy array, got list"),
        ({"resolution": -1.0}, r"elevation: grid resolution must be > 0, got -1"),
        ({"traversability": np.zeros((3, 3))}, r"traversability: shape \(3, 3\) differs from the elevation's \(100, 200\)"),
        ({"traversability": np.full((NY, NX), 2.0)}, r"traversability: value 2 at \[0, 0\] .* outside \[0, 1\]"),
        ({"occupancy": np.zeros((NY, NX))}, r"occupancy: dtype float64 is not supported; use bool"),
        ({"mission": {"start": (1.0, 1.0), "targets": []}}, r"mission.start: expected \(x, y, yaw\), got 2 numbers"),
        ({"mission": {"start": (1.0, 1.0, 0.0), "targets": [{"id": "t", "position": (1, 1), "pois": [(50.0, 1.0, 0.0)]}]}},
         r"mission: PoI 0 of target `t` lies outside the map \(bounds \[0, 0\] to \[20, 10\]\)"),
        ({"mission": {"start": (1.0, 1.0, 0.0), "targets": [{"id": "t", "pois": []}]}}, r"mission: missing field `position`"),
        ({"mission": {"start": (1.0, 1.0, 0.0), "targets": [{"id": "t", "position": (1, 1), "pois": []}]}},
         r"mission: target `t` has no pose of interest"),
    ],
)
def test_from_arrays_errors_name_the_culprit(kwargs, message):
    args = {"elevation": np.zeros((NY, NX)), "resolution": RES, "mission": MISSION}
    args.update(kwargs)
    with pytest.raises(smug.InputError, match=message):
        smug.World.from_arrays(args.pop("elevation"), args.pop("resolution"), **args)


# --- traversability written in Python ----------------------------------------------------


def test_python_traversability_changes_the_plan():
    world = flat_world()
    straight = smug.plan(LUNAR, world=world)
    calls = []

    def estimator(elevation, resolution):
        calls.append((elevation.shape, elevation.dtype, resolution))
        return band(elevation, resolution)

    around = smug.plan(LUNAR, world=world, traversability=estimator)
    assert calls == [((NY, NX), np.float64, RES)]
    assert np.array_equal(around.world.traversability, band(np.zeros((NY, NX)), RES))
    assert around.cost > straight.cost + 1.0
    # no waypoint lies in the band (the checkers test the traversability under the
    # robot's centre, every 0.5 m along a leg: a leg may clip the band's corner)
    w = around.waypoints
    for x, y in w[:, :2]:
        assert not (8.0 <= x <= 12.0 and y <= 8.0), (x, y)
    for a, b in zip(w[:-1], w[1:]):
        n = int(np.ceil(np.hypot(*(b[:2] - a[:2])) / 0.5))
        inside = [
            (x, y)
            for x, y in (a[:2] + s * (b[:2] - a[:2]) for s in np.linspace(0.0, 1.0, 4 * n + 1))
            if 8.0 + 0.5 <= x <= 12.0 - 0.5 and y <= 8.0 - 0.5
        ]
        assert not inside, inside[:3]
    # and it goes through the gap
    assert any(p[1] > 8.0 and 8.0 <= p[0] <= 12.0 for p in w) or any(
        a[1] > 8.0 and b[1] > 8.0 and a[0] < 8.0 < 12.0 < b[0] for a, b in zip(w[:-1], w[1:])
    )
    # the plan's metrics are computed on the Python layer
    assert straight.metrics.get("traversability_mean") is None or straight.metrics["risky_length_m"] == 0.0
    assert around.metrics["traversability_mean"] > 0.95


def test_python_traversability_float32_and_nan_are_accepted():
    def estimator(elevation, resolution):
        t = np.ones(elevation.shape, dtype=np.float32)
        t[0, :] = np.nan
        return t

    plan = smug.plan(LUNAR, world=flat_world(), traversability=estimator)
    assert np.isnan(plan.world.traversability[0]).all()


@pytest.mark.parametrize(
    "returned, message",
    [
        (lambda e: np.ones((5, 5)), r"the traversability function's result: shape \(5, 5\) differs from the elevation's \(100, 200\)"),
        (lambda e: np.ones(e.shape, dtype=np.int64), r"the traversability function's result: dtype int64 is not supported; use float32 or float64"),
        (lambda e: np.full(e.shape, 1.5), r"the traversability function's result: value 1.5 at \[0, 0\] \(row, column\) is outside \[0, 1\]"),
        (lambda e: np.ones(e.shape[0]), r"the traversability function's result: expected a 2-D array .* got shape \(100,\)"),
        (lambda e: "no", r"the traversability function's result: expected a numpy array, got str"),
    ],
)
def test_python_traversability_errors_name_shape_dtype_range(returned, message):
    with pytest.raises(smug.InputError, match=message):
        smug.plan(LUNAR, world=flat_world(), traversability=lambda e, r: returned(e))


def test_python_traversability_exception_is_the_cause():
    def broken(elevation, resolution):
        raise RuntimeError("model weights missing")

    with pytest.raises(smug.InputError, match="the traversability function raised RuntimeError: model weights missing") as info:
        smug.plan(LUNAR, world=flat_world(), traversability=broken)
    assert isinstance(info.value.__cause__, RuntimeError)


# --- errors carry the CLI's messages ----------------------------------------------------


@pytest.mark.parametrize(
    "config, set, error, culprit",
    [
        (LUNAR, ["planner.params.no_such_key=1"], smug.ConfigError, "planner.params.no_such_key"),
        (LUNAR, ["selector.type=\"nope\""], smug.ConfigError, "unknown selector plugin `nope`"),
        (LUNAR, ["robot.length=100.0"], smug.ConfigError, "robot.length"),
        (REPO / "configs" / "no-such.toml", [], smug.ConfigError, "no-such.toml: cannot read"),
    ],
)
def test_errors_are_typed_and_carry_the_cli_message(config, set, error, culprit):
    with pytest.raises(error) as info:
        smug.plan(config, set=set)
    message = str(info.value)
    assert culprit in message
    assert isinstance(info.value, smug.SmugError)
    args = ["plan", str(config), "--out", "/dev/null/never"]
    for s in set:
        args += ["--set", s]
    cli = run_cli(*args)
    assert cli.returncode == 2
    assert cli.stderr.strip() == f"smug: error: {message}"


def test_no_solution_names_the_target_like_the_cli(tmp_path):
    occupancy = np.zeros((NY, NX), dtype=bool)
    occupancy[:, 95:105] = True
    with pytest.raises(smug.NoSolution) as info:
        smug.plan(LUNAR, world=flat_world(occupancy=occupancy))
    first, *legs = str(info.value).splitlines()
    assert first == "no solution: no safe path reaches target(s) `far`"
    assert legs and legs[0].startswith("  `far`: the legs from the start to its PoIs: ")
    assert "budget_spent" in legs[0]


def test_input_error_for_a_start_in_collision():
    t = np.ones((NY, NX))
    with pytest.raises(smug.InputError, match=r"the start pose \(2.000, 5.000, yaw 0.000\) is not valid"):
        smug.plan(LUNAR, world=flat_world(), traversability=lambda e, r: t * 0.0)


# --- plugins, load_world, p2p -----------------------------------------------------------


def test_plugins_is_the_registry():
    stages = smug.plugins()
    names = {s["stage"]: [p["name"] for p in s["plugins"]] for s in stages}
    assert list(names)[:2] == ["world", "traversability"]
    assert {"lunar", "indoor", "flat", "map"} <= set(names["world"])
    assert "lazy-prm-star" in names["planner"]
    cli = run_cli("plugins", "--json")
    assert json.loads(cli.stdout) == stages


def test_load_world_matches_the_plans_world():
    world = smug.load_world(LUNAR, seed=1)
    plan = smug.plan(LUNAR, seed=1)
    assert np.array_equal(world.elevation, plan.world.elevation)
    assert np.array_equal(world.traversability, plan.world.traversability, equal_nan=True)
    assert len(world.mission["targets"]) == 13


def test_p2p_on_a_shared_roadmap():
    occupancy = np.zeros((NY, NX), dtype=bool)
    occupancy[:80, 95:105] = True  # a wall with a gap at the top
    world = flat_world(occupancy=occupancy)
    queries = np.array([[2.0, 5.0, 0.0, 18.0, 5.0, 0.0], [18.0, 5.0, 0.0, 2.0, 2.0, 0.0]])
    results = smug.p2p(queries, world=world)
    assert [q["status"] for q in results["queries"]] == ["exact", "exact"]
    first = results["queries"][0]
    assert first["no_path"] is None and first["why"] is None
    # Around the wall, not through it (16): at least over its top corners, (2, 5) →
    # (9.5, 8) → (10.5, 8) → (18, 5); and close to that (the disc keeps its radius).
    around = 2.0 * np.hypot(7.5, 3.0) + 1.0
    assert around < first["cost"] < 1.05 * around
    assert all(not (9.5 <= x <= 10.5 and y < 8.0) for x, y, _ in first["waypoints"])
    # the second query reuses the roadmap the first grew
    assert results["queries"][1]["vertices"] >= first["vertices"]
    with pytest.raises(smug.InputError, match=r"queries: expected shape \(n, 6\)"):
        smug.p2p(np.zeros((2, 5)), world=world)


# --- replan ---------------------------------------------------------------------------

DEMO = REPO / "configs" / "flat-demo.toml"


def test_replan_equals_the_cli_and_is_marked(tmp_path):
    state = tmp_path / "state.toml"
    state.write_text(
        'pose = [6.5, 3.0, -1.5]\nvisited = ["gauge-b"]\nfailed_pois = [["gauge-a", 0]]\n'
        "[[obstacles]]\ncenter = [2.5, 3.5]\nradius = 0.6\nheight = 1.0\n"
    )
    plan = smug.replan(DEMO, state)
    cli = run_cli("replan", str(DEMO), "--state", str(state), "--out", str(tmp_path / "out"))
    assert cli.returncode == 0, cli.stderr
    expected = json.loads((tmp_path / "out" / "plan.json").read_text())
    assert plan.cost == expected["cost"]
    assert plan.sequence == expected["sequence"] and "gauge-b" not in plan.sequence
    assert plan.pois == expected["pois"]
    assert tuple(plan.waypoints[0, :2]) == (6.5, 3.0)
    marked = plan.to_dict()["replan"]
    assert marked["state"]["failed_pois"] == [["gauge-a", 0]]
    assert marked["state_file"] == str(state)


def test_replan_errors_name_the_key_or_say_nothing_is_left(tmp_path):
    state = tmp_path / "state.toml"
    state.write_text('pose = [1.0, 1.0, 0.0]\nvisited = ["nope"]\n')
    with pytest.raises(smug.InputError, match=r"`visited\[0\]`: unknown target id `nope`"):
        smug.replan(DEMO, state)
    state.write_text('pose = [1.0, 1.0, 0.0]\nvisited = ["gauge-a", "gauge-b", "valve-c"]\n')
    with pytest.raises(smug.NoSolution, match="no reachable target"):
        smug.replan(DEMO, state)


def test_plan_saves_a_roadmap_that_replan_starts_from(tmp_path):
    roadmap = tmp_path / "demo.roadmap"
    plan = smug.plan(DEMO, save_roadmap=roadmap)
    assert roadmap.is_file()
    state = tmp_path / "state.toml"
    state.write_text("pose = [1.0, 1.0, 0.0]\n")
    # An empty state on the saved roadmap reproduces the plan bit for bit.
    again = smug.replan(DEMO, state, roadmap=roadmap)
    assert again.cost == plan.cost and again.sequence == plan.sequence
    np.testing.assert_array_equal(again.waypoints, plan.waypoints)
    assert again.stats["counters"]["warm_answers_served"] > 0
    cli = run_cli(
        "replan", str(DEMO), "--state", str(state), "--roadmap", str(roadmap),
        "--out", str(tmp_path / "out"),
    )
    assert cli.returncode == 0, cli.stderr
    assert json.loads((tmp_path / "out" / "plan.json").read_text())["cost"] == again.cost
    with pytest.raises(smug.InputError, match="built for another config"):
        smug.replan(DEMO, state, seed=2, roadmap=roadmap)
    truncated = tmp_path / "truncated.roadmap"
    truncated.write_bytes(roadmap.read_bytes()[:-10])
    with pytest.raises(smug.InputError, match="truncated"):
        smug.replan(DEMO, state, roadmap=truncated)
    with pytest.raises(smug.InputError, match="the configured planner keeps none"):
        smug.plan(
            REPO / "configs" / "indoor-disc.toml",
            set={"planner.type": "visibility"},
            save_roadmap=tmp_path / "none.roadmap",
        )


def test_a_session_plans_as_plan_and_replans_in_place(tmp_path):
    session = smug.Session(DEMO)
    plan = session.plan()
    direct = smug.plan(DEMO)
    assert plan.cost == direct.cost
    np.testing.assert_array_equal(plan.waypoints, direct.waypoints)
    assert session.known_paths > 0 and session.obstacles == []
    rock = {"center": (2.5, 3.5), "radius": 0.6, "height": 1.0}
    state = {"pose": (6.5, 3.0, -1.5), "visited": ["gauge-b"], "obstacles": [rock]}
    replan = session.replan(state)
    assert tuple(replan.waypoints[0, :2]) == (6.5, 3.0)
    assert "gauge-b" not in replan.sequence
    assert replan.to_dict()["replan"]["state"]["visited"] == ["gauge-b"]
    assert session.obstacles == [(2.5, 3.5, 0.6, 1.0)]
    for x, y, *_ in replan.waypoints:
        assert (x - 2.5) ** 2 + (y - 3.5) ** 2 > 0.6**2
    # The same replan from scratch: same targets, cost within the flat demo's spread.
    path = tmp_path / "state.toml"
    path.write_text(
        'pose = [6.5, 3.0, -1.5]\nvisited = ["gauge-b"]\n'
        "[[obstacles]]\ncenter = [2.5, 3.5]\nradius = 0.6\nheight = 1.0\n"
    )
    scratch = smug.replan(DEMO, path)
    assert sorted(scratch.sequence) == sorted(replan.sequence)
    assert replan.cost <= scratch.cost * 1.25
    # Obstacles accumulate: dropping an applied one is refused, naming the key.
    with pytest.raises(smug.InputError, match="`obstacles`"):
        session.replan({"pose": (6.5, 3.0, -1.5)})
    with pytest.raises(smug.NoSolution, match="no reachable target"):
        session.replan({"pose": (1.0, 1.0, 0.0), "visited": ["gauge-a", "gauge-b", "valve-c"],
                        "obstacles": [rock]})
    # The session goes on after errors; a state file works too.
    again = session.replan(path)
    assert again.sequence == replan.sequence
    more = dict(state, obstacles=[rock, {"center": (10.5, 1.0), "radius": 0.4, "height": 0.5}])
    session.replan(more)
    assert len(session.obstacles) == 2


# --- run context: each pipeline its own limits and deadline --------------------------


def many_targets_config(path: Path, targets: int = 40) -> Path:
    """A flat 20 × 20 m world at 0.5 m (a 6.4 kB grid) with `targets` one-PoI targets:
    the sequencer's cost matrix takes (targets + 1)² × 8 bytes (13.4 kB for 40)."""
    lines = [
        "seed = 1",
        '[world]\ntype = "flat"',
        '[world.params]\nname = "many-targets"\nsize = [20.0, 20.0]\nresolution = 0.5',
        "[world.params.mission]\nstart = { x = 1.0, y = 1.0, yaw = 0.0 }",
    ]
    for k in range(targets):
        x, y = 3.0 + 2.0 * (k % 8), 3.0 + 3.0 * (k // 8)
        lines.append(
            f'[[world.params.mission.targets]]\nid = "t{k}"\nposition = {{ x = {x}, y = {y} }}\n'
            f"pois = [{{ x = {x}, y = {y - 0.5}, yaw = 0.0 }}]"
        )
    lines += [
        '[validity]\ntype = "clearance-2d"',
        '[motion]\ntype = "discrete"\nparams = { resolution = 0.1 }',
        '[planner]\ntype = "visibility"',
        '[sequencer]\ntype = "auto"',
        '[selector]\ntype = "dp"',
    ]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_two_pipelines_keep_their_own_limits_and_deadlines(tmp_path):
    config = many_targets_config(tmp_path / "many.toml")
    # Built first, with a 10 kB limit: the world fits, the 41 × 41 cost matrix does not.
    limited = smug.Session(config, set={"limits.memory_gb": 1e-5})
    # Built second, with the default limit (before the run context, its assembly
    # reset the process-wide limit the first session planned within).
    roomy = smug.Session(config)
    with pytest.raises(smug.InputError, match=r"41×41 cost matrix.*10\.000 kB"):
        limited.plan()
    plan = roomy.plan()
    assert len(plan.sequence) == 40
    assert not plan.to_dict().get("deadline_reached", False)
    # A limited pipeline built last does not limit the roomy one.
    limited_again = smug.Session(config, set={"limits.memory_gb": 1e-5})
    assert len(roomy.plan().sequence) == 40
    with pytest.raises(smug.InputError, match="cost matrix"):
        limited_again.plan()

    # Deadlines: a pipeline with a deadline that passes at once, one without; planned
    # in turn, each keeps its own.
    hurried = smug.Session(config, set={"plan.deadline": 1e-6})
    patient = smug.Session(config)
    for _ in range(2):
        try:
            assert hurried.plan().to_dict()["deadline_reached"]
        except smug.NoSolution as err:
            assert "deadline" in str(err)
        plan = patient.plan()
        assert len(plan.sequence) == 40
        assert not plan.to_dict().get("deadline_reached", False)


# --- plan.mcap ------------------------------------------------------------------------


def _traversability_cells(t: np.ndarray) -> bytes:
    """plan.mcap's traversability grid: round(100 (1 - t)) as int8, -1 where NaN."""
    cells = np.where(np.isnan(t), -1, np.round(100.0 * (1.0 - np.clip(t, 0.0, 1.0))))
    return cells.astype(np.int8).tobytes()


def _occupancy_cells(elevation: np.ndarray) -> bytes:
    """The exported PGM's rule: occupied 0.5 m above the lowest cell, -1 where NaN."""
    lowest = np.nanmin(elevation)
    cells = np.where(np.isnan(elevation), -1, np.where(elevation - lowest > 0.5, 100, 0))
    return cells.astype(np.int8).tobytes()


def test_plan_mcap_reads_back_in_an_independent_reader(tmp_path):
    from mcap_ros2.reader import read_ros2_messages

    plan = smug.plan(LUNAR, seed=1)  # seed 1: one PoI invalid for ANYmal
    path = tmp_path / "plan.mcap"
    plan.to_mcap(path)
    cli = run_cli("plan", str(LUNAR), "--seed", "1", "--out", str(tmp_path / "cli"))
    assert cli.returncode == 0, cli.stderr
    assert path.read_bytes() == (tmp_path / "cli" / "plan.mcap").read_bytes()

    by_topic: Dict[str, list] = {}
    for m in read_ros2_messages(str(path)):
        assert m.schema.encoding == "ros2msg" and m.channel.message_encoding == "cdr"
        by_topic.setdefault(m.channel.topic, []).append(m)
    (path_msg,) = by_topic["/smug/plan"]
    assert path_msg.schema.name == "nav_msgs/msg/Path"
    poses = path_msg.ros_msg.poses
    assert path_msg.ros_msg.header.frame_id == "map"
    got = np.array([[p.pose.position.x, p.pose.position.y, p.pose.position.z] for p in poses])
    np.testing.assert_array_equal(got, plan.waypoints[:, :3])
    yaw = np.array([2.0 * math.atan2(p.pose.orientation.z, p.pose.orientation.w) for p in poses])
    dyaw = (yaw - plan.waypoints[:, 3] + math.pi) % (2 * math.pi) - math.pi
    assert np.abs(dyaw).max() < 1e-12
    (pois,) = by_topic["/smug/pois"]
    assert [(p.position.x, p.position.y) for p in pois.ros_msg.poses] == [
        (c["pose"]["x"], c["pose"]["y"]) for c in plan.pois
    ]

    world = plan.world
    (trav,) = by_topic["/smug/traversability"]
    ny, nx = world.elevation.shape
    assert (trav.ros_msg.info.width, trav.ros_msg.info.height) == (nx, ny)
    assert bytes(np.asarray(trav.ros_msg.data, dtype=np.int8)) == _traversability_cells(
        world.traversability
    )
    (occ,) = by_topic["/smug/occupancy"]
    assert bytes(np.asarray(occ.ros_msg.data, dtype=np.int8)) == _occupancy_cells(
        world.elevation.astype(np.float64)
    )
    (markers,) = by_topic["/smug/markers"]
    colours = {}
    for marker in markers.ros_msg.markers:
        if marker.ns == "pois":
            colours[marker.text] = (marker.color.r, marker.color.g, marker.color.b)
    chosen = {f"{c['target']}#{c['index']}" for c in plan.pois}
    assert len(colours) == 13 * 10
    assert len({colours[k] for k in chosen}) == 1
    assert len(set(colours.values())) == 3  # chosen, unused, invalid (lunar has one)
    assert len(by_topic["/tf"]) == len(plan.waypoints)

    plan.to_mcap(path, append=True)
    paths = [m for m in read_ros2_messages(str(path)) if m.channel.topic == "/smug/plan"]
    assert len(paths) == 2 and paths[1].log_time_ns > paths[0].log_time_ns


# --- onnx traversability --------------------------------------------------------------

LUNAR_ONNX = REPO / "configs" / "lunar-onnx.toml"
CNN = REPO / "configs" / "models" / "traversability-cnn.onnx"


def test_onnx_layer_equals_onnxruntime_on_generated_terrain():
    import onnxruntime as ort

    session = ort.InferenceSession(str(CNN), providers=["CPUExecutionProvider"])
    for seed in (1, 2):
        world = smug.load_world(LUNAR_ONNX, seed=seed)  # procedural terrain of the seed
        z = world.elevation.astype(np.float32)
        assert not np.isnan(z).any()
        # lunar-onnx.toml: edge padding, overlap 4 >= the CNN's receptive radius (3).
        padded = np.pad(z, 4, mode="edge")[None, None]
        (out,) = session.run(None, {"elevation": padded})
        expected = np.clip(out[0, 0, 4:-4, 4:-4], 0.0, 1.0)
        np.testing.assert_allclose(world.traversability, expected, rtol=0, atol=1e-5)
        assert expected.min() < 0.1 < 0.9 < expected.max()  # the stones show


def test_lunar_plans_with_the_onnx_model_from_python_and_the_cli(tmp_path):
    plan = smug.plan(LUNAR_ONNX, seed=1)
    cli = run_cli("plan", str(LUNAR_ONNX), "--seed", "1", "--out", str(tmp_path))
    assert cli.returncode == 0, cli.stderr
    expected = json.loads((tmp_path / "plan.json").read_text())
    assert plan.cost == expected["cost"] and len(plan.sequence) == 13
    files = plan.to_dict()["traversability_files"]
    assert list(files) == ["models/traversability-cnn.onnx"]
    assert files == expected["traversability_files"]


@pytest.mark.parametrize(
    "model, reason",
    [
        ("no-such-model.onnx", "no such file"),
        (REPO / "smug-validity" / "tests" / "models" / "rank3.onnx", "wrong input rank"),
        (REPO / "smug-validity" / "tests" / "models" / "nan.onnx", "NaN output"),
    ],
)
def test_a_bad_onnx_model_is_an_error_naming_the_file_and_why(model, reason, tmp_path):
    overrides = {"traversability.type": "onnx", "traversability.params": {"model": str(model)}}
    with pytest.raises(smug.SmugError) as raised:
        smug.plan(LUNAR, set=overrides)
    message = str(raised.value)
    assert Path(model).name in message and reason in message, message
    cli = run_cli(
        "plan", str(LUNAR), "--set", "traversability.type=\"onnx\"",
        "--set", f"traversability.params={{ model = {json.dumps(str(model))} }}",
        "--out", str(tmp_path),
    )
    assert cli.returncode == 2 and Path(model).name in cli.stderr and reason in cli.stderr


FLAT_TEAM = """seed = 1
[world]
type = "flat"
[world.params]
size = [12.0, 8.0]
obstacles = [{ min = [6.0, 0.0], max = [7.0, 3.0], height = 1.0 }]
[world.params.mission]
start = { x = 1.0, y = 1.0 }
[[world.params.mission.targets]]
id = "gauge-a"
position = { x = 2.5, y = 6.5 }
pois = [{ x = 2.5, y = 5.5, yaw = 1.5708 }]
[[world.params.mission.targets]]
id = "gauge-b"
position = { x = 10.5, y = 6.0 }
pois = [{ x = 10.5, y = 5.0, yaw = 1.5708 }]
[traversability]
type = "geometric"
[sampler]
type = "informed"
[planner]
type = "lazy-prm-star"
[team]
objective = "makespan"
[[team.robots]]
name = "one"
include = "ANYMAL"
start = { x = 1.0, y = 1.0 }
validity = { type = "volumetric" }
[[team.robots]]
name = "two"
include = "ANYMAL"
start = { x = 1.5, y = 3.0 }
validity = { type = "volumetric" }
"""


def test_a_team_plan_has_one_entry_per_robot(tmp_path: Path) -> None:
    config = tmp_path / "team.toml"
    anymal = REPO / "configs" / "robots" / "anymal.toml"
    config.write_text(FLAT_TEAM.replace("ANYMAL", str(anymal)))
    plan = smug.plan(config)
    robots = plan.robots
    assert [r["name"] for r in robots] == ["one", "two"]
    served = sorted(t for r in robots for t in r["sequence"])
    assert served == ["gauge-a", "gauge-b"]
    data = plan.to_dict()
    assert data["objective"] == "makespan"
    assert math.isclose(data["makespan"], max(r["cost"] for r in robots))
    assert math.isclose(plan.cost, data["makespan"])
    for r in robots:
        assert r["waypoints"].shape[1] == 4 and r["waypoints"].dtype == np.float64
        assert r["time"] == pytest.approx(r["cost"])
    assert "team of 2" in repr(plan)
    assert smug.plan(LUNAR, set={"world.params.targets": 2}).robots == []


def test_a_team_replans_without_a_lost_robot(tmp_path: Path) -> None:
    config = tmp_path / "team.toml"
    anymal = REPO / "configs" / "robots" / "anymal.toml"
    config.write_text(FLAT_TEAM.replace("ANYMAL", str(anymal)))
    state = {
        "visited": ["gauge-a"],
        "robots": [{"name": "one", "lost": True}, {"name": "two", "pose": (3.0, 4.0, 0.0)}],
    }
    state_file = tmp_path / "state.toml"
    state_file.write_text(smug._state_toml(state))
    plan = smug.replan(config, state_file)
    assert [r["name"] for r in plan.robots] == ["two"]
    assert plan.robots[0]["sequence"] == ["gauge-b"]
    assert tuple(plan.robots[0]["waypoints"][0, :2]) == (3.0, 4.0)
    assert plan.to_dict()["replan"]["lost"] == ["one"]
    cli = run_cli("replan", str(config), "--state", str(state_file), "--out", str(tmp_path / "out"))
    assert cli.returncode == 0, cli.stderr
    expected = json.loads((tmp_path / "out" / "plan.json").read_text())
    assert plan.cost == expected["cost"]
    plan.to_mcap(tmp_path / "team.mcap", append=True)
    assert (tmp_path / "team.mcap").read_bytes() == (tmp_path / "out" / "plan.mcap").read_bytes()
    # A session keeps the team: its first plan is smug.plan's, its replans take states.
    session = smug.Session(config)
    assert session.plan().cost == smug.plan(config).cost
    again = session.replan(state)
    assert again.robots[0]["sequence"] == ["gauge-b"]
    with pytest.raises(smug.InputError, match=r"`robots\[1\]\.name`: the team has no robot `three`"):
        session.replan({"robots": [{"name": "one", "lost": True}, {"name": "three", "pose": (1, 1, 0)}]})
    assert session.replan(state).robots[0]["sequence"] == ["gauge-b"], "usable after an error"
    one_robot = tmp_path / "one.toml"
    one_robot.write_text(smug._state_toml({"pose": (3.0, 4.0, 0.0)}))
    with pytest.raises(smug.InputError, match=r"`pose`: this is one robot's state, but the config plans for a team"):
        smug.replan(config, one_robot)
