"""sylva.render gives the bytes `sylva render ... -o x.png` writes, for every built-in style, on a
sample tree and a shared tree; sylva.sample is the tree `sylva sample` writes; SVG output is the
CLI's .svg; turntable frame 0 is the render from the same view."""
import numpy as np
import pytest

import sylva
from conftest import LEAVES, read_image, run_cli

SIZE = 128
STYLES = sorted(sylva.styles())


def cli_png(scene_path, style, tmp_path, *extra):
    out = tmp_path / f"{style}.png"
    run_cli("render", scene_path, "--style", style, "--size", SIZE, *extra, "-o", out)
    pixels, spec = read_image(out)
    assert spec.nchannels == 4 and pixels.dtype == np.uint8
    return pixels


def assert_same(img, expected):
    assert img.shape == expected.shape and img.dtype == np.uint8
    differing = int(np.count_nonzero(np.any(img != expected, axis=2)))
    assert differing == 0, f"{differing} of {img.shape[0] * img.shape[1]} pixels differ"


def test_the_styles_are_listed():
    assert {"standard", "expressive", "ink", "pen", "toon", "watercolor", "blobs"} <= set(STYLES)


@pytest.mark.parametrize("style", STYLES)
def test_render_equals_cli_on_a_sample(tree, tree_glb, style, tmp_path):
    img = sylva.render(tree, style, size=(SIZE, SIZE))
    assert img.shape == (SIZE, SIZE, 4)
    assert img.base is not None  # a view over the rendered image, not a copy
    assert_same(img, cli_png(tree_glb, style, tmp_path))


@pytest.mark.parametrize("style", STYLES)
def test_render_equals_cli_on_the_ash(ash, style, tmp_path):
    img = sylva.render(ash, style, size=SIZE)
    assert_same(img, cli_png(ash.source, style, tmp_path))


def test_view_and_params_as_the_cli_options(tree, tree_glb, tmp_path):
    img = sylva.render(tree, "ink", size=(160, 96), azimuth=75, elevation=5, background="#203040",
                       params={"ink.detail": 4, "edges.width": 1.5})
    out = tmp_path / "view.png"
    run_cli("render", tree_glb, "--style", "ink", "--size", "160x96", "--azimuth", 75,
            "--elevation", 5, "--background", "#203040", "--set", "ink.detail=4",
            "--set", "edges.width=1.5", "-o", out)
    assert_same(img, read_image(out)[0])
    assert not np.array_equal(img, sylva.render(tree, "ink", size=(160, 96), azimuth=75,
                                                elevation=5, background="#203040"))


def test_sample_is_the_cli_sample(tree):
    sample = sylva.sample("tree", seed=1, leaves=LEAVES)
    assert sample.info()["triangles"] == tree.info()["triangles"]
    assert_same(sylva.render(sample, "ink", size=SIZE), sylva.render(tree, "ink", size=SIZE))
    other = sylva.sample("tree", seed=2, leaves=LEAVES)
    assert not np.array_equal(sylva.render(other, "ink", size=SIZE),
                              sylva.render(tree, "ink", size=SIZE))


def test_a_preset_file_works_as_a_style(tree, tree_glb, tmp_path):
    preset = tmp_path / "mine.toml"
    preset.write_text('inherits = ["ink"]\n[ink]\ndetail = 5\n')
    img = sylva.render(tree, preset, size=SIZE)
    assert_same(img, cli_png(tree_glb, str(preset), tmp_path))
    assert sylva.style(preset)["params"]["ink.detail"]["value"] == "5"


def test_svg_is_the_cli_svg(tree, tree_glb, tmp_path):
    svg = sylva.render(tree, "pen", size=SIZE, format="svg")
    out = tmp_path / "pen.svg"
    run_cli("render", tree_glb, "--style", "pen", "--size", SIZE, "-o", out)
    assert svg.startswith("<?xml") or svg.startswith("<svg")
    assert svg == out.read_text()


def test_turntable_frames(tree):
    frames = sylva.turntable(tree, "toon", frames=4, size=64)
    assert len(frames) == 4
    images = list(frames)
    assert len(images) == 4 and all(f.shape == (64, 64, 4) for f in images)
    assert_same(images[0], sylva.render(tree, "toon", size=64))
    assert not np.array_equal(images[0], images[1])


def test_turntable_as_svg(tree):
    frames = list(sylva.turntable(tree, "pen", frames=2, size=64, format="svg"))
    assert len(frames) == 2 and all("<svg" in f for f in frames) and frames[0] != frames[1]
    assert frames[0] == sylva.render(tree, "pen", size=64, format="svg")
