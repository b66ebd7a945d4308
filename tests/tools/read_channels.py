#!/usr/bin/python3
"""Reads channels of an image with OpenImageIO (a reader nobody in this project wrote) for the
tests: read_channels.py IMAGE OUTDIR NAME... writes OUTDIR/NAME.raw for each channel, its
pixels row by row as little-endian float32 (half and float channels) or uint32 (uint channels),
and prints one line per channel: NAME TYPE WIDTH HEIGHT. Exit 1 naming what is missing."""
import os
import sys

import OpenImageIO as oiio


def main():
    image, out_dir, names = sys.argv[1], sys.argv[2], sys.argv[3:]
    inp = oiio.ImageInput.open(image)
    if inp is None:
        sys.exit(f"cannot open {image}: {oiio.geterror()}")
    spec = inp.spec()
    channels = list(spec.channelnames)
    for name in names:
        if name not in channels:
            sys.exit(f"{image}: no channel {name} (has {', '.join(channels)})")
        i = channels.index(name)
        kind = "uint" if str(spec.channelformat(i)) == "uint" else "float"
        pixels = inp.read_image(0, 0, i, i + 1, kind)
        pixels.astype("<u4" if kind == "uint" else "<f4").tofile(os.path.join(out_dir, name + ".raw"))
        print(name, kind, spec.width, spec.height)
    inp.close()


main()
