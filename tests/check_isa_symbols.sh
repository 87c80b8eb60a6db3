#!/usr/bin/env bash
# IsaObjectsShareNoInlineCode: a per-ISA kernel object must not define a weak
# (inline/template) symbol that baseline code could also use, or the linker
# might hand AVX code to a caller on a CPU without AVX. Every weak symbol in
# an AVX2/AVX-512 object must name its own ISA.
set -euo pipefail
objects_dir=$1
status=0
found=0
for isa in avx2 avx512; do
  tag=$([ "$isa" = avx512 ] && echo avx512bw || echo avx2)
  for object in "$objects_dir"/*_"$isa".cpp.o; do
    [ -f "$object" ] || continue
    found=$((found + 1))
    leaked=$(nm -C "$object" | awk '$2 ~ /^[WVu]$/' | grep -v "DW.ref.__gxx_personality_v0" |
             grep -v "xsimd::$tag" || true)
    if [ -n "$leaked" ]; then
      echo "$object: weak symbols shared with other ISAs:"
      echo "$leaked" | head -20
      status=1
    fi
  done
done
if [ "$found" -eq 0 ]; then
  echo "no per-ISA objects found in $objects_dir"
  exit 1
fi
[ "$status" -eq 0 ] && echo "$found per-ISA objects share no inline code"
exit $status
