/**
 * @class   vtkCausticsMeshReader
 * @brief   Reads a triangle mesh from .ply, .obj or .stl and makes a caustics actor of it.
 *
 * The file is read by VTK's own reader for its extension (case-insensitive):
 * vtkPLYReader, vtkOBJReader or vtkSTLReader. Those readers trust the file: they
 * report some bad files only as warnings, accept faces that refer to missing
 * vertices, silently drop the tail of a truncated binary STL, read unparsable OBJ
 * numbers ("nan", "1.0.0") as 0 or as the previous line's value, read out of bounds
 * on an out-of-range OBJ normal or texture coordinate index (a crash for a far one,
 * garbage normals for a near one), and vtkPLYReader 9.1 crashes on a truncated PLY.
 * So RequestData():
 * 1. checks the path with stat() before opening it: it must be a regular file
 *    (a FIFO or a device such as /dev/zero would block or never end), with a known
 *    extension, not empty;
 * 2. streams the file once (nothing is kept but counts) to check the container
 *    before VTK reads it:
 *    - PLY: the header, and that the body holds every element the header declares,
 *      with face indices in range; the header and an ASCII body line by line and
 *      word by word as vtkPLY reads them, and vertex and face properties of the
 *      kinds vtkPLYReader stores (docs/reliability.md lists why);
 *    - OBJ: lines of at most 262142 bytes (vtkOBJReader's buffer) without NUL
 *      bytes; "v" lines of three decimal numbers that fit a 32-bit float; every
 *      vertex, texture coordinate and normal index of the "f", "l" and "p" lines,
 *      absolute (1..count of "v"/"vt"/"vn" lines in the file) or relative (-1 is
 *      the last line above); material names of at most 99 bytes (vtkOBJReader's
 *      buffer);
 *    - STL: a binary file's size against its triangle count; every vertex
 *      coordinate finite (vtkSTLReader's point merging converts it to a bucket
 *      index);
 * 3. runs VTK's reader, turning its first error into this reader's error (VTK's
 *    reason, e.g. "Premature EOF ... line 5", quoted) and passing its warnings on
 *    with the file name; the reader's executive's "returned failure for request"
 *    dump is kept out of the output window;
 * 4. checks the result: every face refers to an existing vertex, every vertex
 *    position is finite (a NaN/Inf position is an error), and at least one
 *    polygon has a triangle of non-zero area (the area test of
 *    vtkCausticsSceneExtractor, which drops degenerate triangles);
 * 5. repairs normals: when an OBJ "vn" line is not three finite numbers, a PLY
 *    normal is NaN/Inf, or the normals do not cover every vertex, a warning names
 *    the file and the first bad one, and the point normals are dropped, so that
 *    vtkCausticsSceneExtractor (and VTK's mapper) recompute them from the
 *    triangles; other point or cell arrays shorter than the points or cells are
 *    dropped silently (caustics does not use them). When vtkOBJReader dropped
 *    faces (it drops faces without normals when others have them), a warning
 *    says how many.
 * A failure leaves the output empty, returns 0 from RequestData (Update() then
 * reports it through the executive) and sets GetLastError() to one line naming
 * the file and the problem. Text from the file is quoted at most 60 characters
 * long, with bytes outside printable ASCII escaped as \xNN.
 *
 * CreateActor() reads the file if needed and returns an actor with the material
 * chosen by Role, RefractiveIndex and Color, set through vtkCausticsMaterial so
 * that vtkCausticsSceneExtractor classifies it as asked, e.g. for a command line
 * `--mesh bunny.ply --role refractor --ior 1.5`. Lengths are taken as metres: the
 * mesh is not rescaled.
 */
#ifndef vtkCausticsMeshReader_h
#define vtkCausticsMeshReader_h

#include "vtkIOCausticsModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // For return value

#include <cstdint> // For std::uint64_t
#include <string>  // For std::string

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
   * Steps of RequestData(): check the path (a regular file with a supported
   * extension, not empty; its size is returned); run VTK's reader on it; check the
   * faces it produced. Each returns 1, or ReadFail()'s 0 (nullptr for RunVTKReader).
   */
  int CheckFile(const std::string& path, std::uint64_t& size);
  vtkSmartPointer<vtkPolyDataAlgorithm> RunVTKReader(const std::string& path);
  int CheckGeometry(const std::string& path, vtkPolyData* mesh);
  ///@}
  /**
   * Drops the point normals of `mesh`, with a warning, when `problem` (a bad OBJ
   * "vn" line) is set or a normal is NaN/Inf; consumers then recompute them.
   */
  void RepairNormals(const std::string& path, vtkPolyData* mesh, std::string problem);
  /** Fail() for a read: the message is also kept as ReadError. */
  int ReadFail(const std::string& message);
};

#endif
