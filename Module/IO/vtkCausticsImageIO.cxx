#include "vtkCausticsImageIO.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <map>

vtkStandardNewMacro(vtkCausticsImageIO);

void vtkCausticsImageIO::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Backend: OpenImageIO " << OIIO_VERSION_STRING << "\n";
  os << indent << "LastError: " << this->LastError << "\n";
}

namespace
{
void SetError(std::string* error, const std::string& message)
{
  if (error)
  {
    *error = message;
  }
}

const char* ChannelSuffix(int components, int c)
{
  static const char* rgba[] = { "R", "G", "B", "A" };
  return components == 1 ? "Y" : rgba[c];
}

/**
 * The arrays of the layers (name, EXR layer) and their channel names ("R", "G",
 * "B", "A" or "Y", prefixed with "<layer>." unless the layer is unnamed). False,
 * with the error, for a missing array or one of 2 or more than 4 components.
 */
bool CollectLayers(vtkImageData* image,
  const std::vector<std::pair<std::string, std::string>>& layers, const std::string& path,
  std::vector<vtkDataArray*>& arrays, std::vector<std::string>& channelNames, std::string* error)
{
  for (const auto& layer : layers)
  {
    vtkDataArray* array = image->GetPointData()->GetArray(layer.first.c_str());
    if (!array)
    {
      SetError(error, "image has no array '" + layer.first + "' to write to " + path);
      return false;
    }
    const int components = array->GetNumberOfComponents();
    if (components != 1 && components != 3 && components != 4)
    {
      SetError(error,
        "array '" + layer.first + "' has " + std::to_string(components) +
          " components; EXR layers need 1, 3 or 4");
      return false;
    }
    arrays.push_back(array);
    for (int c = 0; c < components; ++c)
    {
      channelNames.push_back(layer.second.empty()
          ? ChannelSuffix(components, c)
          : layer.second + "." + ChannelSuffix(components, c));
    }
  }
  return true;
}

/** The arrays' values interleaved per pixel, top row first as files store them. */
std::vector<float> InterleavePixels(
  const std::vector<vtkDataArray*>& arrays, int width, int height, int channels)
{
  std::vector<float> pixels(static_cast<std::size_t>(width) * height * channels);
  for (int y = 0; y < height; ++y)
  {
    const int fileRow = height - 1 - y;
    for (int x = 0; x < width; ++x)
    {
      const vtkIdType id = static_cast<vtkIdType>(y) * width + x;
      float* out = &pixels[(static_cast<std::size_t>(fileRow) * width + x) * channels];
      for (vtkDataArray* array : arrays)
      {
        for (int c = 0; c < array->GetNumberOfComponents(); ++c)
        {
          *out++ = static_cast<float>(array->GetComponent(id, c));
        }
      }
    }
  }
  return pixels;
}

/** Writes interleaved float pixels with OpenImageIO, ZIP-compressed. */
bool WriteFloatImage(const std::string& path, int width, int height,
  const std::vector<std::string>& channelNames, const std::vector<float>& pixels,
  std::string* error)
{
  auto output = OIIO::ImageOutput::create(path);
  if (!output)
  {
    SetError(error, "cannot create " + path + ": " + OIIO::geterror());
    return false;
  }
  OIIO::ImageSpec spec(width, height, static_cast<int>(channelNames.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = channelNames;
  spec.attribute("compression", "zip");
  if (!output->open(path, spec) || !output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) ||
    !output->close())
  {
    SetError(error, "cannot write " + path + ": " + output->geterror());
    return false;
  }
  return true;
}
}

bool vtkCausticsImageIO::WriteEXR(vtkImageData* image,
  const std::vector<std::pair<std::string, std::string>>& layers, const std::string& path,
  std::string* error)
{
  if (!image)
  {
    SetError(error, "no image to write to " + path);
    return false;
  }
  int dims[3];
  image->GetDimensions(dims);
  const int width = dims[0], height = dims[1];
  if (width <= 0 || height <= 0 || dims[2] != 1)
  {
    SetError(error, "image to write to " + path + " is not a 2D image");
    return false;
  }
  std::vector<vtkDataArray*> arrays;
  std::vector<std::string> channelNames;
  if (!CollectLayers(image, layers, path, arrays, channelNames, error))
  {
    return false;
  }
  const int channels = static_cast<int>(channelNames.size());
  if (channels == 0)
  {
    SetError(error, "no layers to write to " + path);
    return false;
  }
  return WriteFloatImage(
    path, width, height, channelNames, InterleavePixels(arrays, width, height, channels), error);
}

vtkSmartPointer<vtkImageData> vtkCausticsImageIO::ReadEXR(
  const std::string& path, std::string* error)
{
  auto input = OIIO::ImageInput::open(path);
  if (!input)
  {
    SetError(error, "cannot open " + path + ": " + OIIO::geterror());
    return nullptr;
  }
  const OIIO::ImageSpec& spec = input->spec();
  const int width = spec.width, height = spec.height, channels = spec.nchannels;
  if (width <= 0 || height <= 0 || channels <= 0 || spec.depth > 1)
  {
    SetError(error, path + " is not a 2D image");
    return nullptr;
  }
  std::vector<float> pixels(static_cast<std::size_t>(width) * height * channels);
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
  {
    SetError(error, "cannot read " + path + ": " + input->geterror());
    return nullptr;
  }
  input->close();

  // Group channels "<layer>.<c>" into layers, keeping file order.
  std::vector<std::string> order;
  std::map<std::string, std::vector<int>> layerChannels;
  for (int c = 0; c < channels; ++c)
  {
    const std::string& name = spec.channelnames[c];
    const auto dot = name.rfind('.');
    const std::string layer = dot == std::string::npos ? "Default" : name.substr(0, dot);
    if (!layerChannels.count(layer))
    {
      order.push_back(layer);
    }
    layerChannels[layer].push_back(c);
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  for (const auto& layer : order)
  {
    const auto& indices = layerChannels[layer];
    vtkNew<vtkFloatArray> array;
    array->SetName(layer.c_str());
    array->SetNumberOfComponents(static_cast<int>(indices.size()));
    array->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
    for (int y = 0; y < height; ++y)
    {
      const int fileRow = height - 1 - y;
      for (int x = 0; x < width; ++x)
      {
        const float* in = &pixels[(static_cast<std::size_t>(fileRow) * width + x) * channels];
        for (std::size_t c = 0; c < indices.size(); ++c)
        {
          array->SetComponent(
            static_cast<vtkIdType>(y) * width + x, static_cast<int>(c), in[indices[c]]);
        }
      }
    }
    image->GetPointData()->AddArray(array);
  }
  return image;
}

bool vtkCausticsImageIO::WritePNG(vtkImageData* image, const std::string& arrayName,
  const std::string& path, double exposure, bool srgb, std::string* error)
{
  vtkDataArray* array = image ? image->GetPointData()->GetArray(arrayName.c_str()) : nullptr;
  if (!array || array->GetNumberOfComponents() < 3)
  {
    SetError(error, "image has no RGB array '" + arrayName + "' to write to " + path);
    return false;
  }
  int dims[3];
  image->GetDimensions(dims);
  const int width = dims[0], height = dims[1];
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const vtkIdType id = static_cast<vtkIdType>(y) * width + x;
      for (int c = 0; c < 3; ++c)
      {
        double v = array->GetComponent(id, c) * exposure;
        v = std::isfinite(v) ? std::min(1.0, std::max(0.0, v)) : 0.0;
        if (srgb)
        {
          v = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
        }
        pixels[(static_cast<std::size_t>(height - 1 - y) * width + x) * 3 + c] =
          static_cast<unsigned char>(std::lround(v * 255.0));
      }
    }
  }
  auto output = OIIO::ImageOutput::create(path);
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  if (!output || !output->open(path, spec) ||
    !output->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !output->close())
  {
    SetError(
      error, "cannot write " + path + ": " + (output ? output->geterror() : OIIO::geterror()));
    return false;
  }
  return true;
}

bool vtkCausticsImageIO::WriteEXRFile(vtkImageData* image, const std::vector<std::string>& arrays,
  const std::vector<std::string>& layers, const std::string& path)
{
  this->LastError.clear();
  if (!image)
  {
    this->LastError = "WriteEXRFile: no image to write to " + path;
    return false;
  }
  if (arrays.size() != layers.size())
  {
    this->LastError = "WriteEXRFile: " + std::to_string(arrays.size()) + " arrays but " +
      std::to_string(layers.size()) + " layer names for " + path;
    return false;
  }
  std::vector<std::pair<std::string, std::string>> pairs;
  for (std::size_t i = 0; i < arrays.size(); ++i)
  {
    pairs.emplace_back(arrays[i], layers[i]);
  }
  return vtkCausticsImageIO::WriteEXR(image, pairs, path, &this->LastError);
}

vtkImageData* vtkCausticsImageIO::ReadEXRFile(const std::string& path)
{
  this->LastError.clear();
  vtkSmartPointer<vtkImageData> image = vtkCausticsImageIO::ReadEXR(path, &this->LastError);
  if (image)
  {
    image->Register(nullptr); // the reference handed to the caller
  }
  return image;
}

bool vtkCausticsImageIO::WritePNGFile(vtkImageData* image, const std::string& array,
  const std::string& path, double exposure, bool srgb)
{
  this->LastError.clear();
  if (!image)
  {
    this->LastError = "WritePNGFile: no image to write to " + path;
    return false;
  }
  return vtkCausticsImageIO::WritePNG(image, array, path, exposure, srgb, &this->LastError);
}
