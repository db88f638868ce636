# bricklight_add_shaders(<target> BASE_DIR <dir> SOURCES <file>... [INCLUDE_DIRS <dir>...])
# Compiles each GLSL source at build time (tools/shader_compiler) into an OBJECT library <target> whose
# objects embed SPIR-V, GL GLSL and reflection and register themselves with rhi::findShader(). A shader's
# name is its path relative to BASE_DIR (e.g. "rhi_tests/fill_buffer.comp"). Integrators use the same
# function for their own shaders. OBJECT (not STATIC) so that the self-registering objects always link.
function(bricklight_add_shaders target)
  cmake_parse_arguments(ARG "" "BASE_DIR" "SOURCES;INCLUDE_DIRS" ${ARGN})
  set(outputs)
  set(include_flags -I${BRICKLIGHT_SHADER_INCLUDE_DIR})
  foreach(dir ${ARG_INCLUDE_DIRS})
    list(APPEND include_flags -I${dir})
  endforeach()
  foreach(src ${ARG_SOURCES})
    get_filename_component(abs "${src}" ABSOLUTE BASE_DIR "${ARG_BASE_DIR}")
    file(RELATIVE_PATH name "${ARG_BASE_DIR}" "${abs}")
    string(MAKE_C_IDENTIFIER "${name}" ident)
    set(out "${CMAKE_CURRENT_BINARY_DIR}/${target}_gen/${ident}.cpp")
    add_custom_command(
      OUTPUT "${out}"
      COMMAND bricklight-shaderc "${name}" "${abs}" "${out}" "${out}.d" ${include_flags}
      DEPENDS bricklight-shaderc "${abs}"
      DEPFILE "${out}.d"
      COMMENT "Compiling shader ${name}"
      VERBATIM)
    list(APPEND outputs "${out}")
  endforeach()
  add_library(${target} OBJECT ${outputs})
  target_link_libraries(${target} PUBLIC bricklight_rhi)
endfunction()
