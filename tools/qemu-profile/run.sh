#!/usr/bin/env bash
# Where one frame's instructions go on an emulated Cortex-M (issue 32):
# builds firmware/qemu with ZLINE_QEMU_SCENE=0 (the torus knot alone) for
# TARGET, runs it under QEMU with -icount and the translation and
# execution trace (-d in_asm,exec,nochain), and charges each executed
# block's instructions to its source lines (llvm-addr2line -i) over one
# frame: the counted z16 frame, the window between the last row of the
# checksummed frame before it and the first semihosting output after it.
#   tools/qemu-profile/run.sh [m0|m4f|m33] [PATTERN]    (default m4f)
# Prints the window's size (the frame's instructions, within SysTick's
# overhead of what `cargo qemu*` reports), then the innermost function,
# the outermost one, the inlined call chains and the source lines, each
# with its share; with PATTERN, the whole chains that contain it. Needs qemu-system-arm, llvm-addr2line and python3; the
# trace takes about 500 MB in target/qemu-profile.
set -euo pipefail
cd "$(dirname "$0")/../.."
core=${1:-m4f}
pattern=${2:-}
case "$core" in
  m0) target=thumbv6m-none-eabi; cpu=cortex-m3; machine=mps2-an385 ;;
  m4f) target=thumbv7em-none-eabihf; cpu=cortex-m4; machine=mps2-an386 ;;
  m33) target=thumbv8m.main-none-eabihf; cpu=cortex-m33; machine=mps2-an505 ;;
  *) echo "usage: $0 [m0|m4f|m33]" >&2; exit 2 ;;
esac
out=target/qemu-profile
mkdir -p "$out"
ZLINE_QEMU_SCENE=0 CARGO_TARGET_DIR="$out/build" cargo build --quiet --release \
  --manifest-path firmware/qemu/Cargo.toml --target "$target" --bin zline-qemu
elf="$out/build/$target/release/zline-qemu"
qemu-system-arm -cpu "$cpu" -machine "$machine" -nographic \
  -semihosting-config enable=on,target=native -icount shift=0 \
  -d in_asm,exec,nochain -D "$out/trace.log" -kernel "$elf" > "$out/firmware.txt"
grep -m1 "depth=z16" "$out/firmware.txt"
python3 tools/qemu-profile/charge.py "$out/trace.log" "$elf" ${pattern:+"$pattern"}
