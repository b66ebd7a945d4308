#!/usr/bin/python3
"""Benchmark (label perf): a sweep of ink.detail on one loaded scene through the module against
a shell loop of `sylva render` processes, in one run, each with a fresh result cache. Prints the
times and the ratios the issue asks for:
  sweep8 / one   8 module renders at new ink.detail values over one loaded scene, against one
                 render of a freshly loaded scene (load + upload + preprocessing + render);
  module / CLI   the 16-value sweep at 512 px through the module and as 16 `sylva render`s.
Usage: bench_sweep.py [SCENE.glb] [SIZE]   (SYLVA_BINARY: the CLI; default the shared ash)"""
import os
import subprocess
import sys
import tempfile
import time

SHARED = os.environ.get("SYLVA_SHARED_DIR", "../shared")
SCENE = sys.argv[1] if len(sys.argv) > 1 else os.path.join(SHARED, "assets",
                                                           "eztree_ash_medium_s5.glb")
SIZE = int(sys.argv[2]) if len(sys.argv) > 2 else 512
SYLVA = os.environ.get("SYLVA_BINARY", "sylva")
VALUES = [0.5 * (i + 1) for i in range(16)]


def module_sweep(values):
    """(seconds of load + first render, seconds of the renders of `values` after it)."""
    import sylva
    start = time.monotonic()
    scene = sylva.load(SCENE)
    sylva.render(scene, "ink", size=SIZE, params={"ink.detail": 20.0})
    first = time.monotonic() - start
    start = time.monotonic()
    for v in values:
        sylva.render(scene, "ink", size=SIZE, params={"ink.detail": v})
    return first, time.monotonic() - start


def cli_sweep(values, out):
    start = time.monotonic()
    for v in values:
        subprocess.run([SYLVA, "render", SCENE, "--style", "ink", "--size", str(SIZE), "--set",
                        f"ink.detail={v}", "-o", os.path.join(out, f"{v}.png")], check=True,
                       capture_output=True)
    return time.monotonic() - start


def main():
    with tempfile.TemporaryDirectory() as tmp:
        os.environ["SYLVA_CACHE_DIR"] = os.path.join(tmp, "module-cache")
        first, sweep8 = module_sweep(VALUES[1::2])
        print(f"module: load + one render {first:.2f} s; 8 more values {sweep8:.2f} s; "
              f"sweep8 / one = {sweep8 / first:.2f}")
        os.environ["SYLVA_CACHE_DIR"] = os.path.join(tmp, "module-cache-2")
        first16, sweep16 = module_sweep(VALUES)
        module16 = first16 + sweep16
        os.environ["SYLVA_CACHE_DIR"] = os.path.join(tmp, "cli-cache")
        cli16 = cli_sweep(VALUES, tmp)
        print(f"16 values of ink.detail at {SIZE} px on {os.path.basename(SCENE)}: module "
              f"{module16:.2f} s (load and one more render included), shell loop of sylva render "
              f"{cli16:.2f} s; module / CLI = {module16 / cli16:.2f}")


if __name__ == "__main__":
    main()
