// Fuzz target: the input as a glTF 2.0 JSON file (.gltf): vtkCausticsGLTFImporter, its document
// checker, VTK's glTF loader.
// Built with libFuzzer when CAUSTICS_FUZZ is ON, else replayed over its corpus
// by FuzzReplayMain.cxx (ctest FuzzCorpusReplay); see docs/reliability.md.
#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  caustics::fuzz::ImportGLTF(data, size, ".gltf");
  return 0;
}
