#!/usr/bin/env bash
# Builds oneTBB instrumented with ThreadSanitizer into DIR/prefix, for
# `scripts/sanitize.sh tsan`, from Debian's source package of the very
# libtbb-dev version that is installed (same headers, same ABI).
#
# Why: Debian's libtbb is not instrumented, so TSan cannot see the ordering
# its task pool and wait contexts provide (atomics inside libtbb.so, futex
# sleeps). Against it, every parallel_for looks racy: reports land in oneTBB's
# header code and in our task bodies alike, and no suppression could tell them
# from real races in our code. Against an instrumented libtbb the suite is
# clean with no suppression of our code at all.
#
# Uses apt-get with private list/cache directories under DIR (adds a deb-src
# entry only there; the machine's apt configuration is untouched). Skips all
# work when DIR/prefix already holds a build of the same version.
set -euo pipefail
dir=$(mkdir -p "$1" && cd "$1" && pwd)
source_name=$(dpkg-query -W -f='${source:Package}' libtbb-dev)
version=$(dpkg-query -W -f='${source:Version}' libtbb-dev)
stamp=$dir/prefix/.quadra-tsan-$source_name-$version
[ -f "$stamp" ] && exit 0

echo "quadra: building $source_name $version with -fsanitize=thread (once per build dir)"
rm -rf "$dir/apt" "$dir/src" "$dir/build" "$dir/prefix"
mkdir -p "$dir/apt/lists/partial" "$dir/apt/cache" "$dir/src"
# The suites the machine's own apt sources name for Debian 12.
cat >"$dir/apt/sources.list" <<'EOF'
deb-src http://deb.debian.org/debian bookworm main
deb-src http://deb.debian.org/debian bookworm-updates main
deb-src http://deb.debian.org/debian-security bookworm-security main
EOF
apt_options=(-q -o "Dir::Etc::SourceList=$dir/apt/sources.list" -o Dir::Etc::SourceParts=/dev/null
  -o "Dir::State::Lists=$dir/apt/lists" -o "Dir::Cache=$dir/apt/cache")
# As root, apt would otherwise try (and warn about) dropping to its _apt user.
[ "$(id -u)" -ne 0 ] || apt_options+=(-o APT::Sandbox::User=root)
apt-get "${apt_options[@]}" update >/dev/null
(cd "$dir/src" && apt-get "${apt_options[@]}" source "$source_name=$version" >/dev/null)
tree=$(find "$dir/src" -mindepth 1 -maxdepth 1 -type d | head -1)

# Only libtbb itself: no tests, no tbbmalloc, no hwloc binding. -O1 -g as the
# project's sanitizer builds; TBB_SANITIZE is oneTBB's own switch for this.
cmake -S "$tree" -B "$dir/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DTBB_SANITIZE=thread -DTBB_TEST=OFF \
  -DTBBMALLOC_BUILD=OFF -DTBB_STRICT=OFF -DTBB_DISABLE_HWLOC_AUTOMATIC_SEARCH=ON \
  -DTBB_ENABLE_IPO=OFF -DCMAKE_INSTALL_PREFIX="$dir/prefix" >/dev/null
cmake --build "$dir/build" -j "$(nproc)" >/dev/null
cmake --install "$dir/build" >/dev/null
touch "$stamp"
