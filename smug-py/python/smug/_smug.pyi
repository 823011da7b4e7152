"""Type stubs of the native module ``smug._smug`` (use the ``smug`` package's API)."""

from typing import Any, Callable, List, Optional, Tuple

import numpy as np

__version__: str

class SmugError(Exception):
    """Base class of every error SMUG raises."""

class ConfigError(SmugError):
    """A bad config: file, key, plugin name or parameter (the CLI's exit 2)."""

class InputError(SmugError):
    """Unusable input data: a map, mission, array or traversability layer (the CLI's exit 2)."""

class NoSolution(SmugError):
    """The pipeline ran but no safe plan exists (the CLI's exit 1)."""

class World:
    """A world: elevation (and traversability) layers and a mission."""

    @staticmethod
    def _from_arrays(
        elevation: np.ndarray,
        resolution: float,
        origin: Tuple[float, float],
        mission_json: str,
        traversability: Optional[np.ndarray] = None,
        occupancy: Optional[np.ndarray] = None,
        obstacle_height: float = 2.0,
        name: str = "arrays",
    ) -> World: ...
    @property
    def name(self) -> str: ...
    @property
    def elevation(self) -> np.ndarray: ...
    @property
    def traversability(self) -> Optional[np.ndarray]: ...
    @property
    def resolution(self) -> float: ...
    @property
    def origin(self) -> Tuple[float, float]: ...
    @property
    def bounds(self) -> Tuple[float, float, float, float]: ...
    def _mission_json(self) -> str: ...

def plan(
    config: str,
    set: List[str] = ...,
    seed: Optional[int] = None,
    world: Optional[World] = None,
    traversability: Optional[Callable[[np.ndarray, float], Any]] = None,
    save_roadmap: Optional[str] = None,
) -> Tuple[str, np.ndarray, World, Tuple[str, int]]: ...
def replan(
    config: str,
    state: str,
    set: List[str] = ...,
    seed: Optional[int] = None,
    roadmap: Optional[str] = None,
) -> Tuple[str, np.ndarray, World, Tuple[str, int]]: ...

class Session:
    """A mission session kept in memory across replans."""

    def __init__(self, config: str, set: List[str] = ..., seed: Optional[int] = None) -> None: ...
    def plan(self) -> Tuple[str, np.ndarray, World, Tuple[str, int]]: ...
    def replan(self, state: str, name: str) -> Tuple[str, np.ndarray, World, Tuple[str, int]]: ...
    def obstacles(self) -> List[Tuple[float, float, float, float]]: ...
    def known_paths(self) -> int: ...

def write_plan_mcap(
    path: str, plan_json: str, world: World, config_toml: str, seed: int, append: bool = False
) -> None: ...
def load_world(config: str, set: List[str] = ..., seed: Optional[int] = None) -> World: ...
def plugins_json() -> str: ...
def p2p(
    queries: np.ndarray,
    config: Optional[str] = None,
    set: List[str] = ...,
    world: Optional[World] = None,
    map: Optional[str] = None,
    obstacle_height: float = 2.0,
) -> str: ...
def sweep_runs(
    configs: List[str], seeds: List[int], grid: List[Tuple[str, List[str]]]
) -> List[Tuple[str, str, List[str], int]]: ...
def sweep_seeds(text: str) -> List[int]: ...
def sweep_task(
    config: str, seed: int, overrides: List[str], threads: Optional[int] = 1
) -> str: ...
def sweep_failed_row(config: str, seed: int, overrides: List[str], message: str) -> str: ...
