// Fuzz target: the input as a PLY file, ASCII or binary: vtkCausticsMeshReader's PLY check, then
// vtkPLYReader.
// Built with libFuzzer when CAUSTICS_FUZZ is ON, else replayed over its corpus
// by FuzzReplayMain.cxx (ctest FuzzCorpusReplay); see docs/reliability.md.
#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  caustics::fuzz::ReadMesh(data, size, ".ply");
  return 0;
}
