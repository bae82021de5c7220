# Cross-compiling mpr for 64-bit ARM (AArch64) with Debian's g++-aarch64-linux-gnu, tests run
# under qemu-user: cmake -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake ...
#
# No arm64 packages are needed: mpr's dependencies are header-only (Eigen, Catch2 v2, the stb
# headers), so the host's headers and CMake package files are used as they are. Libraries are
# looked up in the cross sysroot only, so Debian's x86 libstb is not found and the stb
# implementation is compiled instead (MPR_STB_IMPLEMENTATION, its default then).
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

set(MPR_AARCH64_PREFIX "aarch64-linux-gnu" CACHE STRING "Prefix of the cross tools (<prefix>-g++)")
set(MPR_AARCH64_SYSROOT "/usr/${MPR_AARCH64_PREFIX}" CACHE PATH "The cross C library's root (qemu's -L)")
set(CMAKE_C_COMPILER "${MPR_AARCH64_PREFIX}-gcc")
set(CMAKE_CXX_COMPILER "${MPR_AARCH64_PREFIX}-g++")

# Programs from the host; libraries from the sysroot only; headers and package files (all
# header-only or architecture-independent) from both.
set(CMAKE_FIND_ROOT_PATH "${MPR_AARCH64_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)

# ctest runs the test programs under qemu-user, with the cross C library as the root of the
# dynamic loader's paths.
find_program(MPR_QEMU_AARCH64 NAMES qemu-aarch64 qemu-aarch64-static)
if(MPR_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${MPR_QEMU_AARCH64};-L;${MPR_AARCH64_SYSROOT}")
endif()
