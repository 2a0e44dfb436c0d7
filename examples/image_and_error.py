"""Render a scene and show the image beside a map of its error against a reference.

    PYTHONPATH=build/python python3 examples/image_and_error.py [SCENE] [-o OUT.png]

The error map is each pixel's relative squared error, (x - r)^2 / (r^2 + 0.01) averaged over
the channels (its share of relMSE), on a log scale; the reference is a long path-traced render.
"""

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.colors
import matplotlib.pyplot as plt
import numpy as np

import erpt

ROOT = pathlib.Path(__file__).resolve().parents[1]

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("scene", nargs="?", default=str(ROOT / "scenes" / "default" / "scene.xml"))
parser.add_argument("--integrator", default="erpt")
parser.add_argument("--spp", type=int, default=8)
parser.add_argument("--size", type=int, default=128)
parser.add_argument("-o", "--output", default="image_and_error.png")
args = parser.parse_args()

scene = erpt.load_scene(args.scene)
size = {"width": args.size, "height": args.size}
result = erpt.render(scene, args.integrator, spp=args.spp, seed=1, progress=lambda f: print(f"\r{f:4.0%}", end=""), **size)
print()
reference = erpt.render(scene, "path", spp=512, seed=2, **size).image
metrics = erpt.diff(result.image, reference)

error = np.mean((result.image - reference) ** 2 / (reference**2 + 0.01), axis=2)
fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.6), constrained_layout=True)
left.imshow(np.clip(result.image, 0, 1) ** (1 / 2.2))
left.set_title(f"{args.integrator}, {args.spp} spp, {result.stats['seconds']:.2f} s")
shown = right.imshow(np.maximum(error, 1e-6), cmap="inferno", norm=matplotlib.colors.LogNorm(1e-5, 1))
right.set_title(f"relative squared error (relMSE {metrics['rel_mse']:.3g})")
fig.colorbar(shown, ax=right)
for ax in (left, right):
    ax.axis("off")
fig.savefig(args.output, dpi=100)
print("wrote", args.output)
