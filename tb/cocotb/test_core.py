"""cocotb test of one exported rtu core: streams `rtu encode` words through it and checks every clock.

One generic test, configured by environment variables (tb/cocotb/run.py sets them):
  RTU_IN        <prefix>.in.hex from `rtu encode` (a `// ports:` line naming the input columns, one test a line)
  RTU_EXPECT    <prefix>.out.hex from `rtu encode`: the bit-accurate model's output words, one test a line
  RTU_CAPTURED  where to write the output words that left the core, in the .out.hex form (for `rtu decode`)
  RTU_LATENCY   clocks from a test's clock edge to its result's (default: the `latency N clocks` header)
  RTU_SEED      seed of the bubbles and the bubble data (default 1)
  RTU_BUBBLES   probability of a bubble (valid_in low, random data) before each test (default 0.25)
  RTU_RESET     1 (default): one synchronous reset mid-stream; the tests in flight at that edge must never
                leave; they are then sent again, so every test leaves once, in order
  RTU_STATS     optional: a JSON file for the measured figures (tests, clocks, wall-clock seconds)

Checked on every clock after the initial reset (two clocks of `rst`): `valid_out` is high exactly L clocks
after each test's edge and low otherwise (never X), `tag_out` is the test's tag, and every output word equals
the expected line bit for bit. A failure names the test number, the port, and the words got and wanted.
"""

import json
import os
import random
import re
import time

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

MAX_ERRORS = 20


def read_words(path):
    """(columns, rows, latency) of a .in.hex/.out.hex file: rows are lists of ints, one per column."""
    cols, rows, latency = None, [], None
    with open(path) as f:
        for lineno, line in enumerate(f, 1):
            s = line.strip()
            if not s:
                continue
            if s.startswith("//"):
                m = re.match(r"//\s*ports:\s*(.*)$", s)
                if m:
                    cols = m.group(1).split()
                m = re.search(r"latency (\d+) clocks", s)
                if m and latency is None:
                    latency = int(m.group(1))
                continue
            if cols is None:
                raise ValueError(f"{path}:{lineno}: a data line before the `// ports:` line")
            words = s.split()
            if len(words) != len(cols):
                raise ValueError(f"{path}:{lineno}: {len(words)} words for {len(cols)} ports")
            rows.append([int(w, 16) for w in words])
    if cols is None:
        raise ValueError(f"{path}: no `// ports:` line")
    return cols, rows, latency


def width(handle):
    return len(handle)


def read_port(dut, name):
    """The port's value as an int, or None when it has X or Z bits."""
    v = getattr(dut, name).value
    if not v.is_resolvable:
        return None
    return int(v)


@cocotb.test()
async def stream_checked(dut):
    in_path = os.environ["RTU_IN"]
    exp_path = os.environ["RTU_EXPECT"]
    cap_path = os.environ["RTU_CAPTURED"]
    in_cols, tests, lat_in = read_words(in_path)
    out_cols, expect, _ = read_words(exp_path)
    latency = int(os.environ.get("RTU_LATENCY") or lat_in or 0)
    assert latency > 0, "no latency: set RTU_LATENCY or give a file with a `latency N clocks` header"
    assert len(tests) == len(expect), f"{len(tests)} tests in {in_path}, {len(expect)} results in {exp_path}"
    assert "tag_in" in in_cols and "tag_out" in out_cols, "the files need tag_in and tag_out columns"
    for name in in_cols + out_cols + ["clock", "rst", "valid_in", "valid_out"]:
        assert hasattr(dut, name), f"port {name} named in the files is not a port of {dut._name}"
    rng = random.Random(int(os.environ.get("RTU_SEED", "1")))
    p_bubble = float(os.environ.get("RTU_BUBBLES", "0.25"))
    reset_check = os.environ.get("RTU_RESET", "1") != "0"
    n = len(tests)
    tag_out_col = out_cols.index("tag_out")
    in_handles = [getattr(dut, c) for c in in_cols]
    in_widths = [width(h) for h in in_handles]
    out_handles = [getattr(dut, c) for c in out_cols]
    out_digits = [(width(h) + 3) // 4 for h in out_handles]
    for i, (c, w) in enumerate(zip(in_cols, in_widths)):
        too_wide = [k for k, row in enumerate(tests) if row[i] >> w]
        assert not too_wide, f"test {too_wide[0]}: word {tests[too_wide[0]][i]:x} of {c} does not fit {w} bits"

    errors = []
    captured = []

    def error(msg):
        errors.append(msg)
        dut._log.error(msg)

    # The clock starts low: rising edge k at 10k-5 ns, falling edge k at 10k ns. At falling edge k the
    # outputs show the state after rising edge k, and the inputs driven there are taken at rising edge k+1.
    # A test taken at rising edge E must be sampled (valid_out high, its words) at rising edge E+L, so it
    # is visible from rising edge E+L-1 on: it is checked at falling edge E+L-1.
    dut.rst.value = 1
    dut.valid_in.value = 0
    for h in in_handles:
        h.value = 0
    Clock(dut.clock, 10, unit="ns").start(start_high=False)
    await RisingEdge(dut.clock)  # rising edge 1 (waiting for a falling edge first would see X -> 0 at 0 ns)

    due = {}  # rising edge -> test index whose result must leave there
    recent = {}  # tag -> (test index, edge it was due): names a result that left at the wrong clock
    edge = 0
    reset_edges = 2  # rst high at edges 1 and 2
    nxt = 0  # next test to send
    reset_want = min(2, latency - 1)  # tests in flight wanted at the mid-stream reset (at most L-1 can be)
    mid_reset_done = not reset_check or reset_want == 0
    mid_reset_edge = None
    dropped = []
    dropped_due = {}  # tag -> test index, for the tests dropped by the mid-stream reset
    sent = 0  # tests applied, counting those sent again after the reset
    t0 = None
    drain = 0
    while True:
        await FallingEdge(dut.clock)
        edge += 1
        # ---- check the outputs after rising edge `edge`
        if edge >= reset_edges:
            vo = read_port(dut, "valid_out")
            want = due.pop(edge, None)
            if vo is None:
                error(f"clock {edge}: valid_out is X/Z")
            elif vo == 1:
                words = [read_port(dut, c) for c in out_cols]
                captured.append(words)
                if want is None:
                    tag = words[tag_out_col]
                    hint = ""
                    if tag is not None and tag in dropped_due and edge <= mid_reset_edge + latency:
                        k = dropped_due[tag]
                        hint = f" (tag_out {tag:04x} is test {k}, in flight at the reset at clock {mid_reset_edge}: it must never leave)"
                    elif tag is not None and tag in recent:
                        k, e = recent[tag]
                        hint = f" (tag_out {tag:04x} is test {k}, due at clock {e}: latency {latency + edge - e}, not {latency})"
                    error(f"clock {edge}: valid_out high with no result due{hint}")
                else:
                    for c, got, exp in zip(out_cols, words, expect[want]):
                        if got is None:
                            error(f"test {want}: port {c}: got X/Z, want {exp:x}")
                        elif got != exp:
                            error(f"test {want}: port {c}: got {got:x}, want {exp:x}")
                    if words[tag_out_col] is not None and words[tag_out_col] != want % 65536:
                        error(f"test {want}: tag_out {words[tag_out_col]:04x} is not the test's tag {want % 65536:04x}")
            elif want is not None:
                error(f"test {want}: no result {latency} clocks after it entered (valid_out low at clock {edge})")
        if len(errors) >= MAX_ERRORS:
            break
        # ---- drive the inputs for rising edge `edge + 1`
        nedge = edge + 1
        if nedge <= reset_edges:
            dut.rst.value = 1
            dut.valid_in.value = 0
            continue
        if not mid_reset_done and ((nxt >= n // 2 and len(due) >= reset_want) or (nxt >= n and due)):
            # A reset at edge `nedge`: every result not yet out (due at nedge or later) is dropped, and so
            # is the test applied with valid_in high at that same edge (when one is left to apply).
            mid_reset_done = True
            mid_reset_edge = nedge
            dropped = sorted(due.values())
            dut.rst.value = 1
            if nxt < n:
                for h, word in zip(in_handles, tests[nxt]):
                    h.value = word
                dut.valid_in.value = 1
                dropped.append(nxt)
                sent += 1
            else:
                dut.valid_in.value = 0
                for h, w in zip(in_handles, in_widths):
                    h.value = rng.getrandbits(w)
            dropped_due = {k % 65536: k for k in dropped}
            dut._log.info(f"reset at clock {nedge}: tests {dropped} in flight or entering must never leave")
            due.clear()
            nxt = dropped[0]
            continue
        dut.rst.value = 0
        if nxt < n and rng.random() >= p_bubble:
            if t0 is None:
                t0 = time.perf_counter()
            for h, word in zip(in_handles, tests[nxt]):
                h.value = word
            dut.valid_in.value = 1
            due[nedge + latency - 1] = nxt
            recent[nxt % 65536] = (nxt, nedge + latency - 1)
            nxt += 1
            sent += 1
        else:
            dut.valid_in.value = 0
            for h, w in zip(in_handles, in_widths):
                h.value = rng.getrandbits(w)
            if nxt >= n and not due:
                drain += 1
                if drain > latency + 2:
                    break
    seconds = time.perf_counter() - (t0 or time.perf_counter())

    with open(cap_path, "w") as f:
        f.write(f"// cocotb: output words of {dut._name} captured under the simulator, in the order they left\n")
        f.write("// ports: " + " ".join(out_cols) + "\n")
        for words in captured:
            f.write(" ".join("x" * d if w is None else f"{w:0{d}x}" for w, d in zip(words, out_digits)) + "\n")

    stats = {
        "module": dut._name,
        "tests": n,
        "sent": sent,
        "clocks": edge,
        "latency": latency,
        "seconds": seconds,
        "reset_edge": mid_reset_edge,
        "dropped": dropped,
        "errors": len(errors),
    }
    if os.environ.get("RTU_STATS"):
        with open(os.environ["RTU_STATS"], "w") as f:
            json.dump(stats, f)
    dut._log.info(
        f"{n} tests ({sent} sent, {len(dropped)} again after the reset at clock {mid_reset_edge}), "
        f"{edge} clocks, {seconds:.3f} s"
    )
    if reset_check and reset_want and mid_reset_edge is None and len(errors) < MAX_ERRORS:
        error("the mid-stream reset never met a test in flight (too few tests?)")
    more = f" (stopped after {MAX_ERRORS})" if len(errors) >= MAX_ERRORS else ""
    assert not errors, f"{len(errors)} errors{more}; first: " + "; ".join(errors[:5])
    assert len(captured) == n, f"{len(captured)} results left for {n} tests"
