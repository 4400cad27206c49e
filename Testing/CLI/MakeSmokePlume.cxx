// caustics-make-plume OUTPUT.vdb: writes the smoke-lens plume, a lumpy ball of smoke
// under the ball lens (radius 1.2 m around (0, 1.2, 0)), where the lens focuses the
// sun: a heterogeneous medium for the volume caustic. Written at build time
// (Testing/CLI/CMakeLists.txt) so that the repository holds no binary data.
// A level-set sphere with its surface displaced by a smooth deterministic noise,
// converted to a fog volume (density 1 inside, a ramp across the narrow band), then
// thinned by the same noise at twice the frequency.
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h> // For openvdb::tools::createLevelSetSphere
#include <openvdb/tools/LevelSetUtil.h>   // For openvdb::tools::sdfToFogVolume

#include <cmath>
#include <exception>
#include <iostream>

namespace
{
/** A smooth pseudo-noise in [-1, 1]: a product of sines (no seed, the same everywhere). */
float Noise(const openvdb::Vec3d& p, double frequency)
{
  return static_cast<float>(std::sin(3.1 * frequency * p.x() + 1.7) *
    std::sin(2.3 * frequency * p.y() + 0.4) * std::sin(2.9 * frequency * p.z() + 2.2));
}
}

int main(int argc, char* argv[])
{
  if (argc != 2)
  {
    std::cerr << "usage: caustics-make-plume OUTPUT.vdb\n";
    return 2;
  }
  try
  {
    openvdb::initialize();
    const float voxel = 0.04f, halfWidth = 4.0f;
    auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
      1.2f, openvdb::Vec3f(0.0f, 1.2f, 0.0f), voxel, halfWidth);
    for (auto value = grid->beginValueOn(); value; ++value)
    {
      const openvdb::Vec3d p = grid->indexToWorld(value.getCoord());
      value.setValue(*value + 0.12f * Noise(p, 1.0));
    }
    openvdb::tools::sdfToFogVolume(*grid);
    for (auto value = grid->beginValueOn(); value; ++value)
    {
      const openvdb::Vec3d p = grid->indexToWorld(value.getCoord());
      value.setValue(*value * (0.6f + 0.4f * Noise(p, 2.0)));
    }
    grid->setName("density");
    openvdb::io::File(argv[1]).write({ grid });
    std::cout << "wrote " << argv[1] << ": " << grid->activeVoxelCount() << " active voxels\n";
  }
  catch (const std::exception& e)
  {
    std::cerr << "caustics-make-plume: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
