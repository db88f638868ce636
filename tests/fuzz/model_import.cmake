# Model files through loadModel (examples/common): our checks and the importer's reply decoder in process,
# assimp out of process (seeds in seeds/model_import_fuzzer/: valid OBJ, MTL, PLY, glTF, GLB, STL and the
# hostile cases of issue 23, each led by the byte that picks its format).
bricklight_add_fuzzer(model_import_fuzzer SOURCES ${CMAKE_CURRENT_SOURCE_DIR}/model_import_fuzzer.cpp LIBS bricklight_scenes)
