#!/usr/bin/env bash
# The .deb (ctest install.deb): cpack builds it into a temporary folder; its control fields name
# the runtime packages (dpkg-shlibdeps); lintian reports no error (its warnings are printed);
# `dpkg-deb -x` extracts it and check_installed.sh checks the extracted /usr.
# Usage: deb_test.sh BUILD_DIR
set -euo pipefail
build=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/sylva-deb-XXXXXX")
trap 'rm -rf "$work"' EXIT
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/out" >"$work/cpack.log" 2>&1 ||
  { cat "$work/cpack.log"; exit 1; }
deb=$(find "$work/out" -maxdepth 1 -name 'sylva_*.deb')
[ -n "$deb" ] || { echo "deb_test: cpack made no .deb"; cat "$work/cpack.log"; exit 1; }
dpkg-deb --info "$deb"
depends=$(dpkg-deb --field "$deb" Depends)
for lib in libc6 libegl1 libosmesa6 libopencv-core406 libopenexr-3-1-30 libembree3-3 python3-numpy; do
  [[ $depends == *"$lib"* ]] || { echo "deb_test: Depends lacks $lib: $depends"; exit 1; }
done
lintian --no-tag-display-limit "$deb" >"$work/lintian.txt" 2>&1 || true
cat "$work/lintian.txt"
if grep -q '^E: ' "$work/lintian.txt"; then
  echo "deb_test: lintian reports errors"
  exit 1
fi
dpkg-deb -x "$deb" "$work/root"
"$(dirname "$0")/check_installed.sh" "$work/root/usr" "$work"
