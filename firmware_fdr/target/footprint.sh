#!/usr/bin/env bash
# footprint.sh - `make firmware`: sizes (arm-none-eabi-size), the static
# worst-case stack, then the emulated run's instructions and stack.
# Usage: footprint.sh FW_BUILD FOOTPRINT_ELF VECTORS_ELF [DETECTOR_ELF]
set -eu
fw=$1; elf=$2; vec=$3; det=${4:-}
echo "== arm-none-eabi-size $elf"
arm-none-eabi-size -A "$elf" | grep -E '^(section|\.text|\.rodata|\.data|\.bss) '
python3 firmware_fdr/target/footprint.py "$fw/obj" "$elf.map"
if command -v qemu-system-arm >/dev/null; then
	echo "== qemu-system-arm -M mps2-an386 (semihosting, -icount shift=0)"
	timeout 120 qemu-system-arm -M mps2-an386 -nographic -monitor none \
		-serial none -semihosting-config enable=on,target=native \
		-icount shift=0 -kernel "$vec"
	[ -z "$det" ] || timeout 120 qemu-system-arm -M mps2-an386 -nographic \
		-monitor none -serial none \
		-semihosting-config enable=on,target=native -icount shift=0 \
		-kernel "$det"
else
	echo "qemu-system-arm not installed: no emulated run"
fi
