#include "StressChecks.h"

#include "vtkCausticsRenderPass.h"
#include "vtkCausticsSceneData.h"
#include "vtkCausticsSceneExtractor.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace stress
{
namespace
{
using caustics::Vec3;

/** VTK's output window, keeping errors (their message part) and counting warnings. */
class CaptureWindow : public vtkOutputWindow
{
public:
  static CaptureWindow* New();
  vtkTypeMacro(CaptureWindow, vtkOutputWindow);
  void DisplayErrorText(const char* text) override
  {
    if (this->Listening)
    {
      std::string message = text ? text : "";
      const std::size_t header = message.find('\n');
      const std::size_t object = message.find("): ", header == std::string::npos ? 0 : header);
      if (header != std::string::npos && object != std::string::npos)
      {
        message = message.substr(object + 3);
      }
      while (!message.empty() && message.back() == '\n')
      {
        message.pop_back();
      }
      this->Errors.push_back(message);
    }
  }
  void DisplayWarningText(const char*) override { this->Warnings += this->Listening ? 1 : 0; }
  void DisplayGenericWarningText(const char* text) override { this->DisplayWarningText(text); }
  void DisplayText(const char*) override {}
  void DisplayDebugText(const char*) override {}

  std::vector<std::string> Errors;
  int Warnings = 0;
  bool Listening = true;
};
vtkStandardNewMacro(CaptureWindow);

CaptureWindow* Capture()
{
  static vtkNew<CaptureWindow> window;
  return window;
}

/** Reads a layer, or null when the frame did not make it (its error not counted). */
vtkSmartPointer<vtkImageData> Read(vtkCausticsRenderPass* pass, const std::string& name)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  Messages::SetListening(false);
  const bool read = pass->ReadBuffer(name.c_str(), image);
  Messages::SetListening(true);
  return read ? image : nullptr;
}

bool AllFinite(vtkDataArray* values, bool nonNegative)
{
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < values->GetNumberOfComponents(); ++c)
    {
      const double v = values->GetComponent(i, c);
      if (!std::isfinite(v) || (nonNegative && v < 0.0))
      {
        return false;
      }
    }
  }
  return true;
}

/** Receiver area seen by pixel (i, j) around x: caustics::ReferenceCore's PixelArea. */
double PixelArea(const caustics::Camera& view, int i, int j, const Vec3& x, const Vec3& n)
{
  Vec3 corners[4];
  const double offsets[4][2] = { { -0.5, -0.5 }, { 0.5, -0.5 }, { 0.5, 0.5 }, { -0.5, 0.5 } };
  for (int c = 0; c < 4; ++c)
  {
    Vec3 o, d;
    view.PixelRay(i + offsets[c][0], j + offsets[c][1], o, d);
    const double denominator = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    const double t =
      ((x[0] - o[0]) * n[0] + (x[1] - o[1]) * n[1] + (x[2] - o[2]) * n[2]) / denominator;
    if (!(std::abs(denominator) > 1e-9 && t > 0.0 && std::isfinite(t)))
    {
      return 0.0; // grazing: the corner ray misses the plane; counted as no area (bound side)
    }
    for (int k = 0; k < 3; ++k)
    {
      corners[c][k] = o[k] + d[k] * t;
    }
  }
  Vec3 a, b;
  for (int k = 0; k < 3; ++k)
  {
    a[k] = corners[2][k] - corners[0][k];
    b[k] = corners[3][k] - corners[1][k];
  }
  const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2],
               cz = a[0] * b[1] - a[1] * b[0];
  const double area = 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
  return std::isfinite(area) ? area : 0.0;
}

/** Flux (W per channel) one light can send into a sphere of radius r around c. */
Vec3 LightBound(const caustics::Light& light, const Vec3& c, double r)
{
  double reach = M_PI * r * r; // directional: m^2 of cross-section
  if (light.type != caustics::Light::Type::Directional)
  {
    const double dx = light.position[0] - c[0], dy = light.position[1] - c[1],
                 dz = light.position[2] - c[2];
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
    reach = d <= r ? 4.0 * M_PI : 2.0 * M_PI * (1.0 - std::sqrt(1.0 - (r * r) / (d * d)));
  }
  return { light.radiometric[0] * reach, light.radiometric[1] * reach,
    light.radiometric[2] * reach };
}
}

double Energy::Ratio() const
{
  double ratio = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    if (this->Flux[c] > 0.0)
    {
      ratio = std::max(ratio, this->Bound[c] > 0.0 ? this->Flux[c] / this->Bound[c] : HUGE_VAL);
    }
  }
  return ratio;
}

std::vector<std::string> NonFiniteLayers(vtkCausticsRenderPass* pass, bool vtkColour)
{
  std::vector<std::string> names = { "CausticIrradiance", "DirectIrradiance", "VolumeRadiance",
    "Position", "Normal", "Albedo", "Depth", "RefractivePosition", "RefractiveNormal",
    "RefractiveDepth" };
  if (vtkColour)
  {
    names.push_back("FinalColor");
    names.push_back("TechniqueColor");
  }
  const std::size_t lights = pass->GetSceneExtractor()->GetScene().Lights.size();
  for (std::size_t i = 0; i < lights; ++i)
  {
    for (const char* base : { "LightPosition:", "LightNormal:", "LightFlux:", "LightDepth:" })
    {
      names.push_back(base + std::to_string(i));
    }
  }
  std::vector<std::string> bad;
  for (const std::string& name : names)
  {
    auto image = Read(pass, name);
    const bool nonNegative = name == "CausticIrradiance" || name == "VolumeRadiance";
    if (image && !AllFinite(image->GetPointData()->GetArray(0), nonNegative))
    {
      bad.push_back(name);
    }
  }
  return bad;
}

Energy MeasureEnergy(vtkCausticsRenderPass* pass)
{
  Energy energy;
  auto caustic = Read(pass, "CausticIrradiance");
  auto position = Read(pass, "Position");
  auto normal = Read(pass, "Normal");
  if (!caustic || !position || !normal)
  {
    return energy;
  }
  const caustics::SceneData& scene = pass->GetSceneExtractor()->GetScene();
  vtkDataArray* e = caustic->GetPointData()->GetArray(0);
  vtkDataArray* p = position->GetPointData()->GetArray(0);
  vtkDataArray* n = normal->GetPointData()->GetArray(0);
  int dims[3];
  caustic->GetDimensions(dims);
  for (int j = 0; j < dims[1]; ++j)
  {
    for (int i = 0; i < dims[0]; ++i)
    {
      const vtkIdType id = static_cast<vtkIdType>(j) * dims[0] + i;
      if (std::lround(n->GetComponent(id, 3)) != 1)
      {
        continue; // not a receiver
      }
      const Vec3 x{ p->GetComponent(id, 0), p->GetComponent(id, 1), p->GetComponent(id, 2) };
      const Vec3 normalVector{ n->GetComponent(id, 0), n->GetComponent(id, 1),
        n->GetComponent(id, 2) };
      const double area = PixelArea(scene.View, i, j, x, normalVector);
      for (int c = 0; c < 3; ++c)
      {
        energy.Flux[c] += e->GetComponent(id, c) * area;
      }
    }
  }
  const double* b = scene.SpecularBounds;
  const Vec3 centre{ 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  const double radius = 0.5 *
    std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
      (b[5] - b[4]) * (b[5] - b[4])) *
    (1.0 + 3.0 / pass->GetLightBufferResolution());
  for (const caustics::Light& light : scene.Lights)
  {
    const Vec3 bound = LightBound(light, centre, radius);
    for (int c = 0; c < 3; ++c)
    {
      energy.Bound[c] += bound[c];
    }
  }
  return energy;
}

void Messages::Install()
{
  vtkOutputWindow::SetInstance(Capture());
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF); // errors reach the capture only
}

const std::vector<std::string>& Messages::Errors()
{
  return Capture()->Errors;
}

int Messages::Warnings()
{
  return Capture()->Warnings;
}

void Messages::Clear()
{
  Capture()->Errors.clear();
  Capture()->Warnings = 0;
}

void Messages::SetListening(bool on)
{
  Capture()->Listening = on;
}
}
