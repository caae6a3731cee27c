#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# platform/cross-install.sh - install the cross toolchains and emulators that
# `make cross` needs, only those that are missing (Debian packages only).
# Never installs gcc-multilib: that metapackage removes the gcc-*-linux-gnu
# cross compilers.
set -u
need=()
have_cmd()  { command -v "$1" >/dev/null 2>&1; }
want_cmd()  { have_cmd "$1" || need+=("$2"); }
want_file() { [ -e "$1" ] || need+=("$2"); }

want_cmd  arm-none-eabi-gcc        gcc-arm-none-eabi
want_file /usr/lib/arm-none-eabi/newlib/rdimon.specs libnewlib-arm-none-eabi
want_cmd  qemu-system-arm          qemu-system-arm
want_cmd  qemu-s390x               qemu-user
want_cmd  s390x-linux-gnu-gcc      gcc-s390x-linux-gnu
want_file /usr/s390x-linux-gnu/include/stdio.h   libc6-dev-s390x-cross
want_cmd  powerpc-linux-gnu-gcc    gcc-powerpc-linux-gnu
want_file /usr/powerpc-linux-gnu/include/stdio.h libc6-dev-powerpc-cross
want_cmd  i686-linux-gnu-gcc       gcc-i686-linux-gnu
want_file /usr/i686-linux-gnu/include/stdio.h    libc6-dev-i386-cross
want_cmd  riscv64-unknown-elf-gcc  gcc-riscv64-unknown-elf
want_file /usr/lib/picolibc/riscv64-unknown-elf/picolibc.specs picolibc-riscv64-unknown-elf
want_cmd  qemu-system-riscv32      qemu-system-misc

[ ${#need[@]} -eq 0 ] && exit 0
# de-duplicate
mapfile -t need < <(printf '%s\n' "${need[@]}" | sort -u)
echo "cross: installing ${need[*]}"
sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
log=$(mktemp); trap 'rm -f "$log"' EXIT
$sudo apt-get update -qq >"$log" 2>&1 \
    || { cat "$log" >&2; echo "cross: apt-get update failed" >&2; exit 1; }
$sudo apt-get install -y -qq --no-install-recommends "${need[@]}" >"$log" 2>&1 \
    || { tail -n 20 "$log" >&2; echo "cross: apt-get install ${need[*]} failed" >&2; exit 1; }
