# cmake --install: headers (C++ and the public GLSL includes, side by side under include/bricklight), the
# libraries, the shader compiler, the CMake package (bricklight::core, ::vulkan, ::gl, ::rhi, ::conformance,
# ::shaderc, and bricklight_add_shaders()) and a pkg-config file. See docs/integration.md.
include(CMakePackageConfigHelpers)
set(BRICKLIGHT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/bricklight)

# The one public include tree, C++ and GLSL side by side (the conformance kit's header only with the kit).
if(TARGET bricklight_conformance)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/bricklight DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
else()
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/bricklight DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
    PATTERN conformance.h EXCLUDE)
endif()
install(FILES ${PROJECT_BINARY_DIR}/include/bricklight/version.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/bricklight)

get_property(bricklight_targets GLOBAL PROPERTY BRICKLIGHT_EXPORTED_TARGETS)
install(TARGETS ${bricklight_targets} EXPORT BricklightTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT BricklightTargets NAMESPACE bricklight:: DESTINATION ${BRICKLIGHT_CMAKE_DIR})

# find_package(Bricklight) reads BricklightConfig.cmake, find_package(bricklight) bricklight-config.cmake:
# both are installed, the second only includes the first.
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/BricklightConfig.cmake.in
  ${PROJECT_BINARY_DIR}/package/BricklightConfig.cmake INSTALL_DESTINATION ${BRICKLIGHT_CMAKE_DIR}
  PATH_VARS CMAKE_INSTALL_INCLUDEDIR)  # defines PACKAGE_CMAKE_INSTALL_INCLUDEDIR, relative to the installed config
# 0.x: a minor version may break the API, so only the same major.minor is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/BricklightConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
file(WRITE ${PROJECT_BINARY_DIR}/package/bricklight-config.cmake
  "include(\"\${CMAKE_CURRENT_LIST_DIR}/BricklightConfig.cmake\")\n")
file(WRITE ${PROJECT_BINARY_DIR}/package/bricklight-config-version.cmake
  "include(\"\${CMAKE_CURRENT_LIST_DIR}/BricklightConfigVersion.cmake\")\n")
install(FILES
  ${PROJECT_BINARY_DIR}/package/BricklightConfig.cmake
  ${PROJECT_BINARY_DIR}/package/BricklightConfigVersion.cmake
  ${PROJECT_BINARY_DIR}/package/bricklight-config.cmake
  ${PROJECT_BINARY_DIR}/package/bricklight-config-version.cmake
  ${PROJECT_SOURCE_DIR}/cmake/BricklightShaders.cmake
  DESTINATION ${BRICKLIGHT_CMAKE_DIR})

# pkg-config: one file for the libraries; the order of -l is the link order (core and the backends before
# the RHI they use).
set(BRICKLIGHT_PC_LIBS "-lbricklight_gi -lbricklight_vct -lbricklight_shadows -lbricklight_reflections -lbricklight_gbuffer -lbricklight_sdf -lbricklight_core_common")
set(BRICKLIGHT_PC_REQUIRES "glm")
if(TARGET bricklight_vulkan)
  string(APPEND BRICKLIGHT_PC_LIBS " -lbricklight_vulkan")
  string(APPEND BRICKLIGHT_PC_REQUIRES " vulkan")
endif()
if(TARGET bricklight_gl)
  string(APPEND BRICKLIGHT_PC_LIBS " -lbricklight_gl")
endif()
string(APPEND BRICKLIGHT_PC_LIBS " -lbricklight_rhi")
set(BRICKLIGHT_PC_LIBS_PRIVATE "${CMAKE_DL_LIBS}")
if(BRICKLIGHT_PC_LIBS_PRIVATE)
  set(BRICKLIGHT_PC_LIBS_PRIVATE "-l${BRICKLIGHT_PC_LIBS_PRIVATE}")
endif()
# The prefix is found from the .pc file's own place (pkg-config's ${pcfiledir}), so that
# `cmake --install <build> --prefix <anywhere>` gives a working file, not one naming the configure-time prefix.
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(BRICKLIGHT_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH BRICKLIGHT_PC_UP "/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/")
  string(REGEX REPLACE "/$" "" BRICKLIGHT_PC_UP "${BRICKLIGHT_PC_UP}")
  set(BRICKLIGHT_PC_PREFIX "\${pcfiledir}/${BRICKLIGHT_PC_UP}")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/bricklight.pc.in ${PROJECT_BINARY_DIR}/package/bricklight.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/package/bricklight.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
