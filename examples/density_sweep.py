"""A density sweep in a few lines, plotted with matplotlib: contacts per plant before resolution
and leaf area index against density, one curve per age. Run from the repository root after
`bash scripts/python.sh`:   /usr/bin/python3 examples/density_sweep.py  (writes density_sweep.png)"""
import collections

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import canopy

canopy.sweep("grammars/tomato.yaml", "sweep_py", density=[1.5, 2, 2.5, 3, 4], steps=[16, 22], seeds=2,
             progress=lambda i, n, row: print(f"run {i + 1}/{n}: density {row['density']}, LAI {row['lai']}"))
cells = collections.defaultdict(list)
for row in canopy.sweep_rows("sweep_py", summary=True):
    cells[int(row["steps"])].append(row)

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
for steps, rows in sorted(cells.items()):
    rows.sort(key=lambda r: r["density"])
    d = [r["density"] for r in rows]
    ax1.errorbar(d, [r["exact_between_per_plant_mean"] + r["exact_within_per_plant_mean"] for r in rows],
                 yerr=[r["exact_between_per_plant_sd"] for r in rows], marker="o", label=f"age {steps} steps")
    ax2.errorbar(d, [r["lai_mean"] for r in rows], yerr=[r["lai_sd"] for r in rows], marker="o", label=f"age {steps} steps")
ax1.set(xlabel="plants per m²", ylabel="organ contacts per plant (before resolution)")
ax2.set(xlabel="plants per m²", ylabel="leaf area index")
for ax in (ax1, ax2):
    ax.grid(True)
    ax.legend()
fig.tight_layout()
fig.savefig("density_sweep.png", dpi=100)
print("wrote density_sweep.png")
