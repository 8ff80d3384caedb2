#!/usr/bin/env python3
"""Charges the instructions of one frame of firmware/qemu to source lines.

    charge.py TRACE ELF [PATTERN]

TRACE is QEMU's `-d in_asm,exec,nochain` log: each translated block's
instructions once ("IN:" then one line an instruction), and a "Trace"
line each time a block runs. The window is one frame: from just after
the last block that runs `Crc32Sink` code (the end of the checksummed
frame) to the first block that runs semihosting code (the report printed
after the counted frame). Every instruction of every block run in it is
charged to its address, and each address to its inlined call chain by
`llvm-addr2line -f -C -i`. Prints the window's instruction count, then
the top innermost functions, outermost functions, chains (innermost
three) and source lines; with PATTERN, the whole chains that contain it.
"""

import collections
import re
import subprocess
import sys


def read_trace(path):
    """Blocks (start address -> instruction addresses) and the sequence
    of block starts run."""
    blocks, runs = {}, []
    addresses, reading = [], False
    instruction = re.compile(r"^0x([0-9a-f]+):")
    run = re.compile(r"\[[0-9a-f]+/([0-9a-f]+)/")
    with open(path, errors="ignore") as trace:
        for line in trace:
            if line.startswith("IN:"):
                addresses, reading = [], True
            elif reading:
                m = instruction.match(line)
                if m:
                    addresses.append(int(m.group(1), 16))
                elif not line.strip() and addresses:
                    blocks[addresses[0]] = addresses
                    reading = False
            elif line.startswith("Trace"):
                m = run.search(line)
                if m:
                    runs.append(int(m.group(1), 16))
    return blocks, runs


def chains(elf, addresses):
    """Each address's inlined chain, innermost first: (function, file:line)."""
    out = subprocess.run(
        ["llvm-addr2line", "-e", elf, "-f", "-C", "-i", "-a"] + [hex(a) for a in addresses],
        capture_output=True, text=True, check=True).stdout
    result = {}
    for block in re.split(r"\n(?=0x[0-9a-f]+\n)", out.strip()):
        lines = block.split("\n")
        result[int(lines[0], 16)] = [(lines[i], lines[i + 1]) for i in range(1, len(lines) - 1, 2)]
    return result


def short(function):
    return re.sub(r"::h[0-9a-f]{16}$", "", function).split("::")[-1][:30]


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    blocks, runs = read_trace(sys.argv[1])
    info = chains(sys.argv[2], sorted({a for b in blocks.values() for a in b}))

    def runs_code(start, name):
        return any(name in f for a in blocks.get(start, [start]) for f, _ in info.get(a, []))

    crc = {s for s in blocks if runs_code(s, "Crc32Sink")}
    host = {s for s in blocks if runs_code(s, "semihosting")}
    first_crc = next(i for i, s in enumerate(runs) if s in crc)
    report = next(i for i in range(first_crc, len(runs)) if runs[i] in host)
    start = max(i for i in range(first_crc, report) if runs[i] in crc) + 1
    counts = collections.Counter()
    for s in runs[start:report]:
        for a in blocks.get(s, [s]):
            counts[a] += 1
    total = sum(counts.values())
    tables = {name: collections.Counter() for name in ("innermost", "outermost", "chains", "lines")}
    whole = collections.Counter()
    for a, n in counts.items():
        chain = info.get(a)
        if not chain:
            continue
        tables["innermost"][short(chain[0][0])] += n
        tables["outermost"][short(chain[-1][0])] += n
        tables["chains"][" < ".join(short(f) for f, _ in chain[:3])] += n
        tables["lines"][chain[0][1].split("/")[-1]] += n
        if len(sys.argv) == 4:
            names = [short(f) + "@" + l.split("/")[-1] for f, l in chain]
            if any(sys.argv[3] in name for name in names):
                whole[" < ".join(names)] += n
    print(f"window: {total} instructions")
    for name, table in tables.items():
        print(f"== {name}")
        for key, n in table.most_common(30):
            print(f"{n:>9} {100 * n / total:5.1f} % {key}")
    if len(sys.argv) == 4:
        print(f"== whole chains with {sys.argv[3]}")
        for key, n in whole.most_common(15):
            print(f"{n:>9} {key}")


if __name__ == "__main__":
    main()
