#!/usr/bin/python3
"""A turntable to MP4: the frames of sylva.turntable written by the library's video writer.

    PYTHONPATH=build/python python3 examples/turntable_mp4.py [SCENE.glb] [turntable.mp4]
"""
import sys

import sylva

scene = sylva.load(sys.argv[1]) if len(sys.argv) > 1 else sylva.sample("tree", seed=1)
out = sys.argv[2] if len(sys.argv) > 2 else "turntable.mp4"
frames = sylva.turntable(scene, "toon", frames=48, size=(480, 480), elevation=10)
count = sylva.save_video(frames, out, fps=24)
print(f"wrote {out} ({count} frames)")
