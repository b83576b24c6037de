#!/usr/bin/env python3
"""The honest lockstep player's tick rate while a stranger holds the other seat.

A lockstep server with a lobby of two seats (physics-server --lockstep-players 2
--lockstep-pace realtime, every other limit at its default) and two cases, one
after the other, each for --seconds:
  rejoiner: a stranger takes a seat, sends no inputs, is dropped as a straggler,
            and tries to sit again at once, again and again (every 50 ms while
            refused); an honest physics-client bot plays the other seat.
  honest:   two honest bots (the tick rate without the stranger).
The server's /metrics is read every second: the ticks stepped in that second and the
lockstep timeouts so far. One CSV row a second and case: case, second, ticks,
lockstep_timeouts_total, stranger_seated (1 while the stranger holds a seat).
  bench/lobby-rejoiner.py [--build-dir build] [--seconds 60] [--csv FILE]
"""
import argparse
import json
import os
import re
import socket
import subprocess
import sys
import threading
import time
import urllib.request


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def varint(n):
    out = bytearray()
    while True:
        byte = n & 0x7F
        n >>= 7
        if n:
            out.append(byte | 0x80)
        else:
            out.append(byte)
            return bytes(out)


def hello_frame(name):
    # Hello{protocol_version: 2, client_name: name} in ClientMessage.hello (field 1).
    hello = b"\x08\x02" + b"\x12" + varint(len(name)) + name.encode()
    message = b"\x0a" + varint(len(hello)) + hello
    return varint(len(message)) + message


class Stranger(threading.Thread):
    """Sits, sends nothing, reads everything, and sits again as soon as it can."""

    def __init__(self, port):
        super().__init__(daemon=True)
        self.port = port
        self.seated = False
        self.stop = False
        self.seatings = 0
        self.refusals = 0

    def run(self):
        while not self.stop:
            try:
                with socket.create_connection(("127.0.0.1", self.port), timeout=5) as s:
                    s.sendall(hello_frame("stranger"))
                    first = True
                    while not self.stop:
                        try:
                            data = s.recv(65536)
                        except socket.timeout:
                            continue
                        if not data:
                            break
                        if first:
                            # The first ServerMessage: a Welcome (field 1, tag 0x0a) once
                            # the game takes us, or an Error (refused). Its length prefix
                            # is one byte, or two for a Welcome of up to 16 KiB.
                            first = False
                            body = data[1:] if data[0] < 0x80 else data[2:]
                            if body[:1] == b"\x0a":
                                self.seated = True
                                self.seatings += 1
                            else:
                                self.refusals += 1
                    self.seated = False
            except OSError:
                self.seated = False
            time.sleep(0.05)


def metric(text, name):
    match = re.search(r"^" + name + r"(?:\{[^}]*\})? ([0-9.e+]+)$", text, re.M)
    return float(match.group(1)) if match else 0.0


def run_case(args, case):
    port, metrics_port = free_port(), free_port()
    server = subprocess.Popen(
        [os.path.join(args.build_dir, "server/physics-server"), "--port", str(port),
         "--metrics-port", str(metrics_port), "--lockstep-players", "2",
         "--lockstep-pace", "realtime"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(0.5)
    stranger = None
    bots = 2
    if case == "rejoiner":
        stranger = Stranger(port)
        stranger.start()
        bots = 1
    client = subprocess.Popen(
        [os.path.join(args.build_dir, "client/physics-client"), "--port", str(port),
         "--bots", str(bots), "--duration", str(args.seconds), "--json"],
        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    rows = []
    url = "http://127.0.0.1:%d/metrics" % metrics_port
    last_tick = None
    started = time.monotonic()
    second = 0
    while client.poll() is None and second < args.seconds + 10:
        second += 1
        time.sleep(max(0.0, started + second - time.monotonic()))
        try:
            text = urllib.request.urlopen(url, timeout=2).read().decode()
        except OSError:
            continue
        tick = metric(text, "physics_current_tick")
        timeouts = metric(text, "physics_lockstep_timeouts_total")
        if last_tick is not None:
            rows.append((case, second, int(tick - last_tick), int(timeouts),
                         int(stranger.seated) if stranger else 0))
        last_tick = tick
    out, _ = client.communicate()
    if stranger:
        stranger.stop = True
    server.terminate()
    server.wait()
    summary = json.loads(out.strip().splitlines()[-1]) if out.strip() else {}
    return rows, summary, stranger


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build-dir", default="build")
    parser.add_argument("--seconds", type=int, default=60)
    parser.add_argument("--csv")
    args = parser.parse_args()
    all_rows = []
    for case in ("rejoiner", "honest"):
        rows, summary, stranger = run_case(args, case)
        all_rows += rows
        ticks = sum(r[2] for r in rows)
        seconds = len(rows)
        line = "%s: %d ticks in %d s (%.1f a second); the bots saw %.1f a second" % (
            case, ticks, seconds, ticks / max(seconds, 1), summary.get("ticks_per_second", 0))
        if stranger:
            line += "; the stranger sat %d times, was refused %d times, %d lockstep timeouts" % (
                stranger.seatings, stranger.refusals, rows[-1][3] if rows else 0)
        print(line, file=sys.stderr)
    if args.csv:
        with open(args.csv, "w") as out:
            out.write("case,second,ticks,lockstep_timeouts_total,stranger_seated\n")
            for row in all_rows:
                out.write("%s,%d,%d,%d,%d\n" % row)


if __name__ == "__main__":
    main()
