"""Averages two renders of N/2 spp each (different seeds) into the N-spp reference, and
estimates the standard error of that mean per pixel and channel as |a − b| / 2.

    blender -b --factory-startup --python-exit-code 1 -P scripts/reference/combine_halves.py -- \
        A.exr B.exr MEAN.exr STDERR.exr

For two independent estimates a, b of the same pixel with variance σ² each, the mean has
variance σ²/2, and E[(a − b)²] / 4 = σ²/2: |a − b| / 2 is a one-sample estimate of its
standard error (noisy per pixel, fine averaged over a region).
"""

import os
import sys

import bpy
import numpy as np


def load(path):
    image = bpy.data.images.load(os.path.abspath(path))
    if not image.is_float:
        raise SystemExit(f"combine_halves.py: {path} is not a float image")
    pixels = np.array(image.pixels[:], dtype=np.float64).reshape(image.size[1], image.size[0], 4)
    return pixels[:, :, :3], image.size[0], image.size[1]


def save(path, rgb, width, height):
    image = bpy.data.images.new(os.path.basename(path), width, height, alpha=False,
                                float_buffer=True)
    rgba = np.ones((height, width, 4), dtype=np.float32)
    rgba[:, :, :3] = rgb
    image.pixels.foreach_set(rgba.ravel())
    settings = bpy.context.scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_mode = "RGB"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"
    image.save_render(os.path.abspath(path), scene=bpy.context.scene)
    # Saved linear, as rendered: read it back and compare.
    back, _, _ = load(path)
    if not np.array_equal(back.astype(np.float32), rgb.astype(np.float32)):
        raise SystemExit(f"combine_halves.py: {path} does not read back as written")


def main():
    a_path, b_path, mean_path, stderr_path = sys.argv[sys.argv.index("--") + 1:]
    a, width, height = load(a_path)
    b, w2, h2 = load(b_path)
    if (width, height) != (w2, h2):
        raise SystemExit("combine_halves.py: the two renders differ in size")
    save(mean_path, (a + b) / 2, width, height)
    save(stderr_path, np.abs(a - b) / 2, width, height)


main()
