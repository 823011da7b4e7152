"""Plan the lunar mission from Python, plot it, then plug in a numpy traversability.

Run from the repository root after `pip install ./smug-py matplotlib`:

    python smug-py/examples/lunar.py            # writes lunar-python.png

Cells marked `# %%` run one by one in editors that know them (VS Code, Spyder, Jupyter).
"""

# %% Plan the mission the CLI plans: same config, same seed, same plan.
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import smug

config = Path(__file__).resolve().parents[2] / "configs" / "lunar.toml"
plan = smug.plan(config, seed=1)
print(plan, "order:", " → ".join(plan.sequence))

# %% Our own traversability: a numpy function of the elevation (a learned model would
# go here). Slope from finite differences, 1 on flat ground, 0 from 25°.
def slope_traversability(elevation: np.ndarray, resolution: float) -> np.ndarray:
    filled = np.where(np.isnan(elevation), np.nanmean(elevation), elevation)
    gy, gx = np.gradient(filled, resolution)
    slope = np.degrees(np.arctan(np.hypot(gx, gy)))
    t = np.clip(1.0 - slope / 25.0, 0.0, 1.0)
    t[np.isnan(elevation)] = np.nan
    return t


ours = smug.plan(config, seed=1, traversability=slope_traversability)
print(ours, "with the numpy slope estimator")

# %% Plot both on their traversability layers.
fig, axes = plt.subplots(1, 2, figsize=(12, 5.5), sharey=True)
for ax, p, title in [(axes[0], plan, "geometric (config)"), (axes[1], ours, "numpy slope function")]:
    world = p.world
    ax.imshow(world.traversability, origin="lower", extent=world.extent, cmap="RdYlGn", vmin=0, vmax=1)
    for target in world.mission["targets"]:
        ax.plot(target["position"]["x"], target["position"]["y"], "k^", ms=5)
    ax.plot(p.waypoints[:, 0], p.waypoints[:, 1], "b-", lw=1.5)
    start = world.mission["start"]
    ax.plot(start["x"], start["y"], "bo")
    ax.set_title(f"{title}: cost {p.cost:.2f}")
    ax.set_xlabel("x [m]")
axes[0].set_ylabel("y [m]")
fig.tight_layout()
out = Path(sys.argv[1] if len(sys.argv) > 1 else "lunar-python.png")
fig.savefig(out, dpi=110)
print("wrote", out)
