// The cost table of 001_7c07a484f7a872bb.txt (Table 3) for this implementation:
// per photon-buffer size, the GPU time of rendering the photon buffer, of each
// gather variant and of the final render, on the built-in ball lens (256 x 256
// image). Disabled in the test suite (minutes on a CPU rasterizer); run with
//
//   build-hcm/bin/TestHierarchicalCausticMapTiming --gtest_also_run_disabled_tests
//
// under xvfb-run. CAUSTICS_TABLE3_SIZES (e.g. "256,512") picks the photon-buffer
// sizes (default 256,512,1024,2048), CAUSTICS_TABLE3_SCENE the built-in scene,
// CAUSTICS_TABLE3_FRAMES the measured frames per cell (default 3, after one warm-up
// frame; the median is reported). Times come from vtkCausticsTimings in
// synchronous mode, where each of the pass's stages starts and ends with glFinish:
// the stage's CPU time is then its wall time (Mesa's llvmpipe runs compute
// dispatches at once but timestamps them only when it flushes its rasterizer, so
// its GPU times of compute stages are meaningless). Columns: "light buffers" (GPU
// time of the shared frame's rasterization from the light) + "hcm photon buffer"
// (render photon buffer), "hcm gather" (traversal + splats into the caustic map)
// and "hcm final render".
#include "TestHierarchicalCausticMapUtilities.h"

#include "vtkCausticsLightBuffers.h"
#include "vtkCausticsTimings.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using Pass = vtkCausticsHierarchicalCausticMapPass;

struct Variant
{
  const char* Name;
  int Gather, Cluster, Splat;
};

// The columns of Table 3 this implementation has (the paper's "W&D" columns are
// the flat gather: every photon, fetched by index as §4 recommends).
const Variant Variants[] = {
  { "flat gather (W&D 2006 + §4)", Pass::GATHER_FLAT, Pass::CLUSTER_NONE, Pass::SPLAT_CONSTANT },
  { "hierarchical gather", Pass::GATHER_HIERARCHICAL, Pass::CLUSTER_NONE, Pass::SPLAT_CONSTANT },
  { "combine-last gather", Pass::GATHER_HIERARCHICAL, Pass::CLUSTER_LAST_LEVEL,
    Pass::SPLAT_CONSTANT },
  { "combine-all gather", Pass::GATHER_HIERARCHICAL, Pass::CLUSTER_ALL_LEVELS,
    Pass::SPLAT_CONSTANT },
  { "varying splats, multi-res map", Pass::GATHER_HIERARCHICAL, Pass::CLUSTER_LAST_LEVEL,
    Pass::SPLAT_VARYING_MULTIRES },
  { "varying splats, single map", Pass::GATHER_HIERARCHICAL, Pass::CLUSTER_LAST_LEVEL,
    Pass::SPLAT_VARYING_SINGLE },
};

/** Wall time (ms) of a stage of the last frame: its CPU time in synchronous mode. */
double Wall(vtkCausticsTimings* timings, const char* name)
{
  for (int i = 0; i < timings->GetNumberOfStages(); ++i)
  {
    if (std::string(timings->GetStageName(i)) == name && timings->GetStageRan(i))
    {
      return timings->GetStageCPUMilliseconds(i);
    }
  }
  return -1.0;
}

double Median(std::vector<double> values)
{
  if (values.empty())
  {
    return -1.0;
  }
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

std::vector<int> Sizes()
{
  std::vector<int> sizes = { 256, 512, 1024, 2048 };
  if (const char* text = std::getenv("CAUSTICS_TABLE3_SIZES"))
  {
    sizes.clear();
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ','))
    {
      sizes.push_back(std::atoi(item.c_str()));
    }
  }
  return sizes;
}
}

TEST(HierarchicalCausticMapTiming, DISABLED_Table3)
{
  const char* scene = std::getenv("CAUSTICS_TABLE3_SCENE");
  const int frames =
    std::getenv("CAUSTICS_TABLE3_FRAMES") ? std::atoi(std::getenv("CAUSTICS_TABLE3_FRAMES")) : 3;
  std::ostringstream table;
  table << "| photons | render photon buffer";
  for (const Variant& variant : Variants)
  {
    table << " | " << variant.Name;
  }
  table << " | final render | final render, multi-res | processed / valid |\n|---";
  for (std::size_t i = 0; i < sizeof(Variants) / sizeof(Variants[0]) + 4; ++i)
  {
    table << "|---";
  }
  table << "|\n";
  for (int size : Sizes())
  {
    hcmtest::Frame f(scene ? scene : "ball-lens", size, 256);
    ASSERT_TRUE(f.Populated);
    f.Pass->GetTimings()->SynchronousOn();
    // Table 3 times rendering the photon buffer: the light buffers must not be kept
    // from the frame before (vtkCausticsLightBuffers::ReuseUnchanged).
    f.Pass->GetLightBuffers()->ReuseUnchangedOff();
    std::vector<double> photonBuffer, finalSingle, finalMulti;
    std::vector<double> gathers;
    long long processed = 0, valid = 0;
    for (const Variant& variant : Variants)
    {
      f.Pass->SetGatherMode(variant.Gather);
      f.Pass->SetClusterMode(variant.Cluster);
      f.Pass->SetSplatMode(variant.Splat);
      std::vector<double> gather;
      for (int frame = 0; frame <= frames; ++frame)
      {
        f.Render();
        ASSERT_TRUE(f.Pass->GetLastFrameHadCaustics());
        if (frame == 0)
        {
          continue; // warm-up: first use of this variant's programs and buffers
        }
        vtkCausticsTimings* timings = f.Pass->GetTimings();
        photonBuffer.push_back(
          timings->GetGPUMilliseconds("light buffers") + Wall(timings, "hcm photon buffer"));
        gather.push_back(Wall(timings, "hcm gather"));
        (variant.Splat == Pass::SPLAT_VARYING_MULTIRES ? finalMulti : finalSingle)
          .push_back(Wall(timings, "hcm final render"));
      }
      gathers.push_back(Median(gather));
      if (variant.Cluster == Pass::CLUSTER_NONE && variant.Gather == Pass::GATHER_HIERARCHICAL)
      {
        vtkCausticsHierarchicalCausticMapPass::Counters counters;
        ASSERT_TRUE(f.Pass->GetCounters(0, counters));
        processed = counters.TotalProcessed;
        valid = counters.Valid;
      }
    }
    char line[512];
    std::snprintf(line, sizeof(line), "| %d^2 | %.1f ms", size, Median(photonBuffer));
    table << line;
    for (double gather : gathers)
    {
      std::snprintf(line, sizeof(line), " | %.1f ms", gather);
      table << line;
    }
    std::snprintf(line, sizeof(line), " | %.1f ms | %.1f ms | %lld / %lld |\n", Median(finalSingle),
      Median(finalMulti), processed, valid);
    table << line;
    std::cout << table.str() << std::flush;
  }
  std::cout << "\n" << table.str();
}
