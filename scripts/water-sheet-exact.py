#!/usr/bin/env python3
"""The water sheet's exact floor irradiance, smooth against faceted.

TestWaterSheet compares each technique with the exact caustic of the sinusoidal sheet
y = 1 + 0.02 sin(2 pi x / 0.5) (index 1.33) over a floor seen from above (256 pixel
columns over 2 m). The techniques see the sheet as a mesh: flat facets, `across` of them
over its 6 m width, with the sine's normals at the vertices interpolated between them.
This prints how far the exact irradiance under such a mesh lies from the smooth
surface's, so that the mesh can be chosen fine enough not to be what a test measures:

    /usr/bin/python3 scripts/water-sheet-exact.py [--across 512,2048] [--elevations 90,60,30]

Both are traced the way the test traces the smooth one: every ray refracts once
(Fresnel transmittance of unpolarized light) and lands on the floor; 4 * 10^6 rays
across the sheet, binned into pixel columns. Printed per elevation and mesh: the
relative L2 over the inner 3/4 of the columns (the test's), and the least and greatest
ratio of the faceted to the smooth value at the smooth solution's fold peaks (columns
at 1.5 times the mean or more and the highest within two columns).
"""
import argparse

import numpy as np

AMPLITUDE, WAVELENGTH, HEIGHT, INDEX, SHEET_HALF = 0.02, 0.5, 1.0, 1.33, 3.0
WAVE_NUMBER = 2.0 * np.pi / WAVELENGTH
SIZE, VIEW_HALF = 256, 1.0


def surface(x):
    return HEIGHT + AMPLITUDE * np.sin(WAVE_NUMBER * x)


def slope(x):
    return AMPLITUDE * WAVE_NUMBER * np.cos(WAVE_NUMBER * x)


def normal_of_slope(s):
    length = np.sqrt(1.0 + s * s)
    return -s / length, 1.0 / length


def columns(x, height, facet_slope, nx, ny, elevation):
    """Pixel columns' irradiance (W/m^2 per W/m^2 of sun) of rays hitting at x."""
    e = np.radians(elevation)
    ix, iy = np.cos(e), -np.sin(e)
    cos_i = -(ix * nx + iy * ny)
    eta = 1.0 / INDEX
    cos_t = np.sqrt(np.maximum(0.0, 1.0 - eta * eta * (1.0 - cos_i * cos_i)))
    tx = eta * ix + (eta * cos_i - cos_t) * nx
    ty = eta * iy + (eta * cos_i - cos_t) * ny
    rs = ((cos_i - INDEX * cos_t) / (cos_i + INDEX * cos_t)) ** 2
    rp = ((INDEX * cos_i - cos_t) / (INDEX * cos_i + cos_t)) ** 2
    landed = x + height * tx / -ty
    # The sun's flux through the surface element: its cross-section of the beam.
    section = np.abs(np.sin(e) + facet_slope * np.cos(e)) * (x[1] - x[0])
    pixel = 2.0 * VIEW_HALF / SIZE
    column = np.floor((landed + VIEW_HALF) / pixel).astype(int)
    inside = (column >= 0) & (column < SIZE)
    weight = section * (1.0 - 0.5 * (rs + rp)) / pixel
    return np.bincount(column[inside], weights=weight[inside], minlength=SIZE)


def smooth(x, elevation):
    nx, ny = normal_of_slope(slope(x))
    return columns(x, surface(x), slope(x), nx, ny, elevation)


def faceted(x, elevation, across):
    """Flat facets between vertices on the sine; the vertex normals interpolated."""
    step = 2.0 * SHEET_HALF / across
    i = np.clip(np.floor((x + SHEET_HALF) / step), 0, across - 1)
    x0 = -SHEET_HALF + i * step
    t = (x - x0) / step
    height = surface(x0) * (1.0 - t) + surface(x0 + step) * t
    facet_slope = (surface(x0 + step) - surface(x0)) / step
    n0, n1 = normal_of_slope(slope(x0)), normal_of_slope(slope(x0 + step))
    nx = n0[0] * (1.0 - t) + n1[0] * t
    ny = n0[1] * (1.0 - t) + n1[1] * t
    length = np.sqrt(nx * nx + ny * ny)
    return columns(x, height, facet_slope, nx / length, ny / length, elevation)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--across", default="512,2048", help="facets across the sheet")
    parser.add_argument("--elevations", default="90,60,30", help="sun elevations (degrees)")
    args = parser.parse_args()
    x = -SHEET_HALF + (np.arange(4000000) + 0.5) * (2.0 * SHEET_HALF / 4000000)
    first, last = SIZE // 8, SIZE - SIZE // 8
    for elevation in (float(e) for e in args.elevations.split(",")):
        exact = smooth(x, elevation)
        inner = exact[first:last]
        mean = inner.mean()
        peaks = [c for c in range(first + 2, last - 2)
                 if exact[c] >= 1.5 * mean and exact[c] >= exact[c - 2:c + 3].max()]
        for across in (int(a) for a in args.across.split(",")):
            mesh = faceted(x, elevation, across)
            l2 = np.sqrt(((mesh - exact)[first:last] ** 2).sum() / (inner ** 2).sum())
            ratios = [mesh[c] / exact[c] for c in peaks]
            peak_text = (f"fold peaks {min(ratios):.3f} to {max(ratios):.3f} of the smooth"
                         if ratios else "no fold peaks")
            print(f"sun at {elevation:g} degrees, {across} facets across: relative L2 "
                  f"{100.0 * l2:.2f} %, {peak_text}")


if __name__ == "__main__":
    main()
