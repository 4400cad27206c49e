/**
 * @class   vtkCausticsMeshReader
 * @brief   Reads a triangle mesh from .ply, .obj or .stl and makes a caustics actor of it.
 *
 * The file is read by VTK's own reader for its extension (case-insensitive):
 * vtkPLYReader, vtkOBJReader or vtkSTLReader. Those readers report some bad files
 * only as warnings, accept faces that refer to missing vertices, silently drop the
 * tail of a truncated binary STL, read unparsable OBJ coordinates as 0, and
 * vtkPLYReader 9.1 crashes on a truncated PLY.
 * So RequestData():
 * 1. checks that the file exists and that its extension is known;
 * 2. checks the container before VTK reads it: a PLY's header and that its body
 *    holds every element the header declares (with face indices in range), an
 *    OBJ's vertex coordinates (vtkOBJReader reads "nan" or "1.0.0" as 0), a
 *    binary STL's size against its triangle count;
 * 3. runs VTK's reader, turning its errors into this reader's error and passing
 *    its warnings on with the file name;
 * 4. checks the result: every face refers to an existing vertex, at least one
 *    polygon has only finite vertices (polygons with NaN/Inf vertices are
 *    reported in a warning; vtkCausticsSceneExtractor drops them).
 * A failure leaves the output empty, returns 0 from RequestData (Update() then
 * reports it through the executive) and sets GetLastError() to one line naming
 * the file and the problem.
 *
 * CreateActor() reads the file if needed and returns an actor with the material
 * chosen by Role, RefractiveIndex and Color, set through vtkCausticsMaterial so
 * that vtkCausticsSceneExtractor classifies it as asked, e.g. for a command line
 * `--mesh bunny.ply --role refractor --ior 1.5`. Lengths are taken as metres: the
 * mesh is not rescaled.
 */
#ifndef vtkCausticsMeshReader_h
#define vtkCausticsMeshReader_h

#include "vtkPolyDataAlgorithm.h"
#include "vtkIOCausticsModule.h" // For export macro
#include "vtkSmartPointer.h"            // For return value

#include <string> // For std::string

class vtkActor;

class VTKIOCAUSTICS_EXPORT vtkCausticsMeshReader : public vtkPolyDataAlgorithm
{
public:
  static vtkCausticsMeshReader* New();
  vtkTypeMacro(vtkCausticsMeshReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The mesh file: .ply, .obj or .stl (any letter case). Default none. */
  vtkSetFilePathMacro(FileName);
  vtkGetFilePathMacro(FileName);
  ///@}

  /** True when the file name ends in an extension this reader handles. */
  static bool IsSupportedExtension(const std::string& fileName);

  ///@{
  /**
   * Caustics role of the actor CreateActor() makes: one of vtkCausticsMaterial's
   * ROLE_NONE (0), ROLE_RECEIVER (1, default), ROLE_REFLECTOR (2), ROLE_REFRACTOR (3).
   * Other values make CreateActor() fail.
   */
  vtkSetMacro(Role, int);
  vtkGetMacro(Role, int);
  ///@}

  /**
   * Sets Role from its name as used on the command line: "none", "receiver",
   * "reflector" (or "mirror"), "refractor" (or "glass"). Returns false, sets
   * GetLastError() and leaves Role unchanged on any other name.
   */
  bool SetRoleFromName(const char* name);

  ///@{
  /**
   * Index of refraction of a refractor (outside medium: vacuum/air, 1). Must be
   * finite and >= 1, else CreateActor() fails. Default 1.5 (crown glass).
   */
  vtkSetMacro(RefractiveIndex, double);
  vtkGetMacro(RefractiveIndex, double);
  ///@}

  ///@{
  /**
   * Linear RGB colour in [0, 1], else CreateActor() fails: the diffuse albedo of a
   * receiver, the normal-incidence reflectance F0 of a reflector (its complex IOR
   * is derived from it by vtkCausticsMaterial), the display colour of a refractor
   * or of role none. Default (0.8, 0.8, 0.8).
   */
  vtkSetVector3Macro(Color, double);
  vtkGetVector3Macro(Color, double);
  ///@}

  /**
   * Reads the file (Update()) and returns a new actor rendering it with the
   * material above; its caustics name (vtkCausticsMaterial::GetName) is the file's
   * name without folder. Returns nullptr and sets GetLastError() on a read failure
   * or an invalid Role, RefractiveIndex or Color.
   */
  vtkSmartPointer<vtkActor> CreateActor();

  /** One line naming the file and the problem of the last failure; empty after a success. */
  const char* GetLastError() const { return this->LastError.c_str(); }

protected:
  vtkCausticsMeshReader();
  ~vtkCausticsMeshReader() override;

  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  /** Records (GetLastError) and reports an error; always returns 0 (RequestData's failure value).
   */
  int Fail(const std::string& message);

  char* FileName = nullptr;
  int Role = 1;
  double RefractiveIndex = 1.5;
  double Color[3] = { 0.8, 0.8, 0.8 };
  std::string LastError;
  std::string ReadError; ///< outcome of the last RequestData, kept while it is up to date

private:
  vtkCausticsMeshReader(const vtkCausticsMeshReader&) = delete;
  void operator=(const vtkCausticsMeshReader&) = delete;

  ///@{
  /**
   * Steps of RequestData(): read the file (it exists, has a supported extension,
   * is not empty); run VTK's reader on it; check the faces it produced. Each
   * returns 1, or ReadFail()'s 0 (nullptr for RunVTKReader).
   */
  int ReadFile(const std::string& path, std::string& contents);
  vtkSmartPointer<vtkPolyDataAlgorithm> RunVTKReader(const std::string& path);
  int CheckGeometry(const std::string& path, vtkPolyData* mesh);
  ///@}
  /** Fail() for a read: the message is also kept as ReadError. */
  int ReadFail(const std::string& message);
};

#endif
