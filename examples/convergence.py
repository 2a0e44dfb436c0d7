"""Render a scene with three integrators for the same time each and plot their convergence.

    PYTHONPATH=build/python python3 examples/convergence.py [SCENE] [--time SECONDS] [-o OUT.png]

Without a reference of its own, a long path-traced render of the same scene serves as one.
"""

import argparse
import pathlib

import erpt
import erpt.plot

ROOT = pathlib.Path(__file__).resolve().parents[1]

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("scene", nargs="?", default=str(ROOT / "scenes" / "default" / "scene.xml"))
parser.add_argument("--reference", help="a converged image of the scene at --size (default: rendered here)")
parser.add_argument("--size", type=int, default=96)
parser.add_argument("--time", type=float, default=4.0, help="seconds per integrator")
parser.add_argument("-o", "--output", default="convergence.png")
args = parser.parse_args()

scene = erpt.load_scene(args.scene)
size = {"width": args.size, "height": args.size}
reference = args.reference or erpt.render(scene, "path", spp=1024, seed=99, **size).image
rows = erpt.compare(scene, reference, integrators=["path", "erpt", ("mlt", {"mutations_per_pixel": 64})],
                    time=args.time, **size)
for row in rows:
    print(f"{row['integrator']:32s} {row['seconds']:6.2f} s  relMSE {row['rel_mse']:.4g}  "
          f"Eff_rel {row['eff_rel']:.4g}  ({len(row['curve'])} passes)")
erpt.plot.plot_compare(rows, args.output, title=f"{pathlib.Path(args.scene).parent.name}, {args.time:g} s each")
print("wrote", args.output)
