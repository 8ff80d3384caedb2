#!/usr/bin/env bash
# A/B of zline's speed in one run (issue 30): this repository's zline
# against the code of commit c6aebe4, on the bunny at 800x600 without
# culling, z24, Lambert timed, unless told otherwise. Run from anywhere in
# a clone with its history (a shallow clone needs `git fetch --unshallow`):
#   tools/bench-ab/run.sh [MESH.obj] [--size WxH] [--cull none|back] [--rounds N]
# The old code is extracted once, with `git archive`, into
# target/ab/c6aebe4 (git ignores target/), its package renamed
# zline-c6aebe4 (Cargo refuses two path packages named zline 0.1.0); both
# sides build with fat LTO
# and one codegen unit into target/ab/target. The last line printed is
#   ab: mesh=.. size=.. cull=.. depth=z24 old_ms=.. new_ms=.. ratio=..
# with ratio = old_ms / new_ms.
set -euo pipefail
cd "$(dirname "$0")/../.."
old=c6aebe4
dir=target/ab/$old
if [ ! -f "$dir/Cargo.toml" ]; then
  if ! git rev-parse --verify --quiet "$old^{commit}" >/dev/null; then
    echo "run.sh: commit $old is not in this clone (shallow? git fetch --unshallow)" >&2
    exit 1
  fi
  rm -rf "$dir.partial"
  mkdir -p "$dir.partial"
  git archive "$old" | tar -x -C "$dir.partial"
  # Cargo refuses two path packages named zline 0.1.0 in one lock file:
  # the old one becomes the package zline-c6aebe4 (library zline_c6aebe4).
  sed -i '0,/^name = "zline"$/s//name = "zline-'"$old"'"/' "$dir.partial/Cargo.toml"
  grep -q '^name = "zline-'"$old"'"$' "$dir.partial/Cargo.toml"
  mv "$dir.partial" "$dir"
fi
cargo build --quiet --release --manifest-path tools/bench-ab/Cargo.toml --target-dir target/ab/target
exec target/ab/target/release/zline-bench-ab "$@"
