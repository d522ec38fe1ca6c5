#!/usr/bin/env python3
"""What the live view costs the pipeline: `lccp profile` of a recording without a view,
then with `--view` and three clients on the stream (two reading every message, one
stalled: it opens the stream and never reads), alternated, RUNS times each. Prints the
median frames/s of each, their ratio, the frames dropped, and the bytes the readers got.

    python3 perf/view_load.py build/lccp recordings/mosd_scenes.oni [--runs 9] [--threads 2]
"""
import argparse
import base64
import json
import os
import signal
import socket
import statistics
import subprocess
import tempfile
import threading
import time


def open_stream(port):
    """A WebSocket client of /stream (RFC 6455 handshake); returns the socket."""
    sock = socket.create_connection(("127.0.0.1", port), timeout=600)
    key = base64.b64encode(os.urandom(16)).decode()
    sock.sendall((f"GET /stream HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n"
                  f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n").encode())
    reply = b""
    while b"\r\n\r\n" not in reply:
        chunk = sock.recv(1)
        if not chunk:
            raise RuntimeError("the view closed the stream during the handshake")
        reply += chunk
    if b" 101 " not in reply.split(b"\r\n")[0]:
        raise RuntimeError(f"no WebSocket: {reply[:80]!r}")
    return sock


def read_all(sock, counter):
    """Reads everything into one reused buffer (a page's own cost belongs to its machine, not this one)."""
    buffer = bytearray(1 << 20)
    while True:
        try:
            got = sock.recv_into(buffer)
        except OSError:
            return
        if not got:
            return
        counter[0] += got


def profile(lccp, recording, threads, view):
    with tempfile.TemporaryDirectory() as out:
        command = [lccp, "--threads", str(threads), "profile", recording, "-o", out, "--quiet"]
        if view:
            command += ["--view", "127.0.0.1:0", "--view-hold"]
        process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        readers, received, sockets = [], [0], []
        if view:
            port = int(process.stdout.readline().split()[1].rsplit(":", 1)[1].strip("/"))
            sockets = [open_stream(port) for _ in range(3)]  # the first one opened starts the run
            for sock in sockets[1:]:
                readers.append(threading.Thread(target=read_all, args=(sock, received), daemon=True))
                readers[-1].start()
        for line in process.stdout:
            if line.startswith("reports "):
                break
        report = json.load(open(os.path.join(out, "report.json")))
        if view:
            process.send_signal(signal.SIGINT)  # --view-hold serves until Ctrl-C
        process.wait(timeout=600)
        for sock in sockets:
            sock.close()
        if process.returncode != 0:
            raise RuntimeError(f"{' '.join(command)}: exit {process.returncode}")
        return report, received[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("lccp")
    parser.add_argument("recording")
    parser.add_argument("--runs", type=int, default=9)
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()
    rates = {False: [], True: []}
    dropped = {False: 0, True: 0}
    received = []
    for _ in range(args.runs):
        for view in (False, True):
            report, got = profile(args.lccp, args.recording, args.threads, view)
            rates[view].append(report["frames_per_second"])
            dropped[view] += report["frames_dropped"]
            if view:
                received.append(got)
    without, with_view = statistics.median(rates[False]), statistics.median(rates[True])
    print(f"runs {args.runs} each, {args.threads} threads, {args.recording}")
    print(f"without view: median {without:.2f} frames/s (all: {', '.join(f'{r:.1f}' for r in rates[False])})")
    print(f"with view + 3 clients (1 stalled): median {with_view:.2f} frames/s "
          f"(all: {', '.join(f'{r:.1f}' for r in rates[True])})")
    print(f"ratio with / without: {with_view / without:.3f}; frames dropped: {dropped[False]} without, "
          f"{dropped[True]} with; the two readers got {statistics.median(received) / 1e6:.1f} MB a run (median)")


if __name__ == "__main__":
    main()
