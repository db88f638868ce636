# Texture images through the renderer's texture loader (examples/demo_renderer/texture_loader.cpp, compiled in:
# the renderer library would bring shaders and a GPU backend). Seeds in seeds/image_import_fuzzer/: small
# valid images and headers claiming 30000 x 30000, each led by the byte that picks the format.
if(TARGET PkgConfig::OpenImageIO)
  bricklight_add_fuzzer(image_import_fuzzer SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/image_import_fuzzer.cpp
    ${PROJECT_SOURCE_DIR}/examples/demo_renderer/texture_loader.cpp LIBS bricklight_scenes PkgConfig::OpenImageIO)
  target_include_directories(image_import_fuzzer PRIVATE ${PROJECT_SOURCE_DIR}/examples/demo_renderer)
endif()
