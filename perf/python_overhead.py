#!/usr/bin/env python3
"""Python overhead (issue 12): lccp_stream.segment on an organized mOSD cloud
passed as a numpy array against the same call in C++ (perf/segment_call, the
same shared library), median over CALLS calls each, in alternating rounds (C++
first in odd rounds, Python first in even ones) so that both see the same
machine state.

  PYTHONPATH=build11/python python3 perf/python_overhead.py build11/perf/segment_call \
      tests/data/mosd_test2.pcd [--calls 20 --rounds 3 --threads 2 --config p1]
"""
import argparse
import statistics
import subprocess
import time

import lccp_stream


def cpp_times(program, cloud, config, calls, threads, keep):
    out = subprocess.run([program, cloud, config, str(calls), str(threads), str(int(keep))], check=True,
                         capture_output=True, text=True).stdout
    return [float(line) for line in out.split()]


def python_times(points, colors, config, calls, threads):
    lccp_stream.segment(points, colors, config=config, threads=threads)  # warm-up, as in C++
    times = []
    for _ in range(calls):
        start = time.perf_counter()
        lccp_stream.segment(points, colors, config=config, threads=threads)
        times.append((time.perf_counter() - start) * 1000)
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("program")
    parser.add_argument("cloud")
    parser.add_argument("--config", default="p1")
    parser.add_argument("--calls", type=int, default=20)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--keep-freed-memory", action="store_true",
                        help="both sides call keep_freed_memory_for_next_frames first, as the lccp tool does")
    args = parser.parse_args()
    if args.keep_freed_memory:
        lccp_stream.keep_freed_memory_for_next_frames()
    cloud = lccp_stream.read_cloud(args.cloud)
    points, colors = cloud["points"], cloud["colors"]
    print(f"cloud {args.cloud}: points {points.shape} {points.dtype}, config {args.config}, "
          f"threads {args.threads}, {args.calls} calls per round, keep freed memory: {args.keep_freed_memory}")
    cpp, python = [], []
    for r in range(args.rounds):
        if r % 2 == 0:
            c = cpp_times(args.program, args.cloud, args.config, args.calls, args.threads, args.keep_freed_memory)
            p = python_times(points, colors, args.config, args.calls, args.threads)
        else:
            p = python_times(points, colors, args.config, args.calls, args.threads)
            c = cpp_times(args.program, args.cloud, args.config, args.calls, args.threads, args.keep_freed_memory)
        cpp += c
        python += p
        print(f"round {r + 1}: C++ median {statistics.median(c):.2f} ms, "
              f"Python median {statistics.median(p):.2f} ms, ratio {statistics.median(p) / statistics.median(c):.3f}")
    ratio = statistics.median(python) / statistics.median(cpp)
    print(f"all rounds ({len(cpp)} calls each): C++ median {statistics.median(cpp):.2f} ms, "
          f"Python median {statistics.median(python):.2f} ms, overhead {100 * (ratio - 1):+.1f} %")


if __name__ == "__main__":
    main()
