/**
 * @file   FuzzInput.h
 * @brief  What the fuzz targets of Testing/Fuzz share (docs/reliability.md).
 *
 * The readers of VTK::IOCaustics take paths, so each input is written to a
 * regular file with the target's extension, in a folder of this process, and
 * read from there the way caustics-render reads a file:
 * 1. WriteInput() puts the bytes in <temp>/caustics-fuzz-XXXXXX/input<ext>;
 * 2. ImportGLTF() or ReadMesh() runs vtkCausticsGLTFImporter or
 *    vtkCausticsMeshReader on it and, on success, vtkCausticsSceneExtractor on
 *    the renderer that received the scene (what the render passes read next);
 * 3. on failure, CheckError() aborts (a finding, like a crash) unless the error
 *    is one clear line: it starts with the file's path, has no line break, only
 *    printable ASCII, at most MaxErrorLength bytes (messages quote at most 60
 *    characters of the file), and is not the importer's last-resort
 *    "unexpected glTF structure" text, which names no place in the file.
 * VTK's output window is replaced by one that drops the text, and vtkLogger's
 * output to stderr is switched off, so that the fuzzer's log stays readable; the
 * readers' error events still fire. With the environment variable
 * CAUSTICS_FUZZ_VERBOSE set, VTK's messages are shown.
 */
#ifndef FuzzInput_h
#define FuzzInput_h

#include "vtkCausticsGLTFImporter.h"
#include "vtkCausticsMeshReader.h"
#include "vtkCausticsSceneExtractor.h"

#include "vtkActor.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace caustics
{
namespace fuzz
{
/** Longest error accepted: the path, a JSON path and two quotes of 60 characters fit easily. */
constexpr std::size_t MaxErrorLength = 400;
/** Image size for the scene snapshot (its cost does not depend on it). */
constexpr int SnapshotSize = 64;

/** VTK's output window, silenced: the text is dropped, the events are not. */
class QuietOutputWindow : public vtkOutputWindow
{
public:
  static QuietOutputWindow* New();
  vtkTypeMacro(QuietOutputWindow, vtkOutputWindow);
  void DisplayText(const char*) override {}
  void DisplayErrorText(const char*) override {}
  void DisplayWarningText(const char*) override {}
  void DisplayGenericWarningText(const char*) override {}
  void DisplayDebugText(const char*) override {}
};
vtkStandardNewMacro(QuietOutputWindow);

/** The folder of this process's input files, made on first use, removed at exit. */
inline const std::string& InputFolder()
{
  static const std::string folder = []
  {
    if (!std::getenv("CAUSTICS_FUZZ_VERBOSE"))
    {
      vtkNew<QuietOutputWindow> quiet;
      vtkOutputWindow::SetInstance(quiet);
      vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF); // it logs errors itself
    }
    std::string pattern =
      (std::filesystem::temp_directory_path() / "caustics-fuzz-XXXXXX").string();
    if (!mkdtemp(&pattern[0]))
    {
      std::perror("caustics fuzz: mkdtemp");
      std::abort();
    }
    static std::string removeAtExit;
    removeAtExit = pattern;
    std::atexit([] { std::filesystem::remove_all(removeAtExit); });
    return pattern;
  }();
  return folder;
}

/** Writes the input to <folder>/input<extension> (a regular file) and returns the path. */
inline std::string WriteInput(const std::uint8_t* data, std::size_t size, const char* extension)
{
  const std::string path = InputFolder() + "/input" + extension;
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  file.close();
  if (!file)
  {
    std::perror("caustics fuzz: cannot write the input file");
    std::abort();
  }
  return path;
}

/** Aborts, printing why, unless `error` is one clear line about `path` (see the file comment). */
inline void CheckError(const std::string& path, const std::string& error)
{
  const char* problem = nullptr;
  if (error.compare(0, path.size() + 2, path + ": ") != 0)
  {
    problem = "does not start with the file's path";
  }
  else if (error.size() > MaxErrorLength)
  {
    problem = "is longer than MaxErrorLength";
  }
  else if (error.compare(path.size() + 2, 26, "unexpected glTF structure ") == 0)
  {
    problem = "is the importer's last-resort message, which names no place in the file";
  }
  for (char c : error)
  {
    if (!problem && (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f))
    {
      problem = "holds a line break or a byte outside printable ASCII";
    }
  }
  if (problem)
  {
    std::fprintf(stderr, "caustics fuzz: the error message %s:\n%s\n", problem,
      error.substr(0, 2 * MaxErrorLength).c_str());
    std::abort();
  }
}

/** The scene snapshot the render passes would read next. */
inline void Snapshot(vtkRenderer* renderer)
{
  vtkNew<vtkCausticsSceneExtractor> extractor;
  extractor->Update(renderer, SnapshotSize, SnapshotSize);
}

/** Imports the input as a glTF file with `extension` (".gltf" or ".glb"). */
inline void ImportGLTF(const std::uint8_t* data, std::size_t size, const char* extension)
{
  const std::string path = WriteInput(data, size, extension);
  // One window for the process, never rendered (no display needed) and never
  // deleted (no destruction order to get wrong at exit).
  static vtkRenderWindow* const window = vtkRenderWindow::New();
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  vtkNew<vtkCausticsGLTFImporter> importer;
  importer->SetRenderWindow(window);
  importer->SetFileName(path.c_str());
  if (importer->Update())
  {
    Snapshot(renderer);
  }
  else
  {
    CheckError(path, importer->GetLastError());
  }
  window->RemoveRenderer(renderer);
}

/** Reads the input as a mesh file with `extension` (".obj", ".stl" or ".ply"). */
inline void ReadMesh(const std::uint8_t* data, std::size_t size, const char* extension)
{
  const std::string path = WriteInput(data, size, extension);
  vtkNew<vtkCausticsMeshReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetRoleFromName("refractor");
  vtkSmartPointer<vtkActor> actor = reader->CreateActor();
  if (!actor)
  {
    CheckError(path, reader->GetLastError());
    return;
  }
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  Snapshot(renderer);
}
}
}

#endif
