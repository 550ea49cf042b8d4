# Sourced by sizes.sh and no-panic.sh: sets the arrays `nm` and `objdump` to tools that read
# the firmware's ELF, rustup's llvm-tools (installed if missing) or else Debian's
# binutils-arm-none-eabi; fails naming `$1`, the caller, when there are neither.
host="$(rustc -vV | sed -n 's/^host: //p')"
tools="$(rustc --print sysroot)/lib/rustlib/$host/bin"
if [ ! -x "$tools/llvm-objdump" ]; then
    rustup component add llvm-tools >/dev/null 2>&1 || true
fi
if [ -x "$tools/llvm-objdump" ] && [ -x "$tools/llvm-nm" ]; then
    nm=("$tools/llvm-nm") objdump=("$tools/llvm-objdump")
elif command -v arm-none-eabi-objdump >/dev/null; then
    nm=(arm-none-eabi-nm) objdump=(arm-none-eabi-objdump)
else
    echo "$1: no llvm-nm/llvm-objdump (rustup component add llvm-tools) nor arm-none-eabi-objdump (apt-get install binutils-arm-none-eabi)" >&2
    exit 1
fi
