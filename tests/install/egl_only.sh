#!/usr/bin/env bash
# The EGL-only build (`make egl-only`: configured with -DSYLVA_OSMESA=OFF, as on a distribution
# whose Mesa no longer ships libOSMesa): its sylva links no libOSMesa, `info --gl` names EGL as
# the only backend built, a sample tree renders, and asking for OSMesa is one error line, exit 2.
# Usage: tests/install/egl_only.sh BUILD/cli/sylva
set -euo pipefail
sylva=$(realpath "$1")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() {
  echo "egl-only: $*" >&2
  exit 1
}

if ldd "$sylva" | grep -q libOSMesa; then fail "sylva links libOSMesa"; fi
ldd "$sylva" | grep -q libEGL || fail "sylva does not link libEGL"

info=$(env -u SYLVA_GL "$sylva" info --gl)
echo "$info"
grep -qx 'gl built    egl' <<<"$info" || fail "built backends are not just egl"
grep -q '^gl backend  EGL (' <<<"$info" || fail "auto did not take EGL"

export SYLVA_CACHE_DIR="$work/cache"
"$sylva" sample tree --leaves 1500 -o "$work/tree.glb" >/dev/null
"$sylva" render "$work/tree.glb" --style ink --size 128 -o "$work/tree.png" >/dev/null
[ -s "$work/tree.png" ] || fail "no render"

expect_error() {  # expect_error NEEDLE COMMAND...: exit 2, one line naming NEEDLE, no output file
  local needle=$1 status=0 out
  shift
  out=$("$@" 2>&1) || status=$?
  [ "$status" = 2 ] || fail "$* exited $status, not 2: $out"
  [ "$(printf '%s\n' "$out" | wc -l)" = 1 ] || fail "$* printed more than one line: $out"
  grep -q -- "$needle" <<<"$out" || fail "$* did not say '$needle': $out"
}
expect_error "built without osmesa" "$sylva" render "$work/tree.glb" --gl osmesa -o "$work/x.png"
expect_error "built without osmesa" env SYLVA_GL=osmesa "$sylva" render "$work/tree.glb" -o "$work/x.png"
[ ! -e "$work/x.png" ] || fail "a failed render wrote its output"
echo "egl-only: ok"
