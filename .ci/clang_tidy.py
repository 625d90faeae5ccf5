#!/usr/bin/env python3
"""clang-tidy (Debian's, .ci/debian-packages.txt) on refracta's own C++, cheaply enough for `make test`.

Every library .cpp under cpp/refracta/ (not bindings/: each of its TUs parses pybind11 whole, and
GCC's -Werror build covers them) and the project headers they include are checked with the checks
of .clang-tidy, with the flags of the editable install's build (build/*/compile_commands.json,
written by `make install`). Any finding fails (WarningsAsErrors): exit status 1.

Why "unity" TUs: clang-tidy's time goes into parsing the third-party headers (Eigen, Ceres, TBB,
the standard library) and running every check over their whole AST, again for each TU; refracta's
own code is a few per cent of it. So each layer's .cpp files are checked together, as one TU that
#includes them all (build/clang-tidy/<layer>.cpp): measured 4.4 s of CPU for media/ as one unit
against 24.7 s for its 10 TUs one by one; the whole library (85 files, 11 runs with the two splits
below) 138-145 s of CPU, 186-267 s of wall time on 2 cores under a load average of 6-8 from other
builds, against 390 s of CPU (561 s wall) TU by TU (2026-12-03). Findings in the included .cpp files are reported at
their own lines (HeaderFilterRegex matches cpp/refracta/). Two .cpp files of a layer may not fit
in one TU (two file-local helpers of one name): clang then reports an error, and the unit is split
before the file where the error is (halved when the error is elsewhere) and each part checked
again, down to single files, so a real compile error is still reported against its file.
What a unity TU cannot see: clang's -Wunused-const-variable, which clang reports only in the main
file (an unused namespace-scope constant in a .cpp); `--per-tu` checks TU by TU (~3x the time).

Usage: python3 .ci/clang_tidy.py [--jobs N] [--per-tu]   (JOBS in the environment sets the default)
"""

from __future__ import annotations

import argparse
import concurrent.futures
import glob
import json
import os
import re
import resource
import shlex
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LIBRARY = ROOT / "cpp" / "refracta"
OUT = ROOT / "build" / "clang-tidy"
# clang-tidy's own lines worth showing: findings and compile errors, "file:line:col: error: ... [check]".
FINDING = re.compile(r"^(/[^:]+):(\d+):\d+: (?:warning|error): .*\[[\w.,-]+\]$")
COMPILE_ERROR = "[clang-diagnostic-error]"


def library_commands() -> dict[Path, list[str]]:
    """The build's compile command of each library .cpp (not bindings/), by file."""
    databases = sorted(glob.glob(str(ROOT / "build" / "*" / "compile_commands.json")))
    databases = [d for d in databases if Path(d).parent != OUT]  # not this script's own
    if not databases:
        sys.exit("error: no build/*/compile_commands.json: run make install first")
    commands = {}
    for entry in json.loads(Path(databases[0]).read_text()):
        path = Path(entry["directory"], entry["file"]).resolve()
        if path.is_relative_to(LIBRARY) and path.parent.parent == LIBRARY and path.parent.name != "bindings":
            if path.exists():  # a file deleted since the last build
                commands[path] = shlex.split(entry["command"]) if "command" in entry else entry["arguments"]
    if not commands:
        sys.exit(f"error: no cpp/refracta/*/*.cpp in {databases[0]}")
    return commands


def flags_of(command: list[str]) -> list[str]:
    """The compiler, -D/-I/-std... flags of a compile command, without its -o output and -c input."""
    kept, skip = [], False
    for arg in command:
        if skip:
            skip = False
        elif arg in ("-o", "-c"):
            skip = True
        else:
            kept.append(arg)
    return kept


def run_tidy(unit: Path) -> str:
    """clang-tidy on one file of build/clang-tidy/compile_commands.json: its output and wall time."""
    start = time.monotonic()
    done = subprocess.run(
        ["clang-tidy", "-p", str(OUT), "--quiet", "-extra-arg=-Wno-ignored-optimization-argument", str(unit)],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    text = re.sub(r"\x1b\[[0-9;]*m", "", done.stdout + done.stderr)
    if done.returncode != 0 and not any(FINDING.match(line) for line in text.splitlines()):
        # clang-tidy failed without saying where (a crash, a missing file): fail on the unit itself.
        text += f"\n{unit}:1:1: error: clang-tidy exited with status {done.returncode} [clang-tidy-failed]\n"
    return f"({time.monotonic() - start:.1f} s)\n{text}"


Unit = tuple[list[Path], str]  # the .cpp files checked as one TU, and its name


class Runner:
    """Checks units on a pool of clang-tidy processes; a unit that does not compile is split."""

    def __init__(self, commands: dict[Path, list[str]], jobs: int) -> None:
        self.commands = commands
        self.jobs = jobs
        self.database: list[dict[str, str]] = []
        self.findings: set[str] = set()
        self.log: list[str] = []
        self.splits: list[str] = []
        self.runs = 0

    def unit_file(self, files: list[Path], name: str) -> Path:
        """A single file as itself, or a .cpp that #includes the files; either with a compile command."""
        if len(files) == 1:
            unit = files[0]
        else:
            unit = OUT / f"{name}.cpp"
            unit.write_text("".join(f'#include "{f}"\n' for f in files))
        command = flags_of(self.commands[files[0]]) + ["-c", str(unit)]
        self.database.append({"directory": str(ROOT), "file": str(unit), "command": shlex.join(command)})
        (OUT / "compile_commands.json").write_text(json.dumps(self.database, indent=1))
        return unit

    def run(self, units: list[Unit]) -> None:
        """Checks the units, the largest first (so the processes end together), and any split parts."""
        pending = sorted(units, key=lambda unit: len(unit[0]))
        running: dict[concurrent.futures.Future[str], Unit] = {}
        with concurrent.futures.ThreadPoolExecutor(self.jobs) as pool:
            while pending or running:
                while pending and len(running) < self.jobs:
                    files, name = pending.pop()
                    running[pool.submit(run_tidy, self.unit_file(files, name))] = (files, name)
                done, _ = concurrent.futures.wait(running, return_when=concurrent.futures.FIRST_COMPLETED)
                for future in done:
                    parts = self.result(*running.pop(future), future.result())
                    pending = sorted(pending + parts, key=lambda unit: len(unit[0]))

    def result(self, files: list[Path], name: str, text: str) -> list[Unit]:
        """Keeps a unit's findings; if it did not compile as one TU, the two parts to check instead."""
        self.runs += 1
        self.log.append(f"== {name} ({len(files)} files)\n{text}")
        lines = text.splitlines()
        errors = [line for line in lines if line.endswith(COMPILE_ERROR)]
        if errors and len(files) > 1:
            # Two files may clash in one TU: split before the file with the error (else in halves).
            where = Path(errors[0].split(":")[0])
            at = files.index(where) if where in files[1:] else len(files) // 2
            self.splits.append(f"{name}: {errors[0]}")
            return [(files[:at], f"{name}.a"), (files[at:], f"{name}.b")]
        self.findings.update(line for line in lines if FINDING.match(line))
        return []


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--jobs", type=int, default=int(os.environ.get("JOBS", "2")))
    parser.add_argument("--per-tu", action="store_true", help="check each .cpp as its own TU (slower)")
    args = parser.parse_args()
    start = time.monotonic()
    commands = library_commands()
    OUT.mkdir(parents=True, exist_ok=True)
    layers: dict[str, list[Path]] = {}
    for path in sorted(commands):
        layers.setdefault(path.parent.name, []).append(path)
    if args.per_tu:
        units = [([f], f"{f.parent.name}/{f.name}") for files in layers.values() for f in files]
    else:
        units = [(files, layer) for layer, files in layers.items()]
    runner = Runner(commands, args.jobs)
    runner.run(units)
    (OUT / "clang-tidy.log").write_text("\n".join(runner.log))
    for split in runner.splits:
        print(f"clang-tidy: checked in two parts, as its files clash in one TU: {split}")
    for finding in sorted(runner.findings):
        print(finding)
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    print(
        f"clang-tidy: {len(commands)} files in {runner.runs} clang-tidy runs, {len(runner.findings)} findings, "
        f"{time.monotonic() - start:.0f} s ({usage.ru_utime + usage.ru_stime:.0f} s CPU); "
        f"full log in {(OUT / 'clang-tidy.log').relative_to(ROOT)}"
    )
    return 1 if runner.findings else 0


if __name__ == "__main__":
    sys.exit(main())
