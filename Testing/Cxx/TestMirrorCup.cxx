// A mirror cup (issue 13): an open silver cylinder, 1 m tall and 1 m in radius,
// standing on a floor under a sun 30 degrees above it. Light reflected by the
// inner wall focuses into a cusp on the floor inside; some of it meets the wall
// again (second reflections), and the outer wall throws a wedge back onto the
// floor outside. Each technique's caustic irradiance against the CPU reference of
// the same frame, from above and from an oblique view, 256 x 256 pixels,
// 256 x 256 photons (caustic maps: MaximumReflections 3, their default).
#include "TestReferenceUtilities.h"

#include "vtkCausticsErrorMetrics.h"
#include "vtkCausticsProgressivePhotonPass.h"
#include "vtkCausticsReferenceRenderer.h"
#include "vtkCausticsScreenSpacePhotonPass.h"
#include "vtkCausticsTechniques.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderer.h"
#include "vtkRenderWindow.h"

#include <gtest/gtest.h>

#include <functional>
#include <iostream>
#include <string>

namespace
{
struct MirrorCup
{
  static constexpr int Size = 256;
  vtkNew<vtkOpenGLRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkSmartPointer<vtkImageData> Truth;

  /** From above (0) or obliquely (1). */
  explicit MirrorCup(int view)
  {
    reftest::MirrorCupScene(this->Renderer, view);
    this->Window->SetOffScreenRendering(1);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(Size, Size);
    this->Window->AddRenderer(this->Renderer);
    vtkNew<vtkCausticsReferenceRenderer> reference;
    reference->SetInputRenderer(this->Renderer);
    reference->SetImageSize(Size, Size);
    reference->SetPhotonsPerLight(4000000);
    reference->CameraSeesRefractorsOff();
    EXPECT_TRUE(reference->Update()) << reference->GetLastError();
    this->Truth = reference->GetOutput();
  }

  /** Relative L2 and flux ratio of `technique`'s caustic after three frames;
   * `configure` may set the pass's knobs first. */
  void Compare(const std::string& technique, double& l2, double& flux,
    const std::function<void(vtkCausticsRenderPass*)>& configure = nullptr)
  {
    vtkSmartPointer<vtkCausticsRenderPass> pass = vtkCausticsTechniques::Create(technique);
    ASSERT_TRUE(pass);
    if (configure)
    {
      configure(pass);
    }
    pass->SetLightBufferResolution(256);
    pass->KeepBuffersOn();
    this->Renderer->SetPass(pass);
    for (int frame = 0; frame < 3; ++frame)
    {
      this->Window->Render();
    }
    vtkNew<vtkImageData> caustic;
    EXPECT_TRUE(pass->ReadBuffer("CausticIrradiance", caustic));
    this->Renderer->SetPass(nullptr);
    pass->ReleaseGraphicsResources(this->Window);
    vtkNew<vtkCausticsErrorMetrics> metrics;
    metrics->SetArrayName("CausticIrradiance");
    metrics->SetMaskArrayName("ReceiverMask");
    metrics->SetAreaArrayName("PixelArea");
    ASSERT_TRUE(metrics->Compute(caustic, this->Truth));
    l2 = metrics->GetRelativeL2Error();
    flux = metrics->GetFluxRatio();
    std::cout << technique << ": relative L2 " << 100.0 * l2 << " %, flux " << flux << "\n";
  }
};

struct Bound
{
  const char* Technique;
  double RelativeL2, Flux; // most relative L2, most |flux ratio - 1|
};

void Check(int view, std::initializer_list<Bound> bounds)
{
  vtkCausticsProgressivePhotonPass::RegisterTechnique();
  MirrorCup cup(view);
  for (const Bound& bound : bounds)
  {
    double l2 = 1.0, flux = 0.0;
    cup.Compare(bound.Technique, l2, flux);
    EXPECT_LT(l2, bound.RelativeL2) << bound.Technique;
    EXPECT_NEAR(flux, 1.0, bound.Flux) << bound.Technique;
  }
}
}

// Measured from above: screen-space 8.7 %, flux 0.986 (8.8 % and 0.983 before the
// splats kept their flux at a receiver's end and along the image's border,
// docs/accuracy.md); caustic maps 8.8 %, 0.986
// (23.2 % with the paper's max-distance spacing, MaxDistanceFraction 1, which blurs
// the cusp's arms across; at 128 x 128 pixels, until 2026-12-04, 6.5 %, 0.987, and
// 21.8 % and 0.922 while their photons passed through the mirror they met a second
// time); cpu-progressive 4.4 %, 1.000 (three frames of 65536 photons: at 256 x 256
// pixels its kernels hold a quarter of the photons they held at 128). Bounds just
// above.
TEST(MirrorCup, SecondReflectionsFromAbove)
{
  Check(0,
    { { "screen-space", 0.09, 0.02 }, { "caustic-maps", 0.09, 0.016 },
      { "cpu-progressive", 0.046, 0.005 } });
}

// Obliquely: screen-space 15.9 %, flux 0.988 (16.5 % and 0.978 before the splats kept
// their flux at a receiver's end and along the image's border, docs/accuracy.md; at
// 128 x 128 pixels 19.1 % and 0.969, "Mirror cup"); caustic maps 14.4 %, 1.015 (17.3 %, 1.017 with the
// max-distance spacing; at 128 pixels 11.6 %, 0.997, and 54.7 % and 1.25 before the
// second reflections); cpu-progressive 12.5 %, 1.000. Before the reference's estimate
// held up to a receiver's end (docs/reference.md) and the caustic maps' kernels gave
// the floor what they lost on the wall at its foot: 16.3 % and 0.981, 14.3 % and
// 1.012. The floor's ring along the wall's foot is what the screen-space splats lost.
TEST(MirrorCup, SecondReflectionsObliquely)
{
  Check(1,
    { { "screen-space", 0.165, 0.015 }, { "caustic-maps", 0.15, 0.018 },
      { "cpu-progressive", 0.13, 0.005 } });
}

// Where the oblique screen-space error comes from (not run by default:
// --gtest_also_run_disabled_tests; figures in docs/accuracy.md, "Mirror cup"): the
// cup is wholly in the frame, so the automatic trace view is the camera's, which
// sees the floor inside the cup at a grazing angle behind the wall; the fitted view
// looks half-way to the sun.
TEST(MirrorCup, DISABLED_ObliqueScreenSpaceByTraceView)
{
  MirrorCup cup(1);
  const char* names[] = { "automatic", "camera", "fitted" };
  for (int mode = 0; mode < 3; ++mode)
  {
    double l2 = 1.0, flux = 0.0;
    std::cout << names[mode] << " trace view, ";
    cup.Compare("screen-space", l2, flux, [mode](vtkCausticsRenderPass* pass) {
      vtkCausticsScreenSpacePhotonPass::SafeDownCast(pass)->SetTraceView(mode);
    });
  }
}
