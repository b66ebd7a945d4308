#!/usr/bin/python3
"""A parameter sweep as a contact sheet: one loaded scene rendered in `ink` at eight values of
ink.detail (the foliage preprocessing and the upload are paid once), laid out with matplotlib.

    PYTHONPATH=build/python python3 examples/sweep_contact_sheet.py [SCENE.glb] [sheet.png]
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import sylva  # noqa: E402

scene = sylva.load(sys.argv[1]) if len(sys.argv) > 1 else sylva.sample("tree", seed=1)
out = sys.argv[2] if len(sys.argv) > 2 else "sweep.png"
values = [0.5, 1, 2, 3, 4, 6, 8, 12]
fig, axes = plt.subplots(2, 4, figsize=(12, 6.4))
for ax, detail in zip(axes.flat, values):
    ax.imshow(sylva.render(scene, "ink", size=(384, 384), params={"ink.detail": detail}))
    ax.set_title(f"ink.detail = {detail}")
    ax.axis("off")
fig.tight_layout()
fig.savefig(out, dpi=100)
print("wrote", out)
