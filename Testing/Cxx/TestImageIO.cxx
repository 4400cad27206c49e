// EXR layers round-trip exactly (float, named layers, row order); missing
// arrays and unwritable paths are reported, not crashed on.
#include "vtkCausticsImageIO.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

namespace
{
vtkSmartPointer<vtkImageData> MakeImage()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(5, 3, 1);
  vtkNew<vtkFloatArray> color, mask;
  color->SetName("Color");
  color->SetNumberOfComponents(3);
  mask->SetName("Mask");
  mask->SetNumberOfComponents(1);
  for (int i = 0; i < 15; ++i)
  {
    color->InsertNextTuple3(i * 1000.5, -i, i * 1e-6);
    mask->InsertNextValue(i % 2);
  }
  image->GetPointData()->AddArray(color);
  image->GetPointData()->AddArray(mask);
  return image;
}
}

TEST(ImageIO, EXRLayersRoundTrip)
{
  auto image = MakeImage();
  const std::string path = std::string(CAUSTICS_TEST_OUTPUT_DIR) + "/TestImageIO.exr";
  std::string error;
  ASSERT_TRUE(
    vtkCausticsImageIO::WriteEXR(image, { { "Color", "" }, { "Mask", "mask" } }, path, &error))
    << error;
  auto back = vtkCausticsImageIO::ReadEXR(path, &error);
  ASSERT_TRUE(back) << error;
  int dims[3];
  back->GetDimensions(dims);
  EXPECT_EQ(dims[0], 5);
  EXPECT_EQ(dims[1], 3);
  auto* color = back->GetPointData()->GetArray("Default");
  auto* mask = back->GetPointData()->GetArray("mask");
  ASSERT_TRUE(color && mask);
  ASSERT_EQ(color->GetNumberOfComponents(), 3);
  for (int i = 0; i < 15; ++i)
  {
    EXPECT_FLOAT_EQ(color->GetComponent(i, 0), i * 1000.5f);
    EXPECT_FLOAT_EQ(color->GetComponent(i, 1), -i);
    EXPECT_FLOAT_EQ(color->GetComponent(i, 2), i * 1e-6f);
    EXPECT_FLOAT_EQ(mask->GetComponent(i, 0), i % 2);
  }
}

TEST(ImageIO, ReportsBadInput)
{
  auto image = MakeImage();
  std::string error;
  EXPECT_FALSE(vtkCausticsImageIO::WriteEXR(image, { { "Nope", "" } }, "x.exr", &error));
  EXPECT_NE(error.find("no array 'Nope'"), std::string::npos) << error;
  EXPECT_FALSE(
    vtkCausticsImageIO::WriteEXR(image, { { "Color", "" } }, "/nonexistent/dir/x.exr", &error));
  EXPECT_NE(error.find("/nonexistent/dir/x.exr"), std::string::npos) << error;
  EXPECT_FALSE(vtkCausticsImageIO::ReadEXR("/nonexistent.exr", &error));
  EXPECT_NE(error.find("/nonexistent.exr"), std::string::npos) << error;
  const std::string png = std::string(CAUSTICS_TEST_OUTPUT_DIR) + "/TestImageIO.png";
  EXPECT_TRUE(vtkCausticsImageIO::WritePNG(image, "Color", png, 1e-3, true, &error)) << error;
  EXPECT_FALSE(vtkCausticsImageIO::WritePNG(image, "Mask", png, 1.0, false, &error));
}
