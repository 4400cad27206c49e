/**
 * @class   vtkCausticsImageIO
 * @brief   Multi-layer EXR (linear HDR) and PNG (display) files of vtkImageData, via OpenImageIO.
 *
 * The caustics outputs are physical quantities: irradiance in W/m^2 and radiance
 * in W/(m^2 sr). EXR keeps them linear and in float, one layer per quantity:
 * each point-data array of the image becomes a layer named by the caller, with
 * channels `<layer>.R`, `<layer>.G`, `<layer>.B` (or `<layer>.Y` for one
 * component); the layer named "" is the default layer (plain `R`, `G`, `B`),
 * which image viewers display. Rows are flipped between VTK's bottom-up and the
 * files' top-down order.
 *
 * From C++, call the static functions. From Python (or any wrapped language), call
 * the *File methods on an instance, which keeps the last failure's message:
 * @code{.py}
 * io = vtkCausticsImageIO()
 * if not io.WriteEXRFile(image, ["FinalColor", "CausticIrradiance"], ["", "caustic"], "a.exr"):
 *     print(io.GetLastError())
 * @endcode
 */
#ifndef vtkCausticsImageIO_h
#define vtkCausticsImageIO_h

#include "vtkObject.h"
#include "vtkIOCausticsModule.h" // For export macro
#include "vtkSmartPointer.h"            // For return value

#include <string>  // For std::string and members
#include <utility> // For std::pair
#include <vector>  // For std::vector

class vtkImageData;

class VTKIOCAUSTICS_EXPORT vtkCausticsImageIO : public vtkObject
{
public:
  static vtkCausticsImageIO* New();
  vtkTypeMacro(vtkCausticsImageIO, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

#ifndef __VTK_WRAP__
  /**
   * Writes the listed point-data arrays (1, 3 or 4 components) of a 2D image as
   * float layers of one EXR file. Each entry is {array name, layer name}. Returns
   * false and sets `error` when an array is missing or the file cannot be written.
   */
  static bool WriteEXR(vtkImageData* image,
    const std::vector<std::pair<std::string, std::string>>& layers, const std::string& path,
    std::string* error = nullptr);

  /**
   * Reads an EXR; each layer becomes a float point-data array named after the
   * layer ("" becomes "Default"). Returns nullptr and sets `error` on failure.
   */
  static vtkSmartPointer<vtkImageData> ReadEXR(
    const std::string& path, std::string* error = nullptr);

  /**
   * Writes one 3- or 4-component array as an 8-bit PNG: value x exposure, clamped
   * to [0, 1], then sRGB-encoded when `srgb` is true (VTK's own window output is
   * not gamma-encoded, so the CLI passes false to match the on-screen picture).
   */
  static bool WritePNG(vtkImageData* image, const std::string& array, const std::string& path,
    double exposure = 1.0, bool srgb = false, std::string* error = nullptr);
#endif

  ///@{
  /**
   * The functions above for wrapped languages (Python). WriteEXRFile writes array
   * `arrays[i]` as layer `layers[i]` (the lists have the same length); ReadEXRFile
   * returns a new image the caller owns. On failure they return false or nullptr
   * and GetLastError() says why.
   */
  bool WriteEXRFile(vtkImageData* image, const std::vector<std::string>& arrays,
    const std::vector<std::string>& layers, const std::string& path);
  VTK_NEWINSTANCE vtkImageData* ReadEXRFile(const std::string& path);
  bool WritePNGFile(vtkImageData* image, const std::string& array, const std::string& path,
    double exposure = 1.0, bool srgb = false);
  ///@}

  /** Why the last *File method failed; empty after a success. */
  const char* GetLastError() const { return this->LastError.c_str(); }

protected:
  vtkCausticsImageIO() = default;
  ~vtkCausticsImageIO() override = default;

  std::string LastError;

private:
  vtkCausticsImageIO(const vtkCausticsImageIO&) = delete;
  void operator=(const vtkCausticsImageIO&) = delete;
};

#endif
