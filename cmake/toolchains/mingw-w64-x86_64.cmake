# Windows x64 with Debian's MinGW-w64 (the POSIX-threads flavour: std::thread and thread_local need it).
# ctest runs the test executables under wine (headless: WINEDEBUG=-all, WINEPREFIX set by the caller).
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(CMAKE_C_COMPILER x86_64-w64-mingw32-gcc-posix)
set(CMAKE_CXX_COMPILER x86_64-w64-mingw32-g++-posix)
set(CMAKE_RC_COMPILER x86_64-w64-mingw32-windres)
set(CMAKE_FIND_ROOT_PATH /usr/x86_64-w64-mingw32)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
# Header-only packages (Eigen) are found where Debian installs them for every architecture.
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)
find_program(TP_WINE NAMES wine wine64 REQUIRED)
set(CMAKE_CROSSCOMPILING_EMULATOR ${TP_WINE})
