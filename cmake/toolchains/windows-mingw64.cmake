# Cross-compiles Bricklight for 64-bit Windows with Debian's MinGW-w64 (g++-mingw-w64-x86-64-posix: the POSIX
# thread model, which std::thread needs). scripts/build_windows.sh uses it; by hand:
#   cmake -S . -B build-windows -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/windows-mingw64.cmake \
#         -DBRICKLIGHT_SHADERC=build/bin/bricklight-shaderc
# Shaders are compiled by the host's bricklight-shaderc (built natively first): its output does not depend on
# the platform it runs on, and glslang is not needed for the target.
#
# The header-only dependencies (Vulkan headers, GLM, nlohmann/json, stb) are the host's Debian packages, seen
# through a folder of links (windows-deps in the build folder) so that the host's /usr/include, whose C library
# headers would shadow MinGW's, is never on the include path. Vulkan's import library for vulkan-1.dll is the
# one Debian's libwine-dev ships (an ordinary PE import library: the binaries load the system's vulkan-1.dll).
# Its own variables are prefixed _bl_: a toolchain file runs in the project's top scope.
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR x86_64)
set(_bl_triple x86_64-w64-mingw32)
set(CMAKE_C_COMPILER ${_bl_triple}-gcc-posix)
set(CMAKE_CXX_COMPILER ${_bl_triple}-g++-posix)
set(CMAKE_RC_COMPILER ${_bl_triple}-windres)

set(_bl_deps "${CMAKE_BINARY_DIR}/windows-deps")
set(_bl_links
  "include/vulkan=/usr/include/vulkan"
  "include/vk_video=/usr/include/vk_video"
  "include/glm=/usr/include/glm"
  "include/nlohmann=/usr/include/nlohmann"
  "include/stb=/usr/include/stb"
  "share/cmake/glm=/usr/share/cmake/glm"
  "share/cmake/nlohmann_json=/usr/share/cmake/nlohmann_json"
  "lib/libvulkan-1.a=/usr/lib/x86_64-linux-gnu/wine/x86_64-windows/libvulkan-1.a")
foreach(_bl_link ${_bl_links})
  string(REPLACE "=" ";" _bl_parts "${_bl_link}")
  list(GET _bl_parts 0 _bl_name)
  list(GET _bl_parts 1 _bl_target)
  if(EXISTS "${_bl_target}" AND NOT EXISTS "${_bl_deps}/${_bl_name}")
    get_filename_component(_bl_parent "${_bl_deps}/${_bl_name}" DIRECTORY)
    file(MAKE_DIRECTORY "${_bl_parent}")
    file(CREATE_LINK "${_bl_target}" "${_bl_deps}/${_bl_name}" SYMBOLIC)
  endif()
endforeach()

# Appended to, so that -DCMAKE_FIND_ROOT_PATH=<prefix> adds a root: a Windows package of Bricklight installed
# there is then found by find_package(bricklight) (tests/windows/run.sh builds examples/integration so).
list(APPEND CMAKE_FIND_ROOT_PATH /usr/${_bl_triple} "${_bl_deps}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# Programs run on the host through Wine (ctest and custom commands that run a target).
set(CMAKE_CROSSCOMPILING_EMULATOR wine)
# The C and C++ runtimes linked in, so that the programs need no MinGW DLLs beside them.
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static -static-libgcc -static-libstdc++")
