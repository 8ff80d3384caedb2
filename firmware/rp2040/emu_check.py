#!/usr/bin/env python3
"""Runs the RP2040 firmware on the emulated RP2040 (../shared/rp2040-emu) and
checks what it sends the LCD:

* the start-up commands are the documented ones (SLPOUT, MADCTL, INVON,
  COLMOD, NORON, DISPON);
* frame 0 is the start-up clear (all black), and every later frame's CRC-32
  equals the CRC the firmware's build script computed for that view on the
  host (the firmware keeps them in its `EXPECTED_CRCS` static, read here
  from the ELF);
* every whole frame's period, in emulated cycles (deterministic), is at
  most the budget;
* the firmware's own `FRAME_US` agrees with the measured period, and
  `FAULT` is 0.

usage: emu_check.py [--elf PATH] [--frames N] [--budget CYCLES (default 5000000)]
                    [--emu DIR] [--out DIR]
Exits 1 on any failure, after printing what differed."""

import argparse
import json
import re
import struct
import subprocess
import sys
import zlib
from pathlib import Path

START_UP = [0x11, 0x36, 0x21, 0x3A, 0x13, 0x29]
FRAME_BYTES = 240 * 240 * 2
CLK_HZ = 125_000_000


def elf_symbol_words(elf: bytes, name: str) -> list[int]:
    """The 32-bit little-endian words of a symbol's initial value."""
    if elf[:4] != b"\x7fELF" or elf[4] != 1:
        raise SystemExit("not a 32-bit ELF")
    phoff, shoff = struct.unpack_from("<II", elf, 0x1C)
    phentsize, phnum, shentsize, shnum = struct.unpack_from("<HHHH", elf, 0x2A)
    sections = [struct.unpack_from("<IIIIIIIIII", elf, shoff + i * shentsize) for i in range(shnum)]
    for sh in sections:
        if sh[1] != 2:  # SHT_SYMTAB
            continue
        off, size, link, entsize = sh[4], sh[5], sh[6], sh[9]
        stroff = sections[link][4]
        for s in range(off, off + size, entsize):
            name_off, value, ssize = struct.unpack_from("<III", elf, s)
            end = elf.index(b"\0", stroff + name_off)
            if elf[stroff + name_off:end].decode("latin1") != name:
                continue
            for i in range(phnum):
                ptype, poff, vaddr, _paddr, filesz = struct.unpack_from("<IIIII", elf, phoff + i * phentsize)
                if ptype == 1 and vaddr <= value < vaddr + filesz:
                    start = poff + value - vaddr
                    return list(struct.unpack_from(f"<{ssize // 4}I", elf, start))
            raise SystemExit(f"{name} is not in a loaded segment")
    raise SystemExit(f"symbol {name} not found (is it #[used] and #[no_mangle]?)")


def main() -> int:
    p = argparse.ArgumentParser(
        description="Runs the RP2040 firmware on the emulated RP2040 (rp2040js), checks every "
                    "frame's CRC against the host's and each frame period against a budget. "
                    "Paths resolve from the directory the command is run in.")
    p.add_argument("--elf", default="firmware/rp2040/target/thumbv6m-none-eabi/release/zline-rp2040",
                   help="the firmware to run (default: what `cargo fw-rp2040` builds)")
    p.add_argument("--frames", type=int, default=4, help="firmware frames to check after the start-up clear")
    p.add_argument("--budget", type=int, default=5_000_000,
                   help="most cycles a frame period may take (default 5,000,000: the torus knot's "
                        "budget, docs/results/mcu.md; a bigger mesh needs its own)")
    p.add_argument("--emu", default="../shared/rp2040-emu",
                   help="the rp2040js emulator's folder, with its node_modules (npm ci --prefix DIR)")
    p.add_argument("--out", default="target/rp2040-emu",
                   help="where the decoded frames and the emulator's log go")
    a = p.parse_args()

    expected = elf_symbol_words(Path(a.elf).read_bytes(), "EXPECTED_CRCS")
    run = subprocess.run(
        ["node", f"{a.emu}/run-fw.mjs", "--elf", a.elf, "--frames", str(a.frames + 2),
         "--out", a.out, "--png", "first", "--quiet"],
        capture_output=True, text=True)
    if run.returncode != 0:
        print(run.stdout, run.stderr, sep="\n")
        print("the emulator failed")
        return 1
    summary = json.loads((Path(a.out) / "summary.json").read_text())
    frames = summary["frames"]
    problems = []
    if summary["initCommands"] != START_UP:
        problems.append(f"start-up commands {summary['initCommands']} != {START_UP}")
    black = zlib.crc32(bytes(FRAME_BYTES))
    for f in frames:
        k = f["index"]
        want = black if k == 0 else expected[(k - 1) % len(expected)]
        got = int(f["crc32"], 16)
        ok = got == want and f["pixels"] == FRAME_BYTES // 2
        period = f.get("period")
        note = ""
        if k >= 1 and period is not None:
            note = f" period {period} cycles = {period / CLK_HZ * 1e3:.2f} ms = {CLK_HZ / period:.2f} fps at 125 MHz"
            if period > a.budget:
                problems.append(f"frame {k}: period {period} cycles over the budget of {a.budget}")
        print(f"frame {k}: crc32 {got:08X} expected {want:08X} {'ok' if ok else 'MISMATCH'}{note}")
        if not ok:
            problems.append(f"frame {k}: crc32 {got:08X} != expected {want:08X}")
    whole = [f["period"] for f in frames if f["index"] >= 1 and f.get("period") is not None]
    if len(whole) < a.frames:
        problems.append(f"only {len(whole)} whole frames were measured")
    m = re.search(r"FRAME_US=(\w+) FAULT=(\w+)", run.stdout)
    if not m:
        problems.append("FRAME_US and FAULT are not in the ELF (are they #[used]?)")
    else:
        frame_us, fault = m.group(1), m.group(2)
        if fault != "0":
            problems.append(f"FAULT = {fault}")
        # FRAME_US is the period of the frame before the last one started.
        if frame_us == "null" or not whole:
            problems.append(f"FRAME_US = {frame_us}")
        else:
            measured = whole[-1] / CLK_HZ * 1e6
            if abs(int(frame_us) - measured) > 0.02 * measured + 2:
                problems.append(f"FRAME_US = {frame_us} but the measured period is {measured:.0f} us")
            print(f"FRAME_US {frame_us} (measured {measured:.0f} us), FAULT {fault}")
    if whole:
        worst = max(whole)
        print(f"frame period: at most {worst} cycles ({CLK_HZ / worst:.2f} fps at 125 MHz), budget {a.budget}")
    for problem in problems:
        print("FAIL:", problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
