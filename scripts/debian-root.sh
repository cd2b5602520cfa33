#!/usr/bin/env bash
# Runs README's Quick start on another Debian release, in a minimal root made with debootstrap:
# the check before landing a change that touches the lavapipe rules (docs/lavapipe-rules.md §8),
# since each Debian release ships another Mesa (docs/contributing.md "Other Debian releases").
#
#   scripts/debian-root.sh RELEASE [--root DIR] [--only conformance|test] [--capture DIR]
#
# RELEASE is a Debian suite (bookworm, trixie, sid). The root is made once in DIR (default
# /var/tmp/rastercmp-roots/RELEASE) and reused; each run clones this repository's HEAD afresh into
# it, installs README's prerequisite line (apt-get install git make) and runs `make conformance`
# and `make test` there, printing the wall time of each. --capture DIR also records the built-in
# suite and a soak slice (the scenes of `soak --seed 7 --count 30000` on which 22.3.6's rules and
# the driver differ) on that release's lavapipe into DIR (`rastercmp capture`), as tests/captures/
# holds them. Needs root (debootstrap, chroot, bind mounts) and Debian's registry.
# Exit status: that of the first command that failed, else 0.
set -euo pipefail

usage() {
  sed -n '5,6p' "$0" >&2
  exit 2
}
[[ $# -ge 1 ]] || usage
release=$1
shift
root="/var/tmp/rastercmp-roots/$release"
only=""
capture=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --root) root=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --capture) capture=$2; shift 2 ;;
    *) usage ;;
  esac
done
[[ -z "$only" || "$only" == conformance || "$only" == test ]] || usage
if [[ $(id -u) -ne 0 ]]; then
  echo "debian-root: needs root (debootstrap, chroot and bind mounts)" >&2
  exit 3
fi
repo=$(cd "$(dirname "$0")/.." && pwd)
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}

if ! command -v debootstrap >/dev/null; then
  apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q debootstrap
fi
if [[ ! -x "$root/usr/bin/apt-get" ]]; then
  echo "debian-root: making a minimal $release root in $root"
  mkdir -p "$root"
  debootstrap --variant=minbase "$release" "$root" "$mirror"
fi
# A mirror may serve a snapshot whose Release file has expired (apt refuses those by default).
echo 'Acquire::Check-Valid-Until "false";' >"$root/etc/apt/apt.conf.d/99rastercmp-snapshot"
cp /etc/resolv.conf "$root/etc/resolv.conf"

mounts=()
unmount_all() {
  local i
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do umount -l "${mounts[i]}" 2>/dev/null || true; done
}
trap unmount_all EXIT
bind() {  # bind SOURCE TARGET [ro]
  mkdir -p "$2"
  mount --bind "$1" "$2"
  mounts+=("$2")
  if [[ ${3:-} == ro ]]; then mount -o remount,bind,ro "$2"; fi
}
bind /proc "$root/proc"
bind /dev "$root/dev"
bind /dev/pts "$root/dev/pts"
bind /sys "$root/sys"
bind "$repo" "$root/mnt/rastercmp-src" ro
if [[ -n "$capture" ]]; then
  mkdir -p "$capture"
  bind "$(cd "$capture" && pwd)" "$root/mnt/rastercmp-capture"
fi

cat >"$root/root/rastercmp-run.sh" <<EOF
set -uo pipefail
export DEBIAN_FRONTEND=noninteractive
status=0
step() {  # step NAME COMMAND...: runs it, prints its wall time, keeps the first failure
  local name=\$1; shift
  local t0=\$(date +%s)
  "\$@"; local rc=\$?
  echo "debian-root: $release: \$name: exit \$rc in \$(( \$(date +%s) - t0 )) s"
  [[ \$rc -eq 0 || \$status -ne 0 ]] || status=\$rc
  return \$rc
}
step "prerequisite (apt-get install git make)" bash -c 'apt-get update -q && apt-get install -y -q git make' || exit \$status
git config --global --add safe.directory '*'
rm -rf /root/rastercmp && git clone -q /mnt/rastercmp-src /root/rastercmp && cd /root/rastercmp || exit 1
echo "debian-root: $release: \$(git log --oneline -1)"
[[ "$only" == test ]] || step "make conformance" make conformance
[[ "$only" == conformance ]] || step "make test" make test
if [[ -n "$capture" ]]; then
  step "build" make build-app
  step "capture suite" build/app/rastercmp capture --suite scenes --out /mnt/rastercmp-capture/suite
  # The scenes where 22.3.6's rules and this driver differ: the soak writes exactly those (exit 1).
  build/app/rastercmp soak --seed 7 --count 30000 --no-reduce --profile lavapipe-22.3 \
    --out /mnt/rastercmp-capture/soak-scenes | tail -n 14
  step "capture soak slice" build/app/rastercmp capture --suite /mnt/rastercmp-capture/soak-scenes \
    --out /mnt/rastercmp-capture/soak
fi
exit \$status
EOF
chroot "$root" /bin/bash /root/rastercmp-run.sh
