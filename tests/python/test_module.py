"""The module's other promises: info() is `sylva info --json`, styles and style() are `sylva
styles`, save() writes through the library's writers, images show in Jupyter, two threads
rendering two scenes give the pixels of one after the other, Ctrl-C stops a long render, and
renders in a loop keep the memory flat."""
import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np

import sylva
from conftest import read_image, run_cli


def test_info_is_the_cli_json(tree, tree_glb):
    expected = json.loads(run_cli("info", tree_glb, "--json").stdout)
    assert tree.info() == expected
    assert tree.cameras == expected["cameras"]


def test_styles_and_style():
    styles = sylva.styles()
    assert styles["ink"]["builder"] == "ink" and styles["pen"]["description"]
    pen = sylva.style("pen")
    assert pen["name"] == "pen" and pen["lines"] is True
    detail = pen["params"]["ink.detail"]
    assert detail["type"] == "float" and detail["meaning"] and detail["allowed"]
    assert detail["range"][0] <= float(detail["default"]) <= detail["range"][1]
    listing = run_cli("styles", "pen").stdout
    for key, p in pen["params"].items():
        assert key in listing and p["meaning"] in listing


def test_save_writes_png_with_dpi(tree, tmp_path):
    img = sylva.render(tree, "toon", size=48)
    sylva.save(img, tmp_path / "a.png", dpi=300)
    pixels, spec = read_image(tmp_path / "a.png")
    assert np.array_equal(pixels, img)
    assert abs(spec.getattribute("XResolution") - 300) < 0.5
    sylva.save(img[:, :, :3], str(tmp_path / "b.tiff"))
    assert os.path.getsize(tmp_path / "b.tiff") > 0


def test_image_shows_itself_as_png(tree):
    png = sylva.Image(sylva.render(tree, "toon", size=32))._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"


def test_two_threads_render_two_scenes_as_one_after_the_other(tree, tree_glb):
    other = sylva.load(str(tree_glb))
    jobs = [(tree, "ink"), (other, "watercolor"), (tree, "toon"), (other, "pen")]
    serial = [sylva.render(s, style, size=96) for s, style in jobs]
    results = [None] * len(jobs)

    def work(i):
        s, style = jobs[i]
        results[i] = sylva.render(s, style, size=96)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(jobs))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(serial, results):
        assert np.array_equal(a, b)


def test_ctrl_c_stops_a_long_render(tree_glb):
    # One render timed whole, then the same render stopped a quarter of the way: the stop must
    # come well before the render would have ended (between its passes), and the scene renders
    # again afterwards.
    script = textwrap.dedent(f"""
        import time, sylva
        scene = sylva.load({str(tree_glb)!r})
        def long_render():
            return sylva.render(scene, "ink", size=1536, ssaa=2, params={{"ink.detail": 1}})
        start = time.monotonic()
        long_render()
        print("full %.3f" % (time.monotonic() - start), flush=True)
        start = time.monotonic()
        try:
            long_render()
            print("finished %.3f" % (time.monotonic() - start), flush=True)
        except KeyboardInterrupt:
            print("interrupted %.3f" % (time.monotonic() - start), flush=True)
        print("after", sylva.render(scene, "toon", size=16).shape, flush=True)
    """)
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    full = float(p.stdout.readline().split()[1])
    time.sleep(0.25 * full)
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=300)
    first = out.splitlines()[0].split()
    assert first[0] == "interrupted", out
    assert float(first[1]) < 0.75 * full, (full, out)
    assert "after (16, 16, 4)" in out and p.returncode == 0


def rss_kib():
    with open("/proc/self/status") as f:
        return next(int(line.split()[1]) for line in f if line.startswith("VmRSS:"))


def test_renders_in_a_loop_keep_memory_flat(tree):
    for _ in range(20):
        sylva.render(tree, "ink", size=64)
    before = rss_kib()
    for _ in range(200):
        sylva.render(tree, "ink", size=64)
    after = rss_kib()
    assert abs(after - before) <= 0.1 * before, (before, after)


def test_save_video_writes_the_turntable(tree, tmp_path):
    path = tmp_path / "t.mp4"
    assert sylva.save_video(sylva.turntable(tree, "toon", frames=6, size=64), path, fps=12) == 6
    assert open(path, "rb").read(12)[4:8] == b"ftyp"
