// Replays fuzz inputs without libFuzzer, for compilers without it (gcc, CI):
// linked with one fuzz target, it feeds every file named on the command line,
// and every regular file of every folder named (sorted, so runs are alike), to
// LLVMFuzzerTestOneInput. A crash or a failed check of the target ends the run
// with the input's name printed just before. ctest FuzzCorpusReplay runs it over
// the seed corpus and crashes/ (docs/reliability.md).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace
{
/** The files an argument names: itself, or a folder's regular files by name (none if absent). */
std::vector<std::filesystem::path> Inputs(const std::filesystem::path& argument)
{
  std::vector<std::filesystem::path> files;
  std::error_code error;
  if (!std::filesystem::is_directory(argument, error))
  {
    if (std::filesystem::is_regular_file(argument, error))
    {
      files.push_back(argument);
    }
    return files;
  }
  for (const auto& entry : std::filesystem::directory_iterator(argument))
  {
    if (entry.is_regular_file())
    {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}
}

int main(int argc, char* argv[])
{
  std::size_t count = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int a = 1; a < argc; ++a)
  {
    for (const auto& path : Inputs(argv[a]))
    {
      std::ifstream file(path, std::ios::binary);
      const std::vector<char> bytes(
        (std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
      std::printf("replay: %s (%zu bytes)\n", path.c_str(), bytes.size());
      std::fflush(stdout);
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      ++count;
    }
  }
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("replayed %zu inputs in %.2f s\n", count, seconds);
  return count > 0 ? 0 : 1;
}
