"""SMUG: safe multi-goal planning for mobile robots, from Python.

A thin layer over the Rust library: a config is loaded, the pipeline assembled and the
mission planned exactly as ``smug plan`` does, so the same config and seed give the same
plan. Planning releases the GIL.

>>> import smug
>>> plan = smug.plan("configs/lunar.toml", seed=1)
>>> plan.cost, plan.waypoints.shape          # doctest: +SKIP
(83.4..., (143, 4))

Arrays follow the grid's layout: shape ``(ny, nx)``, row ``j`` at
``y = origin_y + (j + 0.5) * resolution``, column ``i`` at ``x = origin_x + (i + 0.5) * resolution``
(row 0 is the *bottom* of the map; flip with ``np.flipud`` to draw an image top-down, or use
``origin="lower"`` in matplotlib).
"""

from __future__ import annotations

import json
import math
import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _smug
from ._smug import ConfigError, InputError, NoSolution, SmugError

__all__ = [
    "ConfigError",
    "InputError",
    "NoSolution",
    "Plan",
    "Session",
    "SmugError",
    "World",
    "load_world",
    "p2p",
    "plan",
    "replan",
    "plugins",
    "sweep",
    "sweep_rows",
    "sweep_task",
]

__version__: str = _smug.__version__

PathLike = Union[str, "os.PathLike[str]"]
Overrides = Union[Mapping[str, Any], Sequence[str], None]
Traversability = Callable[[np.ndarray, float], np.ndarray]


def _toml_value(value: Any) -> str:
    """A Python value as a TOML literal for a ``--set KEY=VALUE`` override."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        value = float(value)
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{k} = {_toml_value(v)}" for k, v in value.items()) + " }"
    raise TypeError(f"set: cannot write {type(value).__name__} {value!r} as a TOML value")


def _overrides(set: Overrides) -> List[str]:
    """``{"planner.params.max_stall": 5}`` or ``["planner.params.max_stall=5"]`` as CLI overrides."""
    if set is None:
        return []
    if isinstance(set, Mapping):
        return [f"{key}={_toml_value(value)}" for key, value in set.items()]
    if isinstance(set, str):
        return [set]
    return [str(item) for item in set]


class World:
    """A world: elevation (and traversability) layers and a mission.

    Build one with :meth:`World.from_arrays`, or get a config's world with
    :func:`load_world` or :attr:`Plan.world`.
    """

    __slots__ = ("_native",)

    def __init__(self, native: "_smug.World") -> None:
        self._native = native

    @classmethod
    def from_arrays(
        cls,
        elevation: np.ndarray,
        resolution: float,
        origin: Tuple[float, float] = (0.0, 0.0),
        traversability: Optional[np.ndarray] = None,
        occupancy: Optional[np.ndarray] = None,
        *,
        mission: Mapping[str, Any],
        obstacle_height: float = 2.0,
        name: str = "arrays",
    ) -> "World":
        """A world from numpy arrays.

        ``elevation``: float32/float64 ``(ny, nx)`` heights in metres (NaN = no data);
        ``resolution``: cell size in metres; ``origin``: the lower-left corner ``(x, y)``;
        ``traversability``: optional ``(ny, nx)`` values in [0, 1] (NaN = unknown);
        ``occupancy``: optional bool ``(ny, nx)``, occupied cells rise ``obstacle_height``
        metres above the elevation (as in the ``map`` world);
        ``mission``: ``{"start": (x, y, yaw), "end": (x, y, yaw) or None,
        "targets": [{"id": str, "position": (x, y[, z]), "pois": [(x, y, yaw), ...]}]}``
        (poses may also be ``{"x":, "y":, "yaw":}`` dicts).

        Raises :class:`InputError` naming the array, its shape or dtype, or the mission
        entry at fault.
        """
        try:
            mission_json = json.dumps(mission, default=_json_default)
        except (TypeError, ValueError) as err:
            raise InputError(f"mission: {err}") from None
        native = _smug.World._from_arrays(
            elevation,
            float(resolution),
            (float(origin[0]), float(origin[1])),
            mission_json,
            traversability,
            occupancy,
            float(obstacle_height),
            name,
        )
        return cls(native)

    @property
    def name(self) -> str:
        """Name in reports."""
        return self._native.name

    @property
    def elevation(self) -> np.ndarray:
        """Terrain height, float32 ``(ny, nx)`` (NaN = no data)."""
        return self._native.elevation

    @property
    def traversability(self) -> Optional[np.ndarray]:
        """Traversability in [0, 1], float32 ``(ny, nx)`` (NaN = unknown), or None."""
        return self._native.traversability

    @property
    def resolution(self) -> float:
        """Cell size, metres."""
        return self._native.resolution

    @property
    def origin(self) -> Tuple[float, float]:
        """Lower-left corner ``(x, y)`` of the map."""
        return self._native.origin

    @property
    def bounds(self) -> Tuple[float, float, float, float]:
        """``(xmin, ymin, xmax, ymax)``."""
        return self._native.bounds

    @property
    def extent(self) -> Tuple[float, float, float, float]:
        """``(xmin, xmax, ymin, ymax)``, for matplotlib's ``imshow(..., origin="lower")``."""
        x0, y0, x1, y1 = self.bounds
        return (x0, x1, y0, y1)

    @property
    def mission(self) -> Dict[str, Any]:
        """The mission as Python data (poses as ``{"x", "y", "yaw"}`` dicts)."""
        return json.loads(self._native._mission_json())

    def __repr__(self) -> str:
        return repr(self._native)

    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]:
        """Pickles the world as its arrays and mission (rebuilt by
        :meth:`from_arrays`); which PoIs the robot could not use is not kept."""
        state = (self.elevation, self.resolution, self.origin, self.traversability)
        return (_world_from_pickle, (*state, self.mission, self.name))


def _world_from_pickle(
    elevation: np.ndarray,
    resolution: float,
    origin: Tuple[float, float],
    traversability: Optional[np.ndarray],
    mission: Dict[str, Any],
    name: str,
) -> World:
    """A world from what :meth:`World.__reduce__` pickled."""
    return World.from_arrays(
        elevation, resolution, origin, traversability, mission=mission, name=name
    )


def _json_default(value: Any) -> Any:
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"{type(value).__name__} {value!r} is not a number, list or dict")


class Plan:
    """A safe multi-goal plan: what ``smug plan`` writes to ``plan.json``."""

    __slots__ = ("_json", "_data", "_run", "waypoints", "world")

    def __init__(
        self,
        text: str,
        waypoints: np.ndarray,
        world: World,
        run: Tuple[str, int] = ("", 0),
    ) -> None:
        self._json = text
        #: ``(config TOML, seed)`` of the run that made the plan (plan.mcap's metadata).
        self._run = run
        self._data: Dict[str, Any] = json.loads(text)
        #: ``(n, 4)`` float64 waypoints ``x, y, z, yaw`` from start to end.
        self.waypoints: np.ndarray = waypoints
        #: The world planned in (with the traversability layer used).
        self.world: World = world

    @property
    def cost(self) -> float:
        """Total cost under the planning objective."""
        return self._data["cost"]

    @property
    def sequence(self) -> List[str]:
        """Target ids in visiting order (a team plan's are per robot: :attr:`robots`)."""
        return self._data.get("sequence", [])

    @property
    def robots(self) -> List[Dict[str, Any]]:
        """A team plan's robots (empty for one robot), as in ``plan.json``: ``{"name",
        "sequence", "pois", "waypoints", "cost", "time", ...}``, with ``"waypoints"`` an
        ``(n, 4)`` float64 array ``x, y, z, yaw``. The team's ``total`` and ``makespan``
        are in :meth:`to_dict`."""
        robots = []
        for robot in self._data.get("robots", []):
            robot = dict(robot)
            points = robot["waypoints"]
            robot["waypoints"] = np.array(points, dtype=np.float64).reshape(-1, 4)
            robots.append(robot)
        return robots

    @property
    def pois(self) -> List[Dict[str, Any]]:
        """The chosen PoI per target: ``{"target", "index", "pose": {"x", "y", "yaw"}}``."""
        return self._data["pois"]

    @property
    def segments(self) -> List[Dict[str, Any]]:
        """The legs ``{"from", "to", "path": {"states", "cost"}}`` from start to end."""
        return self._data["segments"]

    @property
    def metrics(self) -> Dict[str, Any]:
        """Length, cost under every objective, traversability along the plan."""
        return self._data.get("metrics", {})

    @property
    def skipped(self) -> List[str]:
        """Targets left out as unreachable (with ``plan.skip_unreachable = true``)."""
        return self._data.get("skipped", [])

    @property
    def stats(self) -> Dict[str, Any]:
        """Counters and timings."""
        return self._data["stats"]

    def to_dict(self) -> Dict[str, Any]:
        """The plan as Python data (a copy)."""
        return json.loads(self._json)

    def to_json(self) -> str:
        """The plan as JSON, byte for byte what ``smug plan`` writes to ``plan.json``."""
        return self._json

    def to_mcap(self, path: PathLike, append: bool = False) -> None:
        """Writes the plan as ``plan.mcap`` (ROS 2 messages for Foxglove, RViz2 and
        ``ros2 bag play``; see the README), byte for byte what ``smug plan`` writes;
        ``append=True`` adds it after the plans already in the file, as ``smug replan``.
        A team plan puts each robot's path and PoIs on ``/smug/<robot>/plan`` and
        ``/smug/<robot>/pois`` and its pose on ``/tf`` as frame ``<robot>/base_link``.
        """
        config_toml, seed = self._run
        _smug.write_plan_mcap(
            os.fspath(path), self._json, self.world._native, config_toml, seed, append
        )

    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]:
        """Pickles the plan as its JSON, waypoints, world and run (for Ray, Dask and
        process pools)."""
        return (Plan, (self._json, self.waypoints, self.world, self._run))

    def __repr__(self) -> str:
        if "robots" in self._data:
            return (
                f"Plan(team of {len(self._data['robots'])}, {self._data['objective']} "
                f"{self.cost:.3f})"
            )
        return (
            f"Plan(cost={self.cost:.3f}, {len(self.sequence)} targets, "
            f"{len(self.waypoints)} waypoints)"
        )


def plan(
    config: PathLike,
    set: Overrides = None,
    seed: Optional[int] = None,
    world: Optional[World] = None,
    traversability: Optional[Traversability] = None,
    save_roadmap: Optional[PathLike] = None,
) -> Plan:
    """Plans the mission of ``config`` (a pipeline TOML), as ``smug plan`` does.

    ``set``: overrides, ``{"planner.params.max_stall": 5}`` or ``["key=value", ...]``;
    ``seed``: overrides the config's seed; ``world``: plan in this world instead of the
    config's ``[world]``; ``traversability``: a callable ``(elevation, resolution) ->
    array`` used instead of the config's ``[traversability]`` estimator. It gets the
    elevation as float64 ``(ny, nx)`` (NaN = no data) and must return a float32/float64
    array of the same shape with values in [0, 1] (NaN = unknown). ``save_roadmap``: a
    file to save the planner's roadmap to after the mission (``smug plan
    --save-roadmap``), for :func:`replan`'s ``roadmap``; a planner that keeps none
    raises :class:`InputError`.

    Raises :class:`ConfigError` (bad config, key, plugin or parameter), :class:`InputError`
    (unusable map, mission or traversability) or :class:`NoSolution` (unreachable targets);
    each message is the one the CLI prints.
    """
    native_world = world._native if world is not None else None
    text, waypoints, planned_world, run = _smug.plan(
        os.fspath(config),
        _overrides(set),
        seed,
        native_world,
        traversability,
        None if save_roadmap is None else os.fspath(save_roadmap),
    )
    return Plan(text, waypoints, World(planned_world), run)



def replan(
    config: PathLike,
    state: PathLike,
    set: Overrides = None,
    seed: Optional[int] = None,
    roadmap: Optional[PathLike] = None,
) -> Plan:
    """Replans the rest of the mission of ``config`` from the mission state file ``state``
    (TOML: ``pose = [x, y, yaw]``, ``visited``, ``failed_pois``, ``[[obstacles]]``; see
    ``docs/replanning.md``), as ``smug replan`` does. The plan's ``to_dict()["replan"]``
    holds the state it started from and the skipped targets. ``roadmap``: a roadmap file
    saved by :func:`plan` (``save_roadmap``) to start from (``smug replan --roadmap``).
    On a team config the state is a team state (``visited``, ``failed_pois``,
    ``[[obstacles]]`` and one ``[[robots]]`` entry per robot: ``name`` and ``pose``, or
    ``lost = true``; see ``docs/teams.md``): the robots not lost share the targets left.

    Raises :class:`ConfigError` (bad config), :class:`InputError` (bad state: the message
    names the file and the key; a roadmap file for another world, robot or config, or a
    damaged one: the message names the file and why) or :class:`NoSolution` (no
    reachable target left).
    """
    text, waypoints, planned_world, run = _smug.replan(
        os.fspath(config),
        os.fspath(state),
        _overrides(set),
        seed,
        None if roadmap is None else os.fspath(roadmap),
    )
    return Plan(text, waypoints, World(planned_world), run)


State = Union[PathLike, Mapping[str, Any]]


def _state_toml(state: Mapping[str, Any]) -> str:
    """A mission state given as Python data (the keys of the state file) as TOML."""
    lines = []
    for key in ("pose", "visited", "failed_pois"):
        if key in state:
            lines.append(f"{key} = {_toml_value(list(state[key]))}")
    tables = ("obstacles", "robots")
    for key in state:
        if key not in ("pose", "visited", "failed_pois") + tables:
            lines.append(f"{key} = {_toml_value(state[key])}")
    for table in tables:
        for entry in state.get(table, []):
            lines.append(f"[[{table}]]")
            lines.extend(f"{k} = {_toml_value(v)}" for k, v in entry.items())
    return "\n".join(lines) + "\n"


class Session:
    """A mission session kept in memory: the pipeline of ``config`` (world, checkers,
    planner with its roadmap, the paths planned) assembled once, the mission planned
    with :meth:`plan`, then replanned in place with :meth:`replan` for each mission state
    (new obstacles applied only where they reach, paths they do not touch reused; see
    ``docs/replanning.md``). What a robot runs onboard: replans take a fraction of a
    replan from scratch.

    >>> session = smug.Session("configs/lunar.toml", seed=1)   # doctest: +SKIP
    >>> plan = session.plan()                                   # = smug.plan(...)
    >>> later = session.replan({"pose": (3.0, 4.0, 0.0), "visited": ["stone-1"]})

    On a team config the session keeps every robot's pipeline and roadmap, and
    :meth:`replan` takes a team state: ``{"visited": [...], "robots": [{"name":
    "anymal", "pose": (x, y, yaw)}, {"name": "rover", "lost": True}]}`` (a lost robot's
    targets go to the others; a state with other obstacles than the last one builds the
    team again on the updated world).
    """

    __slots__ = ("_native",)

    def __init__(self, config: PathLike, set: Overrides = None, seed: Optional[int] = None) -> None:
        self._native = _smug.Session(os.fspath(config), _overrides(set), seed)

    def plan(self) -> Plan:
        """Plans the whole mission, as :func:`plan` does (the same plan)."""
        text, waypoints, world, run = self._native.plan()
        return Plan(text, waypoints, World(world), run)

    def replan(self, state: State) -> Plan:
        """Replans the rest of the mission from ``state``: a state file, or a dict with its
        keys (``pose``, ``visited``, ``failed_pois``, ``obstacles`` as a list of
        ``{"center": (x, y), "radius": r, "height": h}``; for a team, ``robots`` as a
        list of ``{"name", "pose"}`` or ``{"name", "lost": True}``). Obstacles accumulate: a state
        lists every obstacle the session applied before first, in the same order, then
        the new ones.

        Raises :class:`InputError` (bad state, naming the key; an applied obstacle
        missing) or :class:`NoSolution` (no reachable target left); the session stays
        usable after an error.
        """
        if isinstance(state, Mapping):
            text, name = _state_toml(state), "mission state"
        else:
            with open(os.fspath(state), encoding="utf-8") as f:
                text, name = f.read(), os.fspath(state)
        text, waypoints, world, run = self._native.replan(text, name)
        return Plan(text, waypoints, World(world), run)

    @property
    def obstacles(self) -> List[Tuple[float, float, float, float]]:
        """The obstacles applied so far, as ``(x, y, radius, height)``."""
        return self._native.obstacles()

    @property
    def known_paths(self) -> int:
        """How many paths the session keeps from earlier plans (each direction counts)."""
        return self._native.known_paths()

def load_world(config: PathLike, set: Overrides = None, seed: Optional[int] = None) -> World:
    """The world of ``config`` with its traversability layer, without planning."""
    return World(_smug.load_world(os.fspath(config), _overrides(set), seed))


def plugins() -> List[Dict[str, Any]]:
    """Every registered plugin by stage, as ``smug plugins --json`` prints it:
    ``[{"stage", "summary", "plugins": [{"name", "summary", "params"}]}]``."""
    return json.loads(_smug.plugins_json())


def p2p(
    queries: Union[np.ndarray, Sequence[Sequence[float]]],
    config: Optional[PathLike] = None,
    set: Overrides = None,
    world: Optional[World] = None,
    map: Optional[PathLike] = None,
    obstacle_height: float = 2.0,
) -> Dict[str, Any]:
    """Point-to-point queries on one shared roadmap, in order, as ``smug p2p`` does.

    ``queries``: ``(n, 6)`` rows ``sx, sy, syaw, gx, gy, gyaw``; ``config``: the pipeline
    (default: the CLI's ``configs/p2p-grid.toml``, a disc robot on an occupancy grid);
    ``world`` or ``map`` (a map_server YAML): where to plan (default: the config's world).
    Returns ``{"queries": [{"status", "no_path", "why", "cost", "time_s", "vertices",
    "waypoints"}], "total_time_s", "planner"}``, the JSON ``smug p2p --out`` writes;
    ``no_path`` is ``"proved"`` (no path exists) or ``"budget_spent"`` (one may exist)
    for a ``no_path`` status, else ``None``, and ``why`` its cause (``"disconnected"``,
    ``"samples"``, ``"time"``, …).
    """
    array = np.asarray(queries, dtype=np.float64)
    if array.ndim == 1 and array.size == 6:
        array = array.reshape(1, 6)
    text = _smug.p2p(
        array,
        os.fspath(config) if config is not None else None,
        _overrides(set),
        world._native if world is not None else None,
        os.fspath(map) if map is not None else None,
        float(obstacle_height),
    )
    return json.loads(text)


from ._sweep import sweep, sweep_rows, sweep_task  # noqa: E402  (they use the helpers above)
