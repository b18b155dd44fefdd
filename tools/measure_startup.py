#!/usr/bin/env python3
"""Whole-process cost of rtrt commands: each command run N times (default 20), its wall time and
maximum resident set size (GNU time's %M) reported as medians, with the number of lines ldd lists
for the program. Several programs (RTRT,RTRT2,...) take turns, run for run, so that they share the
machine's load. For bench/results/startup-*.txt.

  tools/measure_startup.py [--runs N] RTRT[,RTRT2...] -- ARGS [-- ARGS ...]
  e.g. tools/measure_startup.py old/rtrt,build/release/game/rtrt -- --version -- info assets/scenes/demo_glass.json
"""
import argparse
import statistics
import subprocess
import sys
import tempfile
import time


def run_once(argv, report):
    # The maximum RSS comes from GNU time, a small program: a child spawned by Python itself
    # would count Python's own pages, which it shares until exec, in its maximum.
    start = time.perf_counter()
    status = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", report] + argv,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
    wall = time.perf_counter() - start
    with open(report) as f:
        kib = int(f.read().split()[-1])
    return wall, kib, status


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=20)
    parser.add_argument("rtrt")
    parser.add_argument("commands", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    # argparse drops the first "--"; the later ones separate the commands.
    commands = [[]]
    for word in args.commands:
        if word == "--":
            commands.append([])
        else:
            commands[-1].append(word)
    commands = [c for c in commands if c]
    if not commands:
        parser.error("no command: give one after --")
    programs = args.rtrt.split(",")
    for program in programs:
        libraries = subprocess.run(["ldd", program], capture_output=True, text=True).stdout
        print(f"{program}: ldd lists {len(libraries.splitlines())} lines")
    for command in commands:
        results = {program: [] for program in programs}
        with tempfile.NamedTemporaryFile() as report:
            for _ in range(args.runs):
                for program in programs:
                    results[program].append(run_once([program] + command, report.name))
        for program, runs in results.items():
            walls = [r[0] for r in runs]
            rss = [r[1] / 1024 for r in runs]
            print(f"{program} {' '.join(command)}: {args.runs} runs, median "
                  f"{statistics.median(walls):.3f} s (min {min(walls):.3f}, max {max(walls):.3f}), "
                  f"median max RSS {statistics.median(rss):.1f} MiB, exit status "
                  f"{sorted({r[2] for r in runs})}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
