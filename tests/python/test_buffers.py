"""sylva.buffers gives what `sylva buffers --format exr` writes, read back through OpenImageIO:
normals, depth, positions, ka and ids exactly, and the camera of the file's header."""
import numpy as np
import OpenImageIO as oiio

import sylva
from conftest import run_cli

NAMES = ["normal", "depth", "position", "id", "ka"]
CHANNELS = {"normal": ["N.X", "N.Y", "N.Z"], "depth": ["Z"], "position": ["P.X", "P.Y", "P.Z"],
            "id": ["id"], "ka": ["ka"]}


def read_exr(path):
    """The header and every channel as stored (float, or uint for the ids: OpenImageIO would
    normalise them read as float)."""
    inp = oiio.ImageInput.open(str(path))
    assert inp, oiio.geterror()
    spec = inp.spec()
    channels = {}
    for i, name in enumerate(spec.channelnames):
        kind = "uint" if spec.channelformat(i) == oiio.UINT else "float"
        channels[name] = inp.read_image(0, 0, i, i + 1, kind)[:, :, 0]
    inp.close()
    return spec, channels


def test_buffers_equal_the_cli_exr(tree, tree_glb, tmp_path):
    view = dict(style="expressive", size=(96, 80), azimuth=50, id="cluster")
    first = sylva.buffers(tree, NAMES, **view)
    sylva.render(tree, "expressive", size=(96, 80), azimuth=50)
    got = sylva.buffers(tree, NAMES, **view)  # the preprocessing kept on the scene
    for name in NAMES:
        assert np.array_equal(first[name], got[name]), name
    run_cli("buffers", tree_glb, "--style", "expressive", "--size", "96x80", "--azimuth", 50,
            "--id", "cluster", "--buffers", ",".join(NAMES), "--format", "exr",
            "--cryptomatte", "none", "--out-dir", tmp_path / "b")
    spec, channels = read_exr(tmp_path / "b" / "buffers.exr")
    assert got["normal"].shape == (80, 96, 3) and got["normal"].dtype == np.float32
    assert got["depth"].shape == (80, 96) and got["id"].dtype == np.uint32
    for name in NAMES:
        expected = np.stack([channels[c] for c in CHANNELS[name]], axis=-1)
        assert np.array_equal(got[name].reshape(expected.shape), expected), name
        assert expected.dtype == (np.uint32 if name == "id" else np.float32), name
    assert np.count_nonzero(got["depth"]) > 0 and len(np.unique(got["id"])) > 2
    # Imath's row-vector worldToCamera is the transpose of the column-vector view matrix.
    world_to_camera = np.array(spec.getattribute("worldToCamera"), dtype=np.float32).reshape(4, 4)
    assert np.allclose(world_to_camera.T, got["camera"]["view"], atol=1e-6)
    assert got["camera"]["width"] == 96 and got["camera"]["height"] == 80


def test_color_buffer_is_rgba(tree):
    got = sylva.buffers(tree, ["color"], size=64)
    render = sylva.render(tree, "standard", size=64)
    assert got["color"].shape == (64, 64, 4) and got["color"].dtype == np.uint8
    assert np.array_equal(got["color"][:, :, 3] > 0, render[:, :, 3] > 0)
