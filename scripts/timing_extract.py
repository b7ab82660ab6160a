#!/usr/bin/env python3
"""Reads one module's synthesis and place-and-route results and writes its rows (scripts/timing).

From DIR (the module's folder under <out>/timing):
  core.v   the tester's Verilog (for the registers' names);
  x.json   Yosys netlist of wrap_<module>, the core kept as the instance `core` (its own module);
  r.json   nextpnr's --report: post-route Fmax per clock and the critical paths;
  pnr.log  nextpnr's log: the last "Max frequency for clock" line, checked against r.json, and
           "Total LUT4s" (the whole design's, carries included).
Counts are of the core module alone: on ECP5 LUT4, CCU2C (carry pairs), TRELLIS_FF, MULT18X18D; on
iCE40 (a DEVICE starting with iCE40) SB_LUT4, SB_CARRY, the SB_DFF* flip-flops, SB_MAC16; the
wrapper's cells (one flip-flop per core input and output bit, about one LUT4 per output bit) are
counted separately and checked against the bits the wrapper was written with.
The critical path is the clock-to-clock one; its start and end cells are named by the register they
hold: the core's register by its plain name (rtl::verilog::plain_name), its path in the core
(`exit_q2_0`, the instance of the child module `<module>_exit_q2_0`; `exit_q2_0_r`, the register `r`
of a cut point (`rtl::cut::Cut`); `mul_entry_2.p_q`, a register `p_q` inside a child; no `core.` prefix, no bit
index), found from the flip-flop's
source line in core.v; `wrap_in:<port>` / `wrap_out:<port>` for the wrapper's shift-register
flip-flop at a core input or output; `<cell type>:<name>` for a cell other than a flip-flop.

Usage: scripts/timing_extract.py DIR MODULE LATENCY DEVICE SEED IN_BITS OUT_BITS SYNTH_S PNR_S
  (or --header DEVICE / --md-header DEVICE: print the CSV / markdown table header for DEVICE's family)
  Writes DIR.row (the CSV row of timing.csv) and DIR.md (the markdown row of timing.md); prints a
  one-line summary on stdout. Exits 1 with a message on stderr when a result is missing.
"""
import collections
import json
import os
import re
import sys

# Net and cell names that Yosys's autoname makes from cell types: the suffix from the first type on.
AUTONAME = re.compile(r"_(TRELLIS_FF|TRELLIS_COMB|LUT4|CCU2C|PFUMX|L6MUX21|MULT18X18D|ALU54B|DP16KD|"
                      r"TRELLIS_DPR16X4|DPR16X4C|SB_LUT4|SB_CARRY|SB_DFF[A-Z]*|SB_MAC16|SB_RAM40_4K)_.*$")


class Cells:
    """The cell types of a family: (LUT, carry, DSP, the LUT total's log pattern) and what a
    flip-flop is; the CSV and markdown headers name them."""

    def __init__(self, device):
        self.ice40 = device.startswith("iCE40")
        if self.ice40:
            self.lut, self.carry, self.dsp = "SB_LUT4", "SB_CARRY", "SB_MAC16"
            self.total = r"ICESTORM_LC:\s+(\d+)/"
        else:
            self.lut, self.carry, self.dsp = "LUT4", "CCU2C", "MULT18X18D"
            self.total = r"Total LUT4s:\s+(\d+)/"

    def is_ff(self, kind):
        return kind.startswith("SB_DFF") if self.ice40 else kind == "TRELLIS_FF"

    def csv_header(self):
        return "module,latency,device,lut4,ff,{},fmax_mhz,crit_from,crit_to,seed".format(
            "mac16" if self.ice40 else "mult18")

    def md_header(self):
        total = "LC all (nextpnr)" if self.ice40 else "LUT4 all (nextpnr)"
        cols = ["module", "latency (clocks)", "LUT4", self.carry, "FF", self.dsp, "Fmax (MHz)",
                "critical path from", "to", "path ns (routing)", "wrapper FF in+out / LUT4", total,
                "other core cells", "synth s", "P&R s"]
        return "| " + " | ".join(cols) + " |\n|" + "---|" * len(cols)


class Source:
    """The modules of the core's Verilog, by line: which module a source line is in, its ports and regs."""

    def __init__(self, path, top):
        self.top = top
        self.modules = []  # (first line, last line, name, ports, regs)
        text = open(path, encoding="utf-8").read().split("\n")
        cur = None
        for i, line in enumerate(text, 1):
            m = re.match(r"\s*module\s+(\\\S+|[A-Za-z_][A-Za-z0-9_$]*)\s*\(([^)]*)\)", line)
            if m:
                cur = [i, None, m.group(1).lstrip("\\"), [p.strip() for p in m.group(2).split(",")], set()]
            elif cur is not None and re.match(r"\s*endmodule\b", line):
                cur[1] = i
                self.modules.append(tuple(cur))
                cur = None
            elif cur is not None:
                r = re.match(r"\s*(?:output\s+)?reg\b[^;]*?([A-Za-z_][A-Za-z0-9_$]*)\s*;", line)
                if r:
                    cur[4].add(r.group(1))

    def register(self, src, net):
        """The register of a flip-flop whose `src` attribute is `core.v:LINE...`, or None.
        In a child module `<top>_<path>`: <path>, and `.<reg>` after it when the child declares more
        than one reg and the flip-flop's net says which. In the top module: the net's name."""
        m = re.match(r"core\.v:(\d+)\.", src)
        if not m:
            return None
        line = int(m.group(1))
        for first, last, name, ports, regs in self.modules:
            if first <= line <= last:
                if name == self.top:
                    return net
                if not name.startswith(self.top + "_"):
                    return None
                path = name[len(self.top) + 1:]
                local = net.rsplit(".", 1)[-1] if net else None
                if len(regs) > 1 and local in regs:
                    return f"{path}.{local}"
                return path
        return None


def fail(msg):
    print(f"timing_extract: {msg}", file=sys.stderr)
    sys.exit(1)


def load(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        fail(f"cannot read {path}: {e}")


class Netlist:
    """The wrapper and core modules of a Yosys JSON netlist, with bit -> net name lookups."""

    def __init__(self, path, module, cells):
        self.cells = cells
        mods = load(path)["modules"]
        self.top_name = f"wrap_{module}"
        if self.top_name not in mods:
            fail(f"{path}: no module {self.top_name}")
        self.top = mods[self.top_name]
        inst = self.top["cells"].get("core")
        if inst is None or inst["type"] not in mods:
            fail(f"{path}: {self.top_name} has no hierarchical instance `core` (keep_hierarchy lost?)")
        self.core = mods[inst["type"]]
        self.names = {id(m): self._bit_names(m) for m in (self.top, self.core)}
        self.source = Source(os.path.join(os.path.dirname(path), "core.v"), inst["type"])

    @staticmethod
    def _bit_names(mod):
        names = collections.defaultdict(list)
        for n, v in mod["netnames"].items():
            if v.get("hide_name"):
                continue
            for b in v["bits"]:
                names[b].append(n)
        return names

    def cell(self, name):
        """(module, cell) of a nextpnr cell name: `core.<x>` is cell <x> of the core."""
        if name.startswith("core.") and name[5:] in self.core["cells"]:
            return self.core, self.core["cells"][name[5:]]
        if name in self.top["cells"]:
            return self.top, self.top["cells"][name]
        return None, None

    def net_name(self, mod, bit):
        """The reader's name of a net bit: the wrapper's shift register, else the name in the
        module's own scope (fewest dots: not a flattened child's port), else None. Names that
        Yosys made up from cell names (`..._TRELLIS_FF_Q_DI_LUT4_Z...`) do not count."""
        names = [n for n in self.names[id(mod)].get(bit, []) if not AUTONAME.search(n)]
        wrap = sorted(n for n in names if n.startswith(("wrap_in__", "wrap_out__")))
        if wrap:
            kind, port = wrap[0].split("__", 1)
            return f"{kind}:{port}"
        if not names:
            return None
        return min(names, key=lambda n: (n.count("."), len(n), n))

    def reg_name(self, cell_name, port):
        """Name of the register a path starts (port: its output) or ends on (port: an input)."""
        mod, cell = self.cell(cell_name)
        bare = cell_name[5:] if cell_name.startswith("core.") else cell_name
        if cell is None:
            return AUTONAME.sub("", bare)
        conns = cell["connections"]
        if self.cells.is_ff(cell["type"]):
            n = self.net_name(mod, conns["Q"][0])
            if mod is self.core:
                # Flattening keeps one name per net, often a child's input port (`mul_exit_0.a`),
                # so the register is found where the Verilog declares it: a rust-hdl register is a
                # child module `<top>_<path>` of its own (ports d, q, clock), named <path>.
                r = self.source.register(cell.get("attributes", {}).get("src", ""), n)
                if r is not None:
                    return r
            return n if n is not None else AUTONAME.sub("", bare)
        # Another cell (a DSP, a RAM): the net of the path's port when it is an output.
        bits = conns.get(port, [])
        n = self.net_name(mod, bits[0]) if bits and cell.get("port_directions", {}).get(port) == "output" else None
        return f"{cell['type']}:{n if n is not None else AUTONAME.sub('', bare)}"

    def count(self, mod, kind):
        return sum(1 for c in mod["cells"].values() if c["type"] == kind)

    def count_ff(self, mod):
        return sum(1 for c in mod["cells"].values() if self.cells.is_ff(c["type"]))


def main():
    if len(sys.argv) == 3 and sys.argv[1] in ("--header", "--md-header"):
        cells = Cells(sys.argv[2])
        print(cells.csv_header() if sys.argv[1] == "--header" else cells.md_header())
        return
    if len(sys.argv) != 10:
        print(__doc__.split("Usage: ")[1].split("\n")[0], file=sys.stderr)
        sys.exit(2)
    d, module, latency, device, seed, in_bits, out_bits, synth_s, pnr_s = sys.argv[1:]
    in_bits, out_bits = int(in_bits), int(out_bits)
    cells = Cells(device)
    net = Netlist(os.path.join(d, "x.json"), module, cells)
    report = load(os.path.join(d, "r.json"))

    # Post-route Fmax: the one clock (driven by clk), from the report; the log's last line agrees.
    clocks = report.get("fmax", {})
    if len(clocks) != 1:
        fail(f"{d}/r.json: expected one clock, found {sorted(clocks)}")
    clock, fm = next(iter(clocks.items()))
    fmax = fm["achieved"]
    log = open(os.path.join(d, "pnr.log"), encoding="utf-8", errors="replace").read()
    lines = re.findall(r"Max frequency for clock '([^']*)': ([0-9.]+) MHz", log)
    if not lines or abs(float(lines[-1][1]) - fmax) > 0.01:
        fail(f"{d}: r.json Fmax {fmax:.2f} MHz disagrees with the log's last line {lines[-1:] or 'none'}")

    paths = [p for p in report.get("critical_paths", [])
             if p.get("from", "").startswith("posedge") and p.get("to", "").startswith("posedge")]
    if not paths or not paths[0]["path"]:
        fail(f"{d}/r.json: no clock-to-clock critical path")
    path = paths[0]["path"]
    crit_from = net.reg_name(path[0]["from"]["cell"], path[0]["from"]["port"])
    crit_to = net.reg_name(path[-1]["to"]["cell"], path[-1]["to"]["port"])
    total = sum(s["delay"] for s in path)
    routing = sum(s["delay"] for s in path if s["type"] == "routing")

    core, top = net.core, net.top
    lut4, ccu2 = net.count(core, cells.lut), net.count(core, cells.carry)
    ff, mult = net.count_ff(core), net.count(core, cells.dsp)
    wrap_ff, wrap_lut = net.count_ff(top), net.count(top, cells.lut)
    if wrap_ff != in_bits + out_bits:
        fail(f"{d}/x.json: the wrapper has {wrap_ff} flip-flops, expected {in_bits} + {out_bits}")
    other = collections.Counter(c["type"] for c in core["cells"].values()
                                if c["type"] not in (cells.lut, cells.carry, cells.dsp, "$scopeinfo")
                                and not cells.is_ff(c["type"]))
    # nextpnr's total for the whole design: on ECP5 logic LUTs (core and wrapper) and two per CCU2C;
    # on iCE40 the logic cells.
    luts = re.findall(cells.total, log)
    all_lut4 = luts[-1] if luts else ""

    row = [module, latency, device, lut4, ff, mult, f"{fmax:.1f}", crit_from, crit_to, seed]
    with open(d + ".row", "w", encoding="utf-8") as f:
        f.write(",".join(str(x) for x in row) + "\n")
    others = ", ".join(f"{v} {k}" for k, v in sorted(other.items())) or "-"
    md = [module, latency, lut4, ccu2, ff, mult, f"**{fmax:.1f}**", f"`{crit_from}`", f"`{crit_to}`",
          f"{total:.2f} ({100 * routing / total:.0f}%)" if total else "-",
          f"{in_bits}+{out_bits} / {wrap_lut}", all_lut4, others, synth_s, pnr_s]
    with open(d + ".md", "w", encoding="utf-8") as f:
        f.write("| " + " | ".join(str(x) for x in md) + " |\n")
    print(f"{fmax:.1f} MHz ({crit_from} -> {crit_to}), {lut4} LUT4, {ff} FF, {mult} {cells.dsp}")


if __name__ == "__main__":
    main()
