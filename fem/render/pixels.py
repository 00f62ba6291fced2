"""Reading rendered bending images back (for the pixel tests of the renderer).

The deformed body is drawn with a saturated colour map; everything else (background,
faint undeformed shaft, supports, text) is grey or black.  A pixel is "body" when the
spread between its largest and smallest RGB channel exceeds ``threshold``."""
from __future__ import annotations

import numpy as np


def body_mask(img: np.ndarray, threshold: int = 25) -> np.ndarray:
    a = np.asarray(img)[..., :3].astype(int)
    return (a.max(axis=-1) - a.min(axis=-1)) > threshold


def centreline(img: np.ndarray, threshold: int = 25, min_pixels: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """(columns, centre rows) of the body: the midpoint between the first and the last body
    pixel of every column with at least ``min_pixels`` body pixels (edges, unlike a colour
    centroid, do not move with the shading of the tube)."""
    mask = body_mask(img, threshold)
    counts = mask.sum(axis=0)
    cols = np.flatnonzero(counts >= min_pixels)
    first = np.argmax(mask, axis=0)
    last = mask.shape[0] - 1 - np.argmax(mask[::-1], axis=0)
    return cols, 0.5 * (first + last)[cols]


def difference_fraction(a: np.ndarray, b: np.ndarray, level: int = 30) -> float:
    """Fraction of pixels whose largest channel difference exceeds ``level``."""
    d = np.abs(np.asarray(a, int)[..., :3] - np.asarray(b, int)[..., :3]).max(axis=-1)
    return float((d > level).mean())


def faint_extent(img: np.ndarray, row: float, band: int = 3, lo: int = 170, hi: int = 232) -> tuple[int, int]:
    """First and last column of the faint (light grey) undeformed shaft in the rows
    ``row +- band``: the picture's x calibration (x = 0 and x = L)."""
    a = np.asarray(img)[..., :3].astype(int)
    r0, r1 = int(round(row)) - band, int(round(row)) + band + 1
    sub = a[r0:r1]
    grey = ((sub.max(-1) - sub.min(-1)) < 12) & (sub.min(-1) >= lo) & (sub.max(-1) <= hi)
    cols = np.flatnonzero(grey.any(axis=0))
    return int(cols.min()), int(cols.max())
