#!/usr/bin/python3
"""Checks a rendered field picture: check_png.py PNG WIDTH HEIGHT

The PNG must have the requested size and not be blank: more than 15% of its pixels differ from
the background (its most common colour); in the scene (left of the colour bar, which
tools/render_fields.py puts at 86% of the width) more than 5% of the pixels are saturated
colours (the colour-mapped bodies; the background, the grey ground and the text are not) in at
least two of six hue sectors (not one flat colour); and the colour bar's strip holds at least
four hue sectors (the bar is there). Exit code 0 if so, 1 with the reasons otherwise.
"""
import sys

import matplotlib.image as mpimg
import numpy as np


def main(argv):
    if len(argv) != 4:
        sys.exit(__doc__)
    path, width, height = argv[1], int(argv[2]), int(argv[3])
    try:
        img = mpimg.imread(path)
    except (OSError, ValueError, SyntaxError) as e:
        print(f"{path}: not a readable PNG ({e})")
        return 1
    if img.dtype != np.uint8:
        img = np.round(img * 255).astype(np.uint8)
    rgb = img[..., :3].astype(np.int32)
    problems = []
    if img.shape[:2] != (height, width):
        print(f"FAIL: {path}: size {img.shape[1]}x{img.shape[0]}, expected {width}x{height}")
        return 1
    key = (rgb[..., 0] << 16) | (rgb[..., 1] << 8) | rgb[..., 2]
    values, counts = np.unique(key, return_counts=True)
    bg = values[np.argmax(counts)]
    non_bg = float(np.mean(key != bg))
    c = rgb.astype(float) / 255
    cmax, cmin = c.max(axis=-1), c.min(axis=-1)
    sat = (cmax - cmin) / np.maximum(cmax, 1e-12)
    coloured = (sat > 0.35) & (cmax > 0.15)
    r, g, b = c[..., 0], c[..., 1], c[..., 2]
    d = np.maximum(cmax - cmin, 1e-12)
    hue = np.where(cmax == r, ((g - b) / d) % 6,
                   np.where(cmax == g, (b - r) / d + 2, (r - g) / d + 4))
    sector = np.floor(hue).astype(int) % 6  # six 60-degree hue sectors

    def region(x0, x1):
        """(fraction coloured, per-sector fraction) of the columns [x0, x1) of the width"""
        cols = slice(int(x0 * width), int(x1 * width))
        mask = coloured[:, cols]
        frac = np.bincount(sector[:, cols][mask], minlength=6) / mask.size
        return float(mask.mean()), frac

    scene, scene_sectors = region(0.0, 0.84)
    _, bar_sectors = region(0.855, 0.88)
    n_scene = int(np.sum(scene_sectors > 0.001))
    n_bar = int(np.sum(bar_sectors > 0.002))
    print(f"{path}: {img.shape[1]}x{img.shape[0]}, background #{bg:06x}, "
          f"{100 * non_bg:.1f}% not background; scene {100 * scene:.1f}% coloured, hue sectors "
          f"(%) {' '.join(f'{100 * v:.1f}' for v in scene_sectors)}; colour bar: {n_bar} sectors")
    if non_bg < 0.15:
        problems.append(f"only {100 * non_bg:.1f}% of the pixels differ from the background")
    if scene < 0.05:
        problems.append(f"only {100 * scene:.1f}% of the scene's pixels are colour-mapped")
    if n_scene < 2:
        problems.append(f"the scene's colours span {n_scene} hue sectors, expected at least 2")
    if n_bar < 4:
        problems.append(f"no colour bar: its strip spans {n_bar} hue sectors, expected 4 or more")
    for p in problems:
        print(f"FAIL: {p}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
