#!/usr/bin/env bash
# Runs the README's two commands exactly as written in a pristine Debian 12 root, as a new user
# on a fresh machine would: a minimal debootstrap system with only git, ca-certificates and
# sudo added, a clean clone of this repository's HEAD (committed work only, like CI), then
# `scripts/run-example.sh` and `scripts/test.sh`. Reports each command's exit status and the
# tail of its log; exits non-zero when either fails.
#
#   scripts/check-fresh-debian.sh [--rebuild-root] [--keep]
#
# Run it whenever a dependency or an install step changes, and before landing such a change:
# the development and CI machines have packages preinstalled that a pristine system lacks.
# Needs root (or sudo), debootstrap (installed when missing) and access to Debian's mirror.
# The pristine root is built once and cached as a tarball in $EOMGEN_FRESH_DEBIAN_CACHE
# (default /var/cache/eomgen); each run unpacks a new copy, so no run sees another's installs.
# Logs go to $EOMGEN_FRESH_DEBIAN_LOGS (default /tmp/eomgen-fresh-debian).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cache="${EOMGEN_FRESH_DEBIAN_CACHE:-/var/cache/eomgen}"
logs="${EOMGEN_FRESH_DEBIAN_LOGS:-/tmp/eomgen-fresh-debian}"
mirror="${EOMGEN_DEBIAN_MIRROR:-http://deb.debian.org/debian}"
rebuild=0
keep=0
for arg in "$@"; do
  case "$arg" in
    --rebuild-root) rebuild=1 ;;
    --keep) keep=1 ;;
    *) echo "usage: scripts/check-fresh-debian.sh [--rebuild-root] [--keep]" >&2; exit 2 ;;
  esac
done

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
run_root() { "${sudo_cmd[@]}" "$@"; }

if ! command -v debootstrap >/dev/null; then
  run_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive run_root apt-get install -y -qq --no-install-recommends debootstrap
fi

tarball="$cache/debian12-minbase.tar.gz"
if [ "$rebuild" -eq 1 ] || [ ! -f "$tarball" ]; then
  echo "== building a pristine Debian 12 (bookworm) minbase root, once; cached as $tarball"
  run_root mkdir -p "$cache"
  staging="$(mktemp -d /var/tmp/eomgen-debootstrap.XXXXXX)"
  run_root debootstrap --variant=minbase --include=git,ca-certificates,sudo bookworm "$staging" "$mirror" \
    >"$cache/debootstrap.log" 2>&1 || { tail -20 "$cache/debootstrap.log"; run_root rm -rf "$staging"; exit 1; }
  run_root tar -C "$staging" -czf "$tarball.partial" .
  run_root mv "$tarball.partial" "$tarball"
  run_root rm -rf "$staging"
fi

work="$(mktemp -d /var/tmp/eomgen-fresh-debian.XXXXXX)"
chroot_dir="$work/root"
mounted=()
cleanup() {
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do run_root umount -l "${mounted[$i]}" 2>/dev/null || true; done
  if [ "$keep" -eq 1 ]; then echo "kept the root at $chroot_dir"; else run_root rm -rf "$work"; fi
}
trap cleanup EXIT
run_root mkdir -p "$chroot_dir"
run_root tar -C "$chroot_dir" -xzf "$tarball"
# mount_into DIR MOUNT-ARGUMENTS...: mounts at $chroot_dir/DIR and remembers it for cleanup
mount_into() {
  local dir="$chroot_dir/$1"
  shift
  run_root mount "$@" "$dir"
  mounted+=("$dir")
}
mount_into proc -t proc proc
mount_into sys -t sysfs sys
mount_into dev --bind /dev
mount_into dev/pts -t devpts devpts
run_root cp /etc/resolv.conf "$chroot_dir/etc/resolv.conf"

# a clean clone of what is committed, as CI takes it
echo "== cloning $(git -C "$root" rev-parse --short HEAD) into the pristine root"
run_root git clone -q "$root" "$chroot_dir/root/eomgen"

mkdir -p "$logs"
status=0
for command in scripts/run-example.sh scripts/test.sh; do
  log="$logs/$(basename "$command" .sh).log"
  echo "== $command (log: $log)"
  start=$SECONDS
  set +e
  run_root chroot "$chroot_dir" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    /bin/bash -c "cd /root/eomgen && $command" >"$log" 2>&1
  rc=$?
  set -e
  echo "   exit status $rc after $((SECONDS - start)) s; last lines:"
  tail -n 15 "$log" | sed 's/^/   | /'
  [ "$rc" -eq 0 ] || status=1
done
if [ "$status" -eq 0 ]; then
  echo "== both README commands pass in a pristine Debian 12 root"
else
  echo "== a README command failed in a pristine Debian 12 root"
fi
exit "$status"
