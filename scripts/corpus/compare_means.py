#!/usr/bin/python3
"""Mean luminance of two linear images (EXR or .hdr) and their ratio, test / reference.

    compare_means.py REFERENCE.exr TEST.exr [--test-scale S] [--name NAME]

Luminance is Rec.709 Y = 0.2126 R + 0.7152 G + 0.0722 B, averaged over every pixel (non-finite
pixels count as 0 and are reported). --test-scale divides the test image first: 683 turns Rayster's
rendering of a Blender-exported glTF (lights in lm) back into Cycles' W (docs/corpus.md).
Needs Debian's python3-numpy and python3-openimageio (run it with /usr/bin/python3).
"""
import argparse
import sys

import numpy as np
import OpenImageIO as oiio

kRec709 = np.array((0.2126, 0.7152, 0.0722))


def mean_luminance(path):
    image = oiio.ImageInput.open(path)
    if image is None:
        sys.exit(f"{path}: {oiio.geterror()}")
    pixels = image.read_image(format="float")
    image.close()
    if pixels is None or pixels.ndim != 3 or pixels.shape[2] < 3:
        sys.exit(f"{path}: not an RGB image")
    rgb = pixels[..., :3].astype(np.float64)
    bad = ~np.isfinite(rgb).all(axis=2)
    rgb[bad] = 0.0
    return float((rgb @ kRec709).mean()), int(bad.sum()), pixels.shape[1], pixels.shape[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("reference")
    parser.add_argument("test")
    parser.add_argument("--test-scale", type=float, default=1.0, help="divide the test image by this first")
    parser.add_argument("--name", default="", help="label for the printed line")
    args = parser.parse_args()
    ref, ref_bad, rw, rh = mean_luminance(args.reference)
    test, test_bad, tw, th = mean_luminance(args.test)
    test /= args.test_scale
    if (rw, rh) != (tw, th):
        print(f"warning: sizes differ ({rw}x{rh} vs {tw}x{th}); means are still per pixel", file=sys.stderr)
    for path, count in ((args.reference, ref_bad), (args.test, test_bad)):
        if count:
            print(f"warning: {path}: {count} non-finite pixels counted as 0", file=sys.stderr)
    ratio = test / ref if ref > 0 else float("nan")
    label = f"{args.name}: " if args.name else ""
    print(f"{label}reference {ref:.6g}  test {test:.6g} (after / {args.test_scale:g})  ratio {ratio:.4f}")


main()
