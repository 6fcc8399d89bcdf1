#!/usr/bin/env bash
# Install the Debian packages straylight builds, tests and demos with.
# Idempotent: installs only what is missing, and says nothing when all is
# there.  Run as root or with sudo available.
set -eu

PKGS=(
	build-essential pkg-config python3
	libcmocka-dev			# unit tests
	libcsv-dev libcjson-dev		# CSV fields, JSON sensors and output
	libplplot-dev plplot-driver-cairo	# plots (PNG through cairo)
	clang libclang-rt-14-dev	# libFuzzer targets of the parsers
	chromium			# the report test opens it headless
	libcfitsio-dev libssl-dev	# FITS frames, SHA-256 of the manifest
	libtiff-dev			# 16-bit TIFF frames of `stray sweep import`
	libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev
	libembree-dev libassimp-dev	# ray queries, OBJ/STL import
	libopenmpi-dev openmpi-bin	# stray-mpi
	libusb-1.0-0-dev libhidapi-dev libgpiod-dev zlib1g-dev	# rig
	umockdev libumockdev-dev	# rig test bed (scripts/rig-testbed.sh)
	libindi-dev indi-bin		# rig INDI backend, its simulators (rig-indi.sh)
	gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm	# flight build
	liberfa-dev cppcheck		# ephemeris reference, flight-code checks
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
