"""Start-up time of the command line against ``python -c "import numpy"``, in the same run.

Each command runs as a fresh subprocess (the console script ``vbikit`` beside this Python, or
``python -c "from vbikit.cli import main; main()"`` when it is not installed), ``--repeat``
rounds interleaved so that the load of a shared machine hits every command alike, after one
untimed round that warms the file-system cache.

    python benchmarks/bench_startup.py              # 9 rounds, ≈ 15 s
    python benchmarks/bench_startup.py --repeat 21  # more rounds

Reported per command: median, min and max wall time (``time.perf_counter`` around
``subprocess.run``); then the ratio of the medians ``vbikit --version`` / ``import numpy`` (the
target is ≤ 3) and of the fastest runs, and for context ``vbikit --help`` and an empty
``python -c pass`` (the interpreter's own start-up).  Finally the heavy modules that
``vbikit --version`` and ``--help`` load (none of numba, scipy, xarray, matplotlib expected).
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("numpy", "numba", "scipy", "xarray", "matplotlib", "pandas", "pydantic")


def vbikit_command() -> list[str]:
    """The console script installed beside this interpreter, else the same entry point through ``-c``."""
    script = Path(sys.executable).with_name("vbikit")
    if script.is_file():
        return [str(script)]
    found = shutil.which("vbikit")
    return [found] if found else [sys.executable, "-c", "from vbikit.cli import main; main()"]


def wall(cmd: list[str]) -> float:
    """Wall time [s] of one subprocess run of ``cmd`` (its output discarded; it must succeed)."""
    t0 = time.perf_counter()
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    return time.perf_counter() - t0


def loaded_modules(argv: list[str]) -> list[str]:
    """The modules of :data:`HEAVY` that ``vbikit ARGV`` has imported when it exits."""
    code = ("import json, sys\nsys.argv = ['vbikit', *json.loads(sys.argv[1])]\ntry:\n"
            "    from vbikit.cli import main\n    main()\nexcept SystemExit:\n    pass\n"
            f"print(json.dumps([m for m in {HEAVY!r} if m in sys.modules]), file=sys.stderr)")
    res = subprocess.run([sys.executable, "-c", code, json.dumps(argv)], capture_output=True, text=True, check=True)
    return json.loads(res.stderr.strip().splitlines()[-1])


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--repeat", type=int, default=9, help="timed rounds (default 9, minimum 3)")
    args = p.parse_args()
    vbikit = vbikit_command()
    commands = {
        "vbikit --version": [*vbikit, "--version"],
        'python -c "import numpy"': [sys.executable, "-c", "import numpy"],
        "vbikit --help": [*vbikit, "--help"],
        "python -c pass": [sys.executable, "-c", "pass"],
    }
    os.environ.setdefault("COLUMNS", "100")
    for cmd in commands.values():  # warm the file-system cache; not timed
        wall(cmd)
    times: dict[str, list[float]] = {label: [] for label in commands}
    for _ in range(max(args.repeat, 3)):
        for label, cmd in commands.items():
            times[label].append(wall(cmd))
    print(f"{'command':<28} {'median':>8} {'min':>8} {'max':>8}  [s], {max(args.repeat, 3)} rounds")
    for label, ts in times.items():
        print(f"{label:<28} {statistics.median(ts):8.3f} {min(ts):8.3f} {max(ts):8.3f}")
    version, numpy = times["vbikit --version"], times['python -c "import numpy"']
    print(f"vbikit --version / import numpy: {statistics.median(version) / statistics.median(numpy):.2f} (medians), "
          f"{min(version) / min(numpy):.2f} (fastest runs); target <= 3")
    for argv in (["--version"], ["--help"]):
        heavy = loaded_modules(argv)
        print(f"vbikit {' '.join(argv)} imports: {', '.join(heavy) if heavy else 'none of ' + ', '.join(HEAVY)}")


if __name__ == "__main__":
    main()
