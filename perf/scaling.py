#!/usr/bin/env python3
"""Time per frame against the work (issue 14, must-show 5), written as an SVG plot.

Segments mOSD clouds at P1 with lccp_stream.segment (the library call the tool
makes; the module adds 0.2-0.4 ms a call, perf/RESULTS.md) and takes the median
of --calls calls per input:
  - points: a quarter (every 2nd row and column), half (every 2nd row) and all of
    an organized VGA frame, and --merged clouds of the 65 scenes side by side
    (unorganized, about 2 million points);
  - voxel size: the full frame at v = 4, 5, 7.5, 10 and 15 mm (seed size 4 v, the
    P1 ratio).
Usage: PYTHONPATH=build/python python3 perf/scaling.py [--mosd DIR] [--threads 2]
       [--calls 15] [--svg perf/scaling.svg]
Prints one line per input (points, voxels' setting, median ms) and writes the SVG.
"""
import argparse
import math
import pathlib
import statistics
import time

import numpy as np

import lccp_stream

P1 = {"voxel_size_m": 0.005, "seed_size_m": 0.02}


def median_ms(points, config, threads, calls):
    lccp_stream.segment(points, config=config, threads=threads)  # warm-up
    times = []
    for _ in range(calls):
        start = time.perf_counter()
        lccp_stream.segment(points, config=config, threads=threads)
        times.append(1000 * (time.perf_counter() - start))
    return statistics.median(times)


def finite_count(points):
    return int(np.isfinite(points).all(axis=-1).sum())


def merged_cloud(mosd, clouds):
    """`clouds` scenes, each shifted 2 m along x from the last: one unorganized cloud."""
    parts = []
    for i, path in enumerate(sorted(mosd.glob("test*.pcd"))[:clouds]):
        p = lccp_stream.read_cloud(str(path))["points"].reshape(-1, 3)
        p = p[np.isfinite(p).all(axis=1)] + np.array([2.0 * i, 0, 0], dtype=np.float32)
        parts.append(p)
    return np.ascontiguousarray(np.concatenate(parts), dtype=np.float32)


def point_series(frame, mosd, merged, threads, calls):
    inputs = [("quarter VGA", frame[::2, ::2]), ("half VGA", frame[::2]), ("VGA", frame),
              (f"{merged} scenes merged", merged_cloud(mosd, merged))]
    rows = []
    for name, points in inputs:
        points = np.ascontiguousarray(points, dtype=np.float32)
        ms = median_ms(points, P1, threads, calls)
        rows.append((name, finite_count(points), ms))
        print(f"{name:24s} {rows[-1][1]:9d} points  v 5 mm    {ms:8.1f} ms", flush=True)
    return rows


def voxel_series(frame, threads, calls):
    rows = []
    for v_mm in (4, 5, 7.5, 10, 15):
        config = {"voxel_size_m": v_mm / 1000, "seed_size_m": 4 * v_mm / 1000}
        ms = median_ms(frame, config, threads, calls)
        rows.append((v_mm, ms))
        print(f"{'VGA':24s} {finite_count(frame):9d} points  v {v_mm:g} mm  {ms:8.1f} ms", flush=True)
    return rows


def panel(x0, title, xlabel, points, loglog):
    """One 360 x 260 panel at x offset x0: axes, points and their labels; on log-log
    axes also the least-squares line y = k x (slope 1: time proportional to points)."""
    w, h, left, bottom = 360, 260, 60, 40
    f = (lambda v: math.log10(v)) if loglog else (lambda v: v)
    xs, ys = [f(p[0]) for p in points], [f(p[1]) for p in points]
    xlo, xhi = (min(xs) - 0.15, max(xs) + 0.35) if loglog else (0, max(xs) * 1.15)
    ylo, yhi = (min(ys) - 0.15, max(ys) + 0.2) if loglog else (0, max(ys) * 1.15)
    sx = lambda x: x0 + left + (w - left - 10) * (x - xlo) / (xhi - xlo)
    sy = lambda y: h - bottom - (h - bottom - 30) * (y - ylo) / (yhi - ylo)
    out = [f'<text x="{x0 + w / 2}" y="18" text-anchor="middle" font-size="13">{title}</text>',
           f'<line x1="{sx(xlo)}" y1="{sy(ylo)}" x2="{sx(xhi)}" y2="{sy(ylo)}" stroke="black"/>',
           f'<line x1="{sx(xlo)}" y1="{sy(ylo)}" x2="{sx(xlo)}" y2="{sy(yhi)}" stroke="black"/>',
           f'<text x="{x0 + w / 2}" y="{h - 8}" text-anchor="middle" font-size="11">{xlabel}</text>',
           f'<text x="{x0 + 14}" y="{h / 2}" font-size="11" transform="rotate(-90 {x0 + 14} {h / 2})" '
           f'text-anchor="middle">ms per frame (median)</text>']
    yticks = [math.log10(v) for v in (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000)] if loglog else \
        [yhi * i / 5 for i in range(5)]
    for y in (t for t in yticks if ylo <= t <= yhi):
        out.append(f'<text x="{sx(xlo) - 4}" y="{sy(y) + 4}" text-anchor="end" font-size="10">'
                   f'{(10 ** y if loglog else y):.0f}</text>')
    if loglog:
        k = sum(x * y for x, y, _ in points) / sum(x * x for x, _, _ in points)
        out.append(f'<line x1="{sx(xlo)}" y1="{sy(xlo + math.log10(k))}" x2="{sx(xhi)}" '
                   f'y2="{sy(xhi + math.log10(k))}" stroke="gray" stroke-dasharray="4 3"/>')
    for (x, y), (_, _, label) in zip(zip(xs, ys), points):
        out.append(f'<circle cx="{sx(x):.1f}" cy="{sy(y):.1f}" r="3.5" fill="steelblue"/>')
        right = x > (xlo + xhi) / 2  # labels of the right half end at their point
        out.append(f'<text x="{sx(x) + (-6 if right else 6):.1f}" y="{sy(y) + 12:.1f}" font-size="10" '
                   f'text-anchor="{"end" if right else "start"}">{label}</text>')
    return out


def write_svg(path, point_rows, voxel_rows, threads):
    points = [(n / 1e6, ms, f"{name}, {ms:.0f} ms") for name, n, ms in point_rows]
    voxels = [(v, ms, f"{v:g} mm, {ms:.0f} ms") for v, ms in voxel_rows]
    body = (panel(0, f"P1, {threads} threads: time against points",
                  "million finite points, log-log (dashed: time = k points)", points, True) +
            panel(380, "VGA mOSD frame: time against voxel size", "voxel size v, mm (seed 4 v)", voxels, False))
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="760" height="270" font-family="sans-serif">',
           '<rect width="760" height="270" fill="white"/>', *body, '</svg>']
    pathlib.Path(path).write_text("\n".join(svg) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mosd", default="../shared/data/mOSD/test", type=pathlib.Path)
    parser.add_argument("--frame", default="tests/data/mosd_test2.pcd", help="the organized VGA frame")
    parser.add_argument("--merged", type=int, default=11, help="scenes merged into the large cloud")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--calls", type=int, default=15)
    parser.add_argument("--svg", default="perf/scaling.svg")
    args = parser.parse_args()
    lccp_stream.keep_freed_memory_for_next_frames()
    frame = np.ascontiguousarray(lccp_stream.read_cloud(args.frame)["points"], dtype=np.float32)
    if frame.ndim != 3:
        raise SystemExit(f"{args.frame}: not an organized cloud")
    point_rows = point_series(frame, args.mosd, args.merged, args.threads, args.calls)
    voxel_rows = voxel_series(frame, args.threads, args.calls)
    write_svg(args.svg, point_rows, voxel_rows, args.threads)
    print(f"wrote {args.svg}")


if __name__ == "__main__":
    main()
