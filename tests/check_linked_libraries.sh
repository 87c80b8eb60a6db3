#!/usr/bin/env bash
# QuadraLinksNoPeerLibraries, QuadraReportLinksNoPeerLibraries: the quadra and
# quadra-report binaries never load OpenImageIO (`report textures` dlopens
# quadra_oiio_peer.so instead) nor Mesa (quadra-llvmpipe is a program of its
# own): linked in, their dependency trees cost every command their loading
# and relocation at start-up, 0.2 s for OpenImageIO's (docs/performance.md
# "Start-up"). Both the binary's own NEEDED entries (readelf -d) and
# everything the dynamic loader would load with them (ldd) are checked, so a
# dependency that drags them in fails too.
#   check_linked_libraries.sh BINARY                passes when BINARY loads none of them
#   check_linked_libraries.sh --expect-found FILE   passes when FILE does: the self-test,
#                                                   on the module or peer that links them
set -euo pipefail

forbidden='libOpenImageIO|libOSMesa|libGL[.X]|libLLVM'

expect_found=0
if [[ ${1:-} == --expect-found ]]; then
  expect_found=1
  shift
fi
binary=${1:?usage: check_linked_libraries.sh [--expect-found] BINARY}
[[ -f $binary ]] || { echo "$binary: no such file"; exit 1; }

needed=$(readelf -d "$binary" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
[[ -n $needed ]] || { echo "$binary: readelf found no NEEDED entries"; exit 1; }
loaded=$(ldd "$binary" | awk '{print $1}')
echo "$binary: $(wc -l <<<"$needed") NEEDED entries, $(wc -l <<<"$loaded") libraries loaded"

found=$( (grep -E "$forbidden" <<<"$needed" | sed 's/$/ (NEEDED)/'
  grep -E "$forbidden" <<<"$loaded" | sed 's/$/ (loaded)/') || true)
if ((expect_found)); then
  [[ -n $found ]] || { echo "self-test: none of $forbidden found in $binary"; exit 1; }
  echo "self-test: found, as expected:"
  echo "$found"
  exit 0
fi
if [[ -n $found ]]; then
  echo "$binary loads libraries it must not (load them with dlopen, or from another program):"
  echo "$found"
  exit 1
fi
