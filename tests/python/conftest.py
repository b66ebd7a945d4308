"""Shared fixtures of the sylva module's tests (docs/python.md): the CLI they compare with
(SYLVA_BINARY), the shared assets (SYLVA_SHARED_DIR), a result cache of the session's own, and a
small sample tree written by `sylva sample` and loaded by the module."""
import os
import subprocess
import tempfile

import pytest

_cache = tempfile.TemporaryDirectory(prefix="sylva-pytest-cache-")
os.environ["SYLVA_CACHE_DIR"] = _cache.name  # before sylva reads it, for the CLI runs too

import sylva  # noqa: E402

SYLVA = os.environ.get("SYLVA_BINARY", "sylva")
SHARED = os.environ.get("SYLVA_SHARED_DIR", os.path.join(os.path.dirname(__file__), "../../../shared"))
ASH = os.path.join(SHARED, "assets", "eztree_ash_medium_s5.glb")
LEAVES = 300


def run_cli(*args, check=True):
    """Runs `sylva ARGS`; returns the CompletedProcess (text)."""
    return subprocess.run([SYLVA, *map(str, args)], capture_output=True, text=True, check=check)


def cli_error(*args):
    """The one line `sylva ARGS` prints on bad input, without "sylva: error: " (exit 2)."""
    p = run_cli(*args, check=False)
    assert p.returncode == 2, p.stderr
    line = p.stderr.strip().splitlines()[-1]
    assert line.startswith("sylva: error: "), line
    return line[len("sylva: error: "):]


def read_image(path):
    """An image file's pixels (OpenImageIO), as stored: uint8 RGBA for an 8-bit PNG."""
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(str(path))
    assert inp, oiio.geterror()
    try:
        return inp.read_image(format=inp.spec().format), inp.spec()
    finally:
        inp.close()


@pytest.fixture(scope="session")
def tree_glb(tmp_path_factory):
    path = tmp_path_factory.mktemp("tree") / "tree.glb"
    run_cli("sample", "tree", "--seed", 1, "--leaves", LEAVES, "-o", path)
    return path


@pytest.fixture(scope="session")
def tree(tree_glb):
    return sylva.load(str(tree_glb))


@pytest.fixture(scope="session")
def ash():
    if not os.path.exists(ASH):
        pytest.skip(f"no shared asset {ASH} (SYLVA_SHARED_DIR)")
    return sylva.load(ASH)
