// The sinusoidal water sheet of issue 13's fold test, shared by TestWaterSheet (its
// exact caustic) and TestPhotonFocus (the photons' focus on it): water of index 1.33
// whose surface is y = Height + Amplitude sin(k x) (2 cm, wavelength 0.5 m, 1 m up),
// 2 SheetHalf = 6 m wide, with its exact normals at the vertices.
#ifndef TestWaterSheetUtilities_h
#define TestWaterSheetUtilities_h

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkSmartPointer.h"

#include "vtkCausticsMaterial.h"

#include <cmath>

namespace watersheet
{
constexpr double Amplitude = 0.02, Wavelength = 0.5, Height = 1.0, WaterIndex = 1.33;
constexpr double SheetHalf = 3.0;
const double WaveNumber = 2.0 * M_PI / Wavelength;

inline double Surface(double x)
{
  return Height + Amplitude * std::sin(WaveNumber * x);
}

/** dy/dx of the surface. */
inline double Slope(double x)
{
  return Amplitude * WaveNumber * std::cos(WaveNumber * x);
}

/** An actor drawing `data`. */
inline vtkSmartPointer<vtkActor> MakeActor(vtkPolyData* data)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/** A rectangle from `origin` along `u` and `v`, `resolution` quads per side. */
inline vtkSmartPointer<vtkActor> MakeRectangle(
  const double origin[3], const double u[3], const double v[3], int resolution = 1)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(origin[0], origin[1], origin[2]);
  plane->SetPoint1(origin[0] + u[0], origin[1] + u[1], origin[2] + u[2]);
  plane->SetPoint2(origin[0] + v[0], origin[1] + v[1], origin[2] + v[2]);
  plane->SetResolution(resolution, resolution);
  plane->Update();
  return MakeActor(plane->GetOutput());
}

/** The floor y = 0 over [-half, half]^2, its normal up. */
inline vtkSmartPointer<vtkActor> MakeFloor(double half)
{
  const double origin[3] = { -half, 0.0, half }, u[3] = { 2.0 * half, 0.0, 0.0 },
               v[3] = { 0.0, 0.0, -2.0 * half };
  return MakeRectangle(origin, u, v);
}

/** A flat silver rectangle (n 0.15, k 3.5) from `origin` along `u` and `v`. */
inline vtkSmartPointer<vtkActor> MakeMirror(const double origin[3], const double u[3], const double v[3])
{
  auto actor = MakeRectangle(origin, u, v, 8);
  const double n[3] = { 0.15, 0.15, 0.15 }, k[3] = { 3.5, 3.5, 3.5 };
  vtkCausticsMaterial::MakeMirror(actor->GetProperty(), n, k);
  return actor;
}

/**
 * The sheet over [-SheetHalf, SheetHalf]^2 in triangles: `across` quads along x (across
 * the crests: the surface's only curvature) by `along` quads along z (default as many).
 * A facet is flat, so the sheet matches the sine only as well as `across` allows: at 512
 * the floor's exact irradiance under the facets differs from the smooth surface's by
 * 2.9 % relative L2 with the sun at 30 degrees, and its fold peaks by up to 5 %; at 2048,
 * by 0.16 % (scripts/water-sheet-exact.py).
 */
inline vtkSmartPointer<vtkPolyData> MakeSheet(int across, int along = 0)
{
  along = along > 0 ? along : across;
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  normals->SetName("Normals");
  for (int j = 0; j <= along; ++j)
  {
    const double z = -SheetHalf + 2.0 * SheetHalf * j / along;
    for (int i = 0; i <= across; ++i)
    {
      const double x = -SheetHalf + 2.0 * SheetHalf * i / across;
      points->InsertNextPoint(x, Surface(x), z);
      const double length = std::sqrt(1.0 + Slope(x) * Slope(x));
      normals->InsertNextTuple3(-Slope(x) / length, 1.0 / length, 0.0);
    }
  }
  vtkNew<vtkCellArray> triangles;
  for (int j = 0; j < along; ++j)
  {
    for (int i = 0; i < across; ++i)
    {
      const vtkIdType a = j * (across + 1) + i, b = a + 1, c = a + across + 1, d = c + 1;
      const vtkIdType t1[3] = { a, c, b }, t2[3] = { b, c, d };
      triangles->InsertNextCell(3, t1);
      triangles->InsertNextCell(3, t2);
    }
  }
  auto sheet = vtkSmartPointer<vtkPolyData>::New();
  sheet->SetPoints(points);
  sheet->SetPolys(triangles);
  sheet->GetPointData()->SetNormals(normals);
  return sheet;
}
}

#endif
