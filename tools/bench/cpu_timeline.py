#!/usr/bin/env python3
"""Runs a command and prints how many cores it used, interval by interval.

    python3 tools/bench/cpu_timeline.py [--every 0.5] -- squeal reduce a.inp b.inp -o x.rom

Every interval, the process's user and system CPU time (from /proc/<pid>/stat, all its
threads) is read; the table gives the cores used over the interval (CPU seconds per wall
second), user and system apart, and the command's total at the end. Linux only. The command's
own output goes to stderr, the table to stdout.
"""

import os
import resource
import subprocess
import sys
import time


def cpu_seconds(pid: int) -> tuple[float, float] | None:
    """User and system CPU seconds of a running process, or None once it has exited."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            # The command name (field 2) may hold spaces: count fields after its ')'.
            fields = f.read().rsplit(")", 1)[1].split()
    except (FileNotFoundError, ProcessLookupError, IndexError):
        return None
    tick = os.sysconf("SC_CLK_TCK")
    # Fields 14 and 15 of stat (utime, stime) are the 12th and 13th after the name.
    return int(fields[11]) / tick, int(fields[12]) / tick


def main() -> int:
    args = sys.argv[1:]
    every = 0.5
    if args[:1] == ["--every"]:
        every, args = float(args[1]), args[2:]
    if args[:1] == ["--"]:
        args = args[1:]
    if not args:
        print(__doc__, file=sys.stderr)
        return 2
    start = time.monotonic()
    proc = subprocess.Popen(args, stdout=sys.stderr)
    print(f"{'t (s)':>7} {'cores':>6} {'user':>6} {'sys':>6}")
    last, last_t = (0.0, 0.0), start
    while proc.poll() is None:
        time.sleep(every)
        now = cpu_seconds(proc.pid)
        t = time.monotonic()
        if now is None or proc.poll() is not None:
            break
        du, ds = now[0] - last[0], now[1] - last[1]
        dt = t - last_t
        print(f"{t - start:7.2f} {(du + ds) / dt:6.2f} {du / dt:6.2f} {ds / dt:6.2f}")
        last, last_t = now, t
    proc.wait()
    wall = time.monotonic() - start
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    print(
        f"total: wall {wall:.2f} s, user {ru.ru_utime:.2f} s, sys {ru.ru_stime:.2f} s, "
        f"user/wall {ru.ru_utime / wall:.2f}, (user+sys)/wall {(ru.ru_utime + ru.ru_stime) / wall:.2f}"
    )
    return proc.returncode


if __name__ == "__main__":
    sys.exit(main())
