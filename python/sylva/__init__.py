"""Sylva: non-photorealistic renders of trees and plants from Python (docs/python.md).

    import sylva
    scene = sylva.load("tree.glb")             # or sylva.sample("tree", seed=1)
    img = sylva.render(scene, "ink", size=(512, 512), params={"ink.detail": 6})
    sylva.save(img, "tree.png", dpi=300)      # img: H x W x 4 uint8 RGBA numpy array

Renders of one Scene run one at a time (a lock per Scene); different Scenes, each with its own
GL context, render in parallel from several threads (the GIL is released while rendering).
"""
import os as _os
import tempfile as _tempfile

from . import _config

# The codecs plugin (TIFF, JPEG output, MP4) is found beside the sylva executable; Python is not
# it, so name the plugin this package was built or installed with, unless the user chose one.
if not _os.environ.get("SYLVA_CODECS") and _os.path.exists(_config.CODECS):
    _os.environ["SYLVA_CODECS"] = _config.CODECS

from ._sylva import (Scene, Turntable, buffers, load, render, sample, save,  # noqa: E402
                     save_video, style, styles, turntable)

__all__ = ["Scene", "Turntable", "Image", "buffers", "load", "render", "sample", "save",
           "save_video", "style", "styles", "turntable"]


class Image:
    """An RGBA array that shows itself in Jupyter (_repr_png_, encoded by sylva.save):
    `sylva.Image(sylva.render(scene, "ink"))` as a cell's last line."""

    def __init__(self, array):
        self.array = array

    def __array__(self, dtype=None):
        return self.array if dtype is None else self.array.astype(dtype)

    def _repr_png_(self):
        with _tempfile.TemporaryDirectory() as folder:
            path = _os.path.join(folder, "image.png")
            save(self.array, path)
            with open(path, "rb") as f:
                return f.read()
