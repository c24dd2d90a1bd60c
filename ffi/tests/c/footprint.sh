#!/usr/bin/env bash
# Flash of gyrostat's C interface in the bare-metal C test images (`make` first): from each
# image's linker map, the bytes placed in flash (.text with .rodata, .ARM.exidx, the .data
# initialisers) by the input sections of libgyrostat_ffi.a (the library, its Rust dependencies
# and the compiler builtins it carries), of libgcc, and of the C objects (the test scenario and
# the startup code). Usage: bash footprint.sh MAP...
set -euo pipefail
for map in "$@"; do
  awk -v name="$(basename "$map" .map)" '
    function hex(s,   i, c, v) {
      v = 0; s = tolower(substr(s, 3))
      for (i = 1; i <= length(s); i++) { c = index("0123456789abcdef", substr(s, i, 1)) - 1; v = v * 16 + c }
      return v
    }
    /^Linker script and memory map/ { on = 1; next }
    !on { next }
    /^\.[A-Za-z_.]+/ { out = $1 }          # an output section starts at column 0
    NF >= 3 && $(NF-1) ~ /^0x[0-9a-f]+$/ && $(NF-2) ~ /^0x[0-9a-f]+$/ && (out == ".text" || out == ".ARM.exidx" || out == ".data") {
      size = hex($(NF-1)); file = $NF
      if (file ~ /libgyrostat_ffi\.a\(/) lib += size
      else if (file ~ /libgcc\.a\(/) gcc += size
      else if (file ~ /\.o$/) c += size
    }
    END { printf "%s: gyrostat C interface %d bytes of flash, libgcc %d, C scenario and startup %d\n", name, lib, gcc, c }
  ' "$map"
done
