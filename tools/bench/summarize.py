#!/usr/bin/env python3
"""The peers bench's CSVs as the tables of docs/results/speed.md.

    python3 tools/bench/summarize.py RUN1/peers.csv [RUN2/peers.csv ...]

For each size, one row per mesh and cull: zline z24's median (ms) in the
first run and every other renderer's ratio (its median over zline z24's,
a drawtarget row's over zline in place at its depth; above 1.00 zline is
faster), where several runs are given the one worse for zline (a peer's
lower ratio, a drawtarget row's higher). Then, for
all runs: how many peer rows are at or below 1.00, against zline z24 and
z16, and the largest drawtarget ratio. The wrong-face shares come from the
first run's `peers_wrong_faces.csv` beside its CSV (a share of the
object's pixels). Runs of `--shading gouraud,textured` give a Gouraud and
a texture-mapping table instead (zline's median at each size, each
peer's ratio at each size).
"""

import csv
import os
import sys

PEERS = ["embedded-3dgfx lit", "embedded-3dgfx unlit", "embedded-3dgfx raster shared", "euc"]
SHORT = {
    "zline z16": "z16",
    "zline z24 drawtarget": "z24 DT",
    "zline z16 drawtarget": "z16 DT",
    "zline z24 target alone": "target alone",
    "embedded-3dgfx lit": "e3d lit",
    "embedded-3dgfx unlit": "e3d unlit",
    "embedded-3dgfx raster shared": "e3d raster shared",
    "euc": "euc",
}


def load(path):
    rows = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            rows[(r["mesh"], r["size"], r["cull"], r["renderer"])] = r
    return rows


def wrong(path):
    stem = os.path.splitext(path)[0]
    out = {}
    try:
        with open(stem + "_wrong_faces.csv", newline="") as f:
            for r in csv.DictReader(f):
                out[(r["mesh"], r["size"], r["cull"], r["renderer"])] = float(r["wrong_fraction"])
    except FileNotFoundError:
        pass
    return out


def main(paths):
    if not paths or paths[0] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if paths else 2
    runs = [load(p) for p in paths]
    if any(key[3] == "zline gouraud z24" for key in runs[0]):
        return shading(runs)
    first = runs[0]
    wrongs = wrong(paths[0])
    configs = sorted({k[:3] for k in first}, key=lambda c: (c[1], c[0], c[2]))
    sizes = sorted({c[1] for c in configs}, key=lambda s: [int(x) for x in s.split("x")])
    columns = list(SHORT)

    def ratio(config, renderer):
        values = [float(r[config + (renderer,)]["ratio"]) for r in runs if config + (renderer,) in r]
        if not values:
            return None
        # The runs' worse figure for zline: a peer's lower ratio, a
        # drawtarget row's higher one.
        return max(values) if renderer.endswith("drawtarget") else min(values)

    for size in sizes:
        print(f"\n{size}: zline z24's median (ms), then each row's ratio"
              + (f", the worse for zline of {len(runs)} runs (a peer's lower, a drawtarget's higher)"
                 if len(runs) > 1 else "")
              + "; e3d wrong faces: raster shared's share of the object's pixels\n")
        print("| mesh | cull | zline z24 ms | " + " | ".join(SHORT[c] for c in columns) + " | e3d wrong |")
        print("|---|---|---:|" + "---:|" * len(columns) + "---:|")
        for config in (c for c in configs if c[1] == size):
            z24 = first.get(config + ("zline z24",))
            if z24 is None:
                continue
            cells = []
            for c in columns:
                r = ratio(config, c)
                text = "–" if r is None else f"{r:.2f}"
                if r is not None and c in PEERS and r <= 1.0:
                    text = f"**{text}**"
                cells.append(text)
            w = wrongs.get(config + ("embedded-3dgfx raster shared",))
            print(f"| {config[0]} | {config[2]} | {float(z24['median_ms']):.3f} | " + " | ".join(cells)
                  + f" | {'–' if w is None else f'{100 * w:.0f} %'} |")

    print()
    for k, run in enumerate(runs):
        base, ratios = {}, {}
        for key, r in run.items():
            base.setdefault(key[:3], {})[key[3]] = float(r["median_ms"])
            ratios.setdefault(key[:3], {})[key[3]] = float(r["ratio"])
        for depth in ("z24", "z16"):
            at_or_below, total, worst = 0, 0, (9.9, None)
            for config, times in base.items():
                z = times.get(f"zline {depth}")
                if not z:
                    continue
                for p in PEERS:
                    if p in times:
                        total += 1
                        # Against z24 the bench's own ratio, from medians
                        # at full precision (the CSV's medians have three
                        # decimals: 0.007 ms against 0.007 ms would count
                        # as a tie); against z16 the medians' ratio.
                        r = ratios[config][p] if depth == "z24" else times[p] / z
                        if r <= 1.0:
                            at_or_below += 1
                        if r < worst[0]:
                            worst = (r, (p,) + config)
            print(f"- run {k + 1}, against zline {depth}: {at_or_below} of {total} peer rows at or below 1.00;"
                  f" lowest {worst[0]:.2f} ({' '.join(worst[1]) if worst[1] else '-'})")
        dt = [(float(r["ratio"]), key) for key, r in run.items() if key[3].endswith("drawtarget")]
        if dt:
            top = max(dt)
            print(f"- run {k + 1}: largest drawtarget over in place {top[0]:.2f} ({' '.join(top[1])});"
                  f" {sum(1 for v, _ in dt if v <= 1.10)} of {len(dt)} within 1.10")
    return 0


SHADED = [
    ("Gouraud", "zline gouraud z24", ["embedded-3dgfx gouraud", "euc gouraud"]),
    ("Texture mapping", "zline textured z24", ["embedded-3dgfx textured", "euc textured"]),
]


def shading(runs):
    """The `--shading gouraud,textured` runs: per mode, one row per mesh
    and cull with zline's median at each size (first run) and each peer's
    ratio at each size, the worse for zline of the runs."""
    first = runs[0]
    sizes = sorted({k[1] for k in first}, key=lambda s: [int(x) for x in s.split("x")])
    for title, ours, peers in SHADED:
        configs = sorted({(k[0], k[2]) for k in first if k[3] == ours})
        if not configs:
            continue
        print(f"\n{title}:\n")
        print("| mesh | cull | zline ms (" + " / ".join(sizes) + ") | "
              + " | ".join(p.split(" ")[0] for p in peers) + " |")
        print("|---|---|---|" + "---|" * len(peers))
        low, total = [0] * len(runs), 0
        for mesh, cull in configs:
            ms = " / ".join(f"{float(first[(mesh, s, cull, ours)]['median_ms']):.2f}"
                            if (mesh, s, cull, ours) in first else "–" for s in sizes)
            cells = []
            for p in peers:
                parts = []
                for s in sizes:
                    key = (mesh, s, cull, p)
                    values = [float(r[key]["ratio"]) for r in runs if key in r]
                    if not values:
                        parts.append("–")
                        continue
                    total += 1
                    for k, r in enumerate(runs):
                        if key in r and float(r[key]["ratio"]) <= 1.0:
                            low[k] += 1
                    v = min(values)
                    parts.append(f"**{v:.2f}**" if v <= 1.0 else f"{v:.2f}")
                cells.append(" / ".join(parts))
            print(f"| {mesh} | {cull} | {ms} | " + " | ".join(cells) + " |")
        print(f"\n({title}: peer rows at or below 1.00: "
              + ", ".join(f"run {k + 1} {n} of {total}" for k, n in enumerate(low)) + ")")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
