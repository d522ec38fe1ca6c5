#!/usr/bin/env python3
"""Work per frame from `lccp profile`'s frames.csv: the sum of the stage columns
(every *_ms column but end_to_end_ms, which includes waiting in the pipeline).
Usage: python3 perf/frame_work.py DIR/frames.csv
Prints the frame count and the median, p99 (nearest rank) and max in ms."""
import csv
import math
import statistics
import sys


def main():
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"{sys.argv[1]}: no frames")
    stages = [c for c in rows[0] if c.endswith("_ms") and c != "end_to_end_ms"]
    work = sorted(sum(float(r[c]) for c in stages) for r in rows)
    p99 = work[max(0, math.ceil(0.99 * len(work)) - 1)]
    print(f"{len(work)} frames: work per frame median {statistics.median(work):.1f} ms, "
          f"p99 {p99:.1f} ms, max {work[-1]:.1f} ms")


if __name__ == "__main__":
    main()
