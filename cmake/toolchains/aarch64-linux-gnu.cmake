# Cross-compiling for aarch64 (a robot's Jetson or Raspberry Pi) with Debian's g++-aarch64-linux-gnu
# and the arm64 libraries of Debian's multiarch (scripts/check-aarch64.sh installs both). The tests
# run under qemu-user.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
# Multiarch: headers are shared in /usr/include, libraries live in /usr/lib/aarch64-linux-gnu.
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(PKG_CONFIG_EXECUTABLE aarch64-linux-gnu-pkg-config CACHE FILEPATH "")
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64)
# GCC notes that passing some vector types changed ABI in GCC 10.1: every object here is built by
# the same compiler, so the note says nothing about this build.
set(CMAKE_CXX_FLAGS_INIT "-Wno-psabi")
