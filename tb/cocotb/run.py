#!/usr/bin/env python3
"""Builds one exported rtu core with Icarus Verilog and runs tb/cocotb/test_core.py on it (cocotb 2.x runner).

Usage:
  run.py --verilog DIR/verilog/M.v --in P.in.hex --expect P.out.hex [--module M] [--latency L]
         [--build-dir DIR] [--captured FILE] [--seed S] [--bubbles P] [--no-reset-check] [--no-vcd]

Writes into the build folder (default <out>/cocotb/<module>, out = $RTU_OUT or `out`): the Icarus build,
results.xml, <module>.vcd (every signal of the core, a VCD for GTKWave or Surfer), captured.out.hex (the
output words in the order they left, for `rtu decode`) and stats.json. Prints one line
`cocotb: <module>: N tests, T s, X tests/s` (wall-clock of the streamed, checked run under the simulator,
without the build) and exits non-zero when the test fails.

The VCD: cocotb's Icarus runner with waves=True adds a dump module (`cocotb_iverilog_dump`, $dumpfile from the
`+dumpfile_path=` plusarg, $dumpvars of the top) but always starts vvp with `-fst`; the runner below passes
`-vcd` instead, so the same dump module writes a VCD.
"""

import argparse
import json
import os
import re
import sys
from pathlib import Path

from cocotb_tools.check_results import get_results
from cocotb_tools.runner import Icarus

HERE = Path(__file__).resolve().parent


class IcarusVcd(Icarus):
    """Icarus with waves written as VCD rather than FST."""

    def _test_command(self):
        cmds = super()._test_command()
        return [["-vcd" if a == "-fst" else a for a in cmd] for cmd in cmds]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--verilog", required=True, help="the exported Verilog of the core (<out>/verilog/<module>.v)")
    ap.add_argument("--module", help="top module (default: the file's base name)")
    ap.add_argument("--in", dest="inp", required=True, help="<prefix>.in.hex from `rtu encode`")
    ap.add_argument("--expect", required=True, help="<prefix>.out.hex from `rtu encode`")
    ap.add_argument("--latency", type=int, help="clocks (default: latency.csv beside the Verilog, else the header)")
    ap.add_argument("--build-dir", help="default <out>/cocotb/<module>")
    ap.add_argument("--captured", help="default <build-dir>/captured.out.hex")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--bubbles", type=float, default=0.25)
    ap.add_argument("--no-reset-check", action="store_true")
    ap.add_argument("--no-vcd", action="store_true")
    a = ap.parse_args()

    verilog = Path(a.verilog).resolve()
    module = a.module or verilog.stem
    build = Path(a.build_dir or Path(os.environ.get("RTU_OUT", "out")) / "cocotb" / module).resolve()
    build.mkdir(parents=True, exist_ok=True)
    captured = Path(a.captured or build / "captured.out.hex").resolve()
    vcd = build / f"{module}.vcd"
    stats = build / "stats.json"
    latency = a.latency
    if latency is None:
        csv = verilog.parent / "latency.csv"
        if csv.exists():
            for line in csv.read_text().splitlines():
                f = line.split(",")
                if len(f) == 2 and f[0] == module:
                    latency = int(f[1])
    if latency is None:
        m = re.search(r"latency (\d+) clocks", Path(a.inp).read_text(errors="replace")[:4000])
        latency = int(m.group(1)) if m else None
    if latency is None:
        sys.exit(f"cocotb: {module}: no latency (give --latency, or latency.csv beside the Verilog)")
    for p in (stats, vcd, captured):
        p.unlink(missing_ok=True)

    waves = not a.no_vcd
    runner = IcarusVcd()
    log = build / "build.log"
    runner.build(
        sources=[verilog],
        hdl_toplevel=module,
        build_dir=build,
        timescale=("1ns", "1ps"),
        waves=waves,
        always=True,
        log_file=log,
    )
    env = {
        "RTU_IN": str(Path(a.inp).resolve()),
        "RTU_EXPECT": str(Path(a.expect).resolve()),
        "RTU_CAPTURED": str(captured),
        "RTU_LATENCY": str(latency),
        "RTU_SEED": str(a.seed),
        "RTU_BUBBLES": str(a.bubbles),
        "RTU_RESET": "0" if a.no_reset_check else "1",
        "RTU_STATS": str(stats),
    }
    sys.path.insert(0, str(HERE))  # the runner passes sys.path on as PYTHONPATH: test_core must be found
    xml = runner.test(
        test_module="test_core",
        hdl_toplevel=module,
        build_dir=build,
        test_dir=build,
        waves=waves,
        plusargs=[f"+dumpfile_path={vcd}"] if waves else [],
        extra_env=env,
        seed=a.seed,
        log_file=build / "sim.log",
    )
    ntests, nfailed = get_results(xml)
    if stats.exists():
        s = json.loads(stats.read_text())
        rate = s["tests"] / s["seconds"] if s["seconds"] > 0 else 0.0
        print(f"cocotb: {module}: {s['tests']} tests, {s['seconds']:.2f} s, {rate:,.0f} tests/s"
              f" ({s['clocks']} clocks, latency {s['latency']}, reset at clock {s['reset_edge']}"
              f" dropped {len(s['dropped'])}{', VCD ' + str(vcd) if waves and vcd.exists() else ''})")
    if nfailed or ntests == 0:
        msg = ""
        try:
            text = (build / "sim.log").read_text(errors="replace")
            m = re.findall(r"AssertionError: (.*)", text)
            msg = ": " + m[-1] if m else ""
        except OSError:
            pass
        print(f"cocotb: {module}: FAILED{msg} (log {build / 'sim.log'})", file=sys.stderr)
        sys.exit(1)
    if waves and not vcd.exists():
        print(f"cocotb: {module}: no VCD at {vcd}", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
