#!/usr/bin/env bash
# Install the Debian packages straylight builds, tests and demos with.
# Idempotent: installs only what is missing, and says nothing when all is
# there.  Run as root or with sudo available.
set -eu
PKGS=(
	build-essential pkg-config python3
	libcmocka-dev
	libcsv-dev
	libcjson-dev
	libplplot-dev plplot-driver-cairo
	clang libclang-rt-14-dev
	chromium
	libcfitsio-dev libssl-dev
	libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev
	libembree-dev libassimp-dev
	libopenmpi-dev openmpi-bin
	libusb-1.0-0-dev libhidapi-dev libgpiod-dev zlib1g-dev
	gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm liberfa-dev cppcheck
)
missing=()
for p in "${PKGS[@]}"; do
	case "$p" in \#*) continue ;; esac
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" ||
		missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
