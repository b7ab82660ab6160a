#!/usr/bin/env python3
"""Writes a timing wrapper around one exported tester, for place-and-route (scripts/timing).

The testers have more input and output bits than any ECP5 package has pins. The wrapper
`wrap_<module>` has three ports, `clk`, `din` and `dout`:
  - every core input bit is driven by its own flip-flop of one input shift register fed by `din`
    (no logic between those flip-flops and the core);
  - every core output bit is XORed into its own flip-flop of an output shift register that continues
    the input one and ends at `dout` (one 2-input XOR behind each core output).
So no core port is left floating or constant, nothing is optimised away, and every timed path starts
and ends on a flip-flop: the core's own registers, or the wrapper's for a core input or output that
is not registered inside the core. The core instance `core` keeps its own level of hierarchy
(`keep_hierarchy`): synthesised flat, Yosys merges a core register that copies an input bit with the
shift register's next flip-flop (the same D), and the core's cell counts would no longer be its own.
nextpnr flattens the design itself, so timing is over the whole. The wrapper's registers are named
`wrap_in__<port>` and `wrap_out__<port>`, so a critical path that starts or ends on them says which
core port it is.

The core's `clock` input is driven by `clk`. Ports are read from the top module's declarations as
the export writes them (`input wire  [15:0] ray_o_lo_0;`, `output reg  hit;`, optionally
`signed`), or ANSI-style in the header. Names with `$` (Verilog from rust-hdl before the plain-name
export) are written as escaped identifiers (`\\ray_o_lo$0 `, with the trailing space).

Usage: scripts/timing_wrap.py CORE.v MODULE WRAP.v
  Prints one line `in_bits out_bits in_ports out_ports` on stdout (the wrapper's flip-flops are
  in_bits + out_bits). Exits 1 with a message on stderr when the module or a port is not understood.
"""
import re
import sys

CLOCK = "clock"


def fail(msg):
    print(f"timing_wrap: {msg}", file=sys.stderr)
    sys.exit(1)


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def plain(name):
    """A port name without the escaped-identifier backslash."""
    return name[1:] if name.startswith("\\") else name


def esc(name):
    """A Verilog escaped identifier for any name (the trailing space ends it)."""
    return "\\" + name + " "


NAME = r"(\\\S+|[A-Za-z_][A-Za-z0-9_$]*)"
# The start of a declaration: direction, optional net type, optional signed, optional [msb:lsb].
HEAD = re.compile(r"^\s*(input|output|inout)\b\s*(?:wire|reg|logic)?\s*(signed\b)?\s*"
                  r"(?:\[\s*(\d+)\s*:\s*(\d+)\s*\])?\s*(.*)$", re.S)


def read_ports(path, module):
    """[(direction, name, width)] of `module` in `path`, in header order."""
    text = strip_comments(open(path, encoding="utf-8").read())
    # The module's text up to its `endmodule` (rust-hdl writes children as separate modules).
    m = re.search(r"\bmodule\s+" + re.escape(module) + r"\s*\((.*?)\)\s*;(.*?)\bendmodule\b",
                  text, flags=re.S)
    if not m:
        fail(f"{path}: no module `{module}`")
    header, body = m.group(1), m.group(2)
    decls = {}  # name -> (direction, width)
    order = []
    current = None  # the declaration an ANSI header item without its own direction continues

    def declare(stmt):
        """Records `input wire [3:0] a, b` (names after the range); returns (direction, width) or None."""
        h = HEAD.match(stmt)
        if not h:
            return None
        direction, msb, lsb = h.group(1), h.group(3), h.group(4)
        if msb is not None and int(lsb) != 0:
            fail(f"{path}: module `{module}`: `{stmt.strip()}` is [{msb}:{lsb}], expected [N:0]")
        kind = (direction, int(msb) + 1 if msb is not None else 1)
        for n in h.group(5).split(","):
            n = n.strip()
            if not re.fullmatch(NAME, n):
                fail(f"{path}: module `{module}`: cannot read the declaration `{stmt.strip()}`")
            decls[plain(n)] = kind
        return kind

    # ANSI headers carry the declarations; rust-hdl's is a list of names declared in the body.
    for item in [s.strip() for s in header.split(",") if s.strip()]:
        kind = declare(item)
        if kind is not None:
            current = kind
            order.append(plain(HEAD.match(item).group(5).strip()))
        elif re.fullmatch(NAME, item):
            order.append(plain(item))
            if current is not None:
                decls[plain(item)] = current
        else:
            fail(f"{path}: module `{module}`: cannot read the header item `{item}`")
    for stmt in body.split(";"):
        declare(stmt)
    ports = []
    for name in order:
        if name not in decls:
            fail(f"{path}: module `{module}`: no input/output declaration for port `{name}`")
        direction, width = decls[name]
        if direction == "inout":
            fail(f"{path}: module `{module}`: inout port `{name}` is not supported")
        ports.append((direction, name, width))
    return ports


def wrapper(module, ports):
    ins = [(n, w) for d, n, w in ports if d == "input" and n != CLOCK]
    outs = [(n, w) for d, n, w in ports if d == "output"]
    if not any(d == "input" and n == CLOCK for d, n, _ in ports):
        fail(f"module `{module}` has no `{CLOCK}` input")
    if not outs:
        fail(f"module `{module}` has no output")
    lines = [
        f"// Timing wrapper of {module}, written by scripts/timing_wrap.py: every core input bit from its own",
        "// flip-flop of an input shift register fed by din, every core output bit XORed into its own",
        "// flip-flop of an output shift register that continues it and ends at dout.",
        f"module wrap_{module}(input wire clk, input wire din, output wire dout);",
    ]

    def rng(w):
        return f"[{w - 1}:0] " if w > 1 else ""

    for n, w in ins:
        lines.append(f"  reg {rng(w)}{esc('wrap_in__' + n)};")
    for n, w in outs:
        lines.append(f"  wire {rng(w)}{esc('core_out__' + n)};")
        lines.append(f"  reg {rng(w)}{esc('wrap_out__' + n)};")
    # The chain: din -> inputs in header order (LSB first) -> outputs (LSB first) -> dout.
    lines.append("  always @(posedge clk) begin")
    prev = "din"
    for n, w in ins:
        r = esc("wrap_in__" + n)
        lines.append(f"    {r} <= {{{r}[{w - 2}:0], {prev}}};" if w > 1 else f"    {r} <= {prev};")
        prev = f"{r}[{w - 1}]" if w > 1 else r
    for n, w in outs:
        r, c = esc("wrap_out__" + n), esc("core_out__" + n)
        lines.append(f"    {r} <= {{{r}[{w - 2}:0], {prev}}} ^ {c};" if w > 1 else f"    {r} <= {prev} ^ {c};")
        prev = f"{r}[{w - 1}]" if w > 1 else r
    lines.append("  end")
    lines.append(f"  assign dout = {prev};")
    conns = [f"    .{CLOCK}(clk)"]
    conns += [f"    .{esc(n)}({esc('wrap_in__' + n)})" for n, _ in ins]
    conns += [f"    .{esc(n)}({esc('core_out__' + n)})" for n, _ in outs]
    # keep_hierarchy: Yosys optimises the core on its own, so it merges none of the core's registers
    # that copy an input with the shift register, and its cell counts are the core's alone.
    lines.append(f"  (* keep_hierarchy *) {esc(module)} core (")
    lines.append(",\n".join(conns))
    lines.append("  );")
    lines.append(f"endmodule // wrap_{module}")
    return "\n".join(lines) + "\n", sum(w for _, w in ins), sum(w for _, w in outs), len(ins), len(outs)


def main():
    if len(sys.argv) != 4:
        print(__doc__.split("Usage: ")[1].split("\n")[0], file=sys.stderr)
        sys.exit(2)
    core, module, out = sys.argv[1:]
    text, in_bits, out_bits, in_ports, out_ports = wrapper(module, read_ports(core, module))
    with open(out, "w", encoding="utf-8") as f:
        f.write(text)
    print(in_bits, out_bits, in_ports, out_ports)


if __name__ == "__main__":
    main()
