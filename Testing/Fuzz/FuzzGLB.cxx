// Fuzz target: the input as a binary glTF file (.glb): the GLB container split, then the .gltf
// path.
// Built with libFuzzer when CAUSTICS_FUZZ is ON, else replayed over its corpus
// by FuzzReplayMain.cxx (ctest FuzzCorpusReplay); see docs/reliability.md.
#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  caustics::fuzz::ImportGLTF(data, size, ".glb");
  return 0;
}
