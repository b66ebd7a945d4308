"""Errors are Python exceptions carrying the CLI's one line: ValueError for bad values and
unknown keys (naming the key and what is allowed), FileNotFoundError for a missing file,
ValueError for a broken one, TypeError for an unknown keyword."""
import math

import pytest

import sylva
from conftest import cli_error, run_cli


def raised(kind, call):
    with pytest.raises(kind) as info:
        call()
    return str(info.value)


@pytest.mark.parametrize("params,option", [
    ({"ink.nope": 1}, "ink.nope=1"),
    ({"ink.detail": 1000}, "ink.detail=1000"),
    ({"ink.detail": -1.5}, "ink.detail=-1.5"),
    ({"ink.detail": math.nan}, "ink.detail=nan"),
    ({"edges.width": "wide"}, "edges.width=wide"),
])
def test_bad_params_raise_the_cli_message(tree, tree_glb, tmp_path, params, option):
    message = raised(ValueError, lambda: sylva.render(tree, "ink", size=32, params=params))
    key = option.split("=")[0]
    assert key in message
    assert message == cli_error("render", tree_glb, "--style", "ink", "--size", 32, "--set",
                                option, "-o", tmp_path / "x.png")


@pytest.mark.parametrize("view,options", [
    ({"size": (0, 10)}, ["--size", "0x10"]),
    ({"size": 20000}, ["--size", "20000"]),
    ({"elevation": 120}, ["--elevation", 120]),
    ({"background": "pink"}, ["--background", "pink"]),
    ({"ssaa": 9}, ["--ssaa", 9]),
    ({"camera": "nope"}, ["--camera", "nope"]),
])
def test_bad_view_values_raise_the_cli_message(tree, tree_glb, tmp_path, view, options):
    args = {"size": 32, **view}
    message = raised(ValueError, lambda: sylva.render(tree, "standard", **args))
    size = [] if "size" in view else ["--size", 32]
    assert message == cli_error("render", tree_glb, *size, *options, "-o", tmp_path / "x.png")


def test_a_nan_angle_is_refused(tree):
    assert "--azimuth" in raised(ValueError, lambda: sylva.render(tree, size=32, azimuth=math.nan))


def test_an_unknown_style_names_the_styles(tree, tree_glb, tmp_path):
    message = raised(ValueError, lambda: sylva.render(tree, "nope", size=32))
    assert "ink" in message
    assert message == cli_error("render", tree_glb, "--style", "nope", "-o", tmp_path / "x.png")


def test_a_missing_file(tmp_path):
    path = tmp_path / "missing.glb"
    message = raised(FileNotFoundError, lambda: sylva.load(str(path)))
    assert message == cli_error("info", path)
    assert isinstance(FileNotFoundError(), OSError)


def test_a_broken_glb(tmp_path):
    path = tmp_path / "broken.glb"
    path.write_bytes(b"glTF\x02\x00\x00\x00" + b"\x00" * 40)
    message = raised(ValueError, lambda: sylva.load(str(path)))
    assert str(path) in message
    assert message == cli_error("info", path)


def test_svg_of_a_style_without_lines(tree, tree_glb, tmp_path):
    message = raised(ValueError, lambda: sylva.render(tree, "toon", size=32, format="svg"))
    assert "ink" in message and "pen" in message


def test_unknown_buffer_and_keyword(tree, tree_glb, tmp_path):
    message = raised(ValueError, lambda: sylva.buffers(tree, ["nope"], size=32))
    assert message == cli_error("buffers", tree_glb, "--buffers", "nope", "--out-dir",
                                tmp_path / "b")
    assert "azimut" in raised(TypeError, lambda: sylva.render(tree, size=32, azimut=3))
    assert "ssaa" in raised(TypeError, lambda: sylva.render(tree, size=32, ssaa=2.5))
    assert "params" in raised(TypeError, lambda: sylva.render(tree, size=32, params=["x"]))


def test_save_checks_its_input(tmp_path):
    import numpy as np
    assert "uint8" in raised(ValueError, lambda: sylva.save(np.zeros((4, 4, 4), np.float32),
                                                            str(tmp_path / "x.png")))
    assert "dpi" in raised(ValueError, lambda: sylva.save(np.zeros((4, 4, 4), np.uint8),
                                                          str(tmp_path / "x.png"), dpi=-1))


def test_the_loaders_warnings_are_python_warnings(tmp_path):
    path = tmp_path / "w.off"
    path.write_text("OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 9\n")
    with pytest.warns(UserWarning) as caught:
        sylva.load(str(path))
    cli = run_cli("render", path, "--size", 16, "-o", tmp_path / "w.png").stderr
    expected = [line[len("sylva: warning: "):] for line in cli.splitlines()
                if line.startswith("sylva: warning: ")]
    assert expected and [str(w.message) for w in caught] == expected
