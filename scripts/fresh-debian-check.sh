#!/usr/bin/env bash
# Runs .ci/run and the README's demo as on a fresh Debian 12 machine: a bookworm made by
# debootstrap in FOLDER (default /var/tmp/tinlod-fresh, about 3 GB once built), a clean clone
# of this checkout's HEAD inside it, and ../shared beside it, read-only. As root, on a
# Debian or Ubuntu host that reaches deb.debian.org. Not part of CI: it takes 20-30 minutes.
# Usage: scripts/fresh-debian-check.sh [FOLDER]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
fresh=${1:-/var/tmp/tinlod-fresh}
shared=$root/../shared
[[ $(id -u) -eq 0 ]] || { echo "fresh-debian-check: run as root (debootstrap, chroot, mounts)" >&2; exit 2; }
command -v debootstrap > /dev/null || apt-get install -y -q debootstrap
[[ -d $fresh/etc ]] || debootstrap bookworm "$fresh" http://deb.debian.org/debian

mounted=()
cleanup() {
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount -R -l "${mounted[i]}" 2> /dev/null || true; done
}
trap cleanup EXIT
bind() {  # bind SOURCE TARGET [ro]: with what is mounted under SOURCE (/dev/pts, /dev/shm)
  mkdir -p "$2"
  mount --rbind "$1" "$2" && mounted+=("$2")
  [[ ${3:-} != ro ]] || mount -o remount,ro,bind "$2"
}
mount -t proc proc "$fresh/proc" && mounted+=("$fresh/proc")
bind /dev "$fresh/dev"
bind /sys "$fresh/sys"
[[ ! -d $shared ]] || bind "$shared" "$fresh/work/shared" ro
cp /etc/resolv.conf "$fresh/etc/resolv.conf"

rm -rf "$fresh/work/main"
git clone -q "$root" "$fresh/work/main"
run() {
  chroot "$fresh" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    LANG=C.UTF-8 CI=true bash -c "cd /work/main && $1"
}
run "bash .ci/run"
run "bash scripts/demo.sh"
echo "fresh-debian-check: .ci/run and scripts/demo.sh passed on a fresh bookworm in $fresh"
