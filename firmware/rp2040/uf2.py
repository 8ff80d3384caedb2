#!/usr/bin/env python3
"""Writes a UF2 file (drag and drop onto a Pico in BOOTSEL mode) from a
firmware ELF: every loadable segment's bytes at their load addresses in
flash, in 256-byte pages, tagged with the chip's UF2 family.

elf2uf2-rs writes RP2040 UF2s only; the RP2350's boot ROM takes only
blocks of its own families (here RP2350 Arm Secure, 0xe48bff59).

usage: uf2.py ELF OUT.uf2 [--family rp2350|rp2040]
"""
import argparse
import struct
import sys

FAMILIES = {"rp2040": 0xE48BFF56, "rp2350": 0xE48BFF59}
FLASH = (0x10000000, 0x10000000 + (16 << 20))
PAGE = 256


def load_segments(elf):
    """(address, bytes) of each PT_LOAD segment with file contents, at its
    physical (load) address."""
    if elf[:4] != b"\x7fELF" or elf[4] != 1 or elf[5] != 1:
        raise ValueError("not a 32-bit little-endian ELF file")
    phoff, = struct.unpack_from("<I", elf, 28)
    phentsize, phnum = struct.unpack_from("<HH", elf, 42)
    for k in range(phnum):
        p_type, p_offset, _vaddr, p_paddr, p_filesz = struct.unpack_from(
            "<IIIII", elf, phoff + k * phentsize)
        if p_type == 1 and p_filesz > 0:
            yield p_paddr, elf[p_offset:p_offset + p_filesz]


def pages(segments):
    """The flash image as {page address: 256 bytes}, gaps within a page
    zero; fails on a byte outside flash or written twice."""
    out, written = {}, set()
    for address, data in segments:
        if address < FLASH[0] or address + len(data) > FLASH[1]:
            raise ValueError(f"segment at {address:#x} ({len(data)} bytes) is not in flash")
        for i, byte in enumerate(data):
            a = address + i
            if a in written:
                raise ValueError(f"two segments write {a:#x}")
            written.add(a)
            page = out.setdefault(a - a % PAGE, bytearray(PAGE))
            page[a % PAGE] = byte
    return out


def uf2(image, family):
    blocks = sorted(image.items())
    out = bytearray()
    for n, (address, data) in enumerate(blocks):
        header = struct.pack("<8I", 0x0A324655, 0x9E5D5157, 0x00002000, address,
                             PAGE, n, len(blocks), family)
        out += header + bytes(data) + bytes(476 - PAGE) + struct.pack("<I", 0x0AB16F30)
    return bytes(out)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("elf")
    p.add_argument("out")
    p.add_argument("--family", choices=sorted(FAMILIES), default="rp2350")
    args = p.parse_args()
    try:
        with open(args.elf, "rb") as f:
            image = pages(load_segments(f.read()))
    except (OSError, ValueError) as e:
        sys.exit(f"uf2.py: {args.elf}: {e}")
    if not image:
        sys.exit(f"uf2.py: {args.elf}: nothing to load into flash")
    data = uf2(image, FAMILIES[args.family])
    with open(args.out, "wb") as f:
        f.write(data)
    first = min(image)
    print(f"{args.out}: {len(image)} blocks of {PAGE} bytes from {first:#x}, family {args.family}")


if __name__ == "__main__":
    main()
