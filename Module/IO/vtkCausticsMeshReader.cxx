#include "vtkCausticsMeshReader.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCausticsMaterial.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkObjectFactory.h"
#include "vtkPLYReader.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSTLReader.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkCausticsMeshReader);

namespace
{
std::string LowerExtension(const std::string& fileName)
{
  return vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(fileName));
}

bool ReadWholeFile(const std::string& path, std::string& contents)
{
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    return false;
  }
  std::ostringstream buffer;
  buffer << file.rdbuf();
  contents = buffer.str();
  return !file.bad();
}

/** Keeps the message of a VTK error/warning event, without VTK's "file, line" preamble. */
std::string EventText(const char* text)
{
  std::string message = text ? text : "";
  // vtkErrorMacro texts look like "ERROR: In file, line N\nClass (0x...): message\n\n".
  const std::size_t object = message.find("): ");
  if (object != std::string::npos)
  {
    message = message.substr(object + 3);
  }
  while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
  {
    message.pop_back();
  }
  std::replace(message.begin(), message.end(), '\n', ' ');
  return message;
}

/** Errors and warnings of VTK's reader, in order. */
struct ReaderMessages
{
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
};

void CollectMessages(vtkObject*, unsigned long event, void* clientData, void* callData)
{
  auto* messages = static_cast<ReaderMessages*>(clientData);
  (event == vtkCommand::ErrorEvent ? messages->Errors : messages->Warnings)
    .push_back(EventText(static_cast<const char*>(callData)));
}

// --- PLY container check --------------------------------------------------------------------
// vtkPLYReader (VTK 9.1) frees invalid pointers when the body is shorter than the
// header says, so the body is walked here first. This reads no geometry: VTK does.

/** Bytes of a PLY scalar type, 0 when the name is not a PLY type. */
int PlyTypeSize(const std::string& type)
{
  if (type == "char" || type == "int8" || type == "uchar" || type == "uint8")
  {
    return 1;
  }
  if (type == "short" || type == "int16" || type == "ushort" || type == "uint16")
  {
    return 2;
  }
  if (type == "int" || type == "int32" || type == "uint" || type == "uint32" || type == "float" ||
    type == "float32")
  {
    return 4;
  }
  if (type == "double" || type == "float64")
  {
    return 8;
  }
  return 0;
}

bool PlyTypeIsFloat(const std::string& type)
{
  return type == "float" || type == "float32" || type == "double" || type == "float64";
}

bool PlyTypeIsSigned(const std::string& type)
{
  return type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" ||
    type == "int32";
}

struct PlyProperty
{
  std::string name;
  std::string type;      ///< value type
  std::string countType; ///< list length type; empty for a scalar property
};

struct PlyElement
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

/** Walks a PLY file's header and body; Check() returns the first problem or "". */
class PlyChecker
{
public:
  std::string Check(const std::string& contents)
  {
    std::string problem = this->ParseHeader(contents);
    if (!problem.empty())
    {
      return problem;
    }
    for (const PlyElement& element : this->Elements)
    {
      const bool isFace = element.name == "face";
      for (std::uint64_t i = 0; i < element.count; ++i)
      {
        for (const PlyProperty& property : element.properties)
        {
          double count = 1.0;
          if (!property.countType.empty() && !this->Value(property.countType, count))
          {
            return this->Truncated(element, i);
          }
          if (!(count >= 0.0) || count != std::floor(count))
          {
            return "element '" + element.name + "' " + std::to_string(i) + ": list length " +
              std::to_string(count) + " is not a non-negative integer";
          }
          const bool isIndex = isFace && !property.countType.empty() &&
            (property.name == "vertex_indices" || property.name == "vertex_index");
          for (double k = 0; k < count; ++k)
          {
            double value = 0.0;
            if (!this->Value(property.type, value))
            {
              return this->Truncated(element, i);
            }
            if (isIndex && !(value >= 0.0 && value < static_cast<double>(this->VertexCount)))
            {
              return "face " + std::to_string(i) + " refers to vertex " +
                std::to_string(static_cast<long long>(value)) + ", but the file has " +
                std::to_string(this->VertexCount) + " vertices";
            }
          }
        }
      }
    }
    return std::string();
  }

private:
  std::string ParseHeader(const std::string& contents)
  {
    std::istringstream header(contents);
    std::string line;
    if (!std::getline(header, line) || line.compare(0, 3, "ply") != 0)
    {
      return "not a PLY file (it does not start with 'ply')";
    }
    bool haveFormat = false;
    while (std::getline(header, line))
    {
      if (!line.empty() && line.back() == '\r')
      {
        line.pop_back();
      }
      std::istringstream words(line);
      std::string keyword;
      words >> keyword;
      if (keyword == "end_header")
      {
        this->Cursor = static_cast<std::size_t>(header.tellg());
        this->Data = &contents;
        if (!haveFormat)
        {
          return "the header has no 'format' line";
        }
        return this->CheckVertexElement();
      }
      std::string problem;
      if (keyword == "format")
      {
        problem = this->ParseFormat(words);
        haveFormat = true;
      }
      else if (keyword == "element")
      {
        problem = this->ParseElement(words, line);
      }
      else if (keyword == "property")
      {
        problem = this->ParseProperty(words, line);
      }
      else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty())
      {
        problem = "unknown header line '" + line + "'";
      }
      if (!problem.empty())
      {
        return problem;
      }
    }
    return "the header has no 'end_header' line";
  }

  /** "format ascii|binary_little_endian|binary_big_endian 1.0" */
  std::string ParseFormat(std::istringstream& words)
  {
    std::string format;
    words >> format;
    if (format == "ascii")
    {
      this->Ascii = true;
    }
    else if (format == "binary_little_endian" || format == "binary_big_endian")
    {
      this->BigEndian = format == "binary_big_endian";
    }
    else
    {
      return "unknown PLY format '" + format + "'";
    }
    return std::string();
  }

  /** "element <name> <count>" */
  std::string ParseElement(std::istringstream& words, const std::string& line)
  {
    PlyElement element;
    long long count = -1;
    words >> element.name >> count;
    if (!words || count < 0)
    {
      return "malformed header line '" + line + "'";
    }
    element.count = static_cast<std::uint64_t>(count);
    this->Elements.push_back(element);
    return std::string();
  }

  /** "property <type> <name>" or "property list <count type> <type> <name>" */
  std::string ParseProperty(std::istringstream& words, const std::string& line)
  {
    if (this->Elements.empty())
    {
      return "header line '" + line + "' comes before any element";
    }
    PlyProperty property;
    words >> property.type;
    if (property.type == "list")
    {
      words >> property.countType >> property.type;
      if (PlyTypeSize(property.countType) == 0 || PlyTypeIsFloat(property.countType))
      {
        return "header line '" + line + "': bad list length type";
      }
    }
    words >> property.name;
    if (!words || PlyTypeSize(property.type) == 0)
    {
      return "malformed header line '" + line + "'";
    }
    this->Elements.back().properties.push_back(property);
    return std::string();
  }

  std::string CheckVertexElement()
  {
    for (const PlyElement& element : this->Elements)
    {
      if (element.name != "vertex")
      {
        continue;
      }
      int xyz = 0;
      for (const PlyProperty& property : element.properties)
      {
        const bool coordinate =
          property.name == "x" || property.name == "y" || property.name == "z";
        xyz += coordinate && property.countType.empty() ? 1 : 0;
      }
      if (xyz != 3)
      {
        return "the 'vertex' element lacks scalar x, y and z properties";
      }
      this->VertexCount = element.count;
      return std::string();
    }
    return "the header declares no 'vertex' element";
  }

  std::string Truncated(const PlyElement& element, std::uint64_t index) const
  {
    return "the file ends inside element '" + element.name + "' " + std::to_string(index) + " of " +
      std::to_string(element.count) + " (truncated?)";
  }

  /** Reads the next value of a PLY type; false at the end of the data or on a non-number. */
  bool Value(const std::string& type, double& value)
  {
    const std::string& data = *this->Data;
    if (this->Ascii)
    {
      while (
        this->Cursor < data.size() && std::isspace(static_cast<unsigned char>(data[this->Cursor])))
      {
        ++this->Cursor;
      }
      const std::size_t begin = this->Cursor;
      while (
        this->Cursor < data.size() && !std::isspace(static_cast<unsigned char>(data[this->Cursor])))
      {
        ++this->Cursor;
      }
      if (begin == this->Cursor)
      {
        return false;
      }
      const std::string token = data.substr(begin, this->Cursor - begin);
      char* end = nullptr;
      value = std::strtod(token.c_str(), &end);
      return end && *end == '\0';
    }
    const int size = PlyTypeSize(type);
    if (this->Cursor + size > data.size())
    {
      return false;
    }
    unsigned char bytes[8];
    std::memcpy(bytes, data.data() + this->Cursor, size);
    this->Cursor += size;
    const std::uint16_t probe = 1;
    const bool hostLittle = *reinterpret_cast<const unsigned char*>(&probe) == 1;
    if (this->BigEndian == hostLittle)
    {
      std::reverse(bytes, bytes + size);
    }
    if (PlyTypeIsFloat(type))
    {
      if (size == 4)
      {
        float f;
        std::memcpy(&f, bytes, 4);
        value = f;
      }
      else
      {
        std::memcpy(&value, bytes, 8);
      }
      return true;
    }
    std::uint64_t raw = 0;
    std::memcpy(&raw, bytes, size); // host order after the swap above
    if (!hostLittle)
    {
      raw >>= 8 * (8 - size);
    }
    if (PlyTypeIsSigned(type) && (raw >> (8 * size - 1)) != 0)
    {
      value = static_cast<double>(raw) - std::ldexp(1.0, 8 * size);
    }
    else
    {
      value = static_cast<double>(raw);
    }
    return true;
  }

  std::vector<PlyElement> Elements;
  const std::string* Data = nullptr;
  std::size_t Cursor = 0;
  std::uint64_t VertexCount = 0;
  bool Ascii = false;
  bool BigEndian = false;
};

/**
 * vtkOBJReader reads a vertex coordinate it cannot parse ("nan", "1.0.0") as 0
 * without a word, so vertex lines are checked here. Returns the problem or "".
 */
std::string CheckOBJVertices(const std::string& contents)
{
  std::istringstream lines(contents);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number)
  {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword != "v")
    {
      continue;
    }
    std::string token;
    for (int c = 0; c < 3; ++c)
    {
      if (!(words >> token))
      {
        return "line " + std::to_string(number) + ": a vertex needs x, y and z";
      }
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (!end || *end != '\0' || !std::isfinite(value))
      {
        return "line " + std::to_string(number) + ": vertex coordinate '" + token +
          "' is not a finite number";
      }
    }
  }
  return std::string();
}

/**
 * A binary STL is an 80-byte header, a 32-bit triangle count and 50 bytes per
 * triangle. vtkSTLReader reads what is there, so a short file would silently lose
 * triangles. Returns the problem or "".
 */
std::string CheckBinarySTL(const std::string& contents)
{
  if (contents.size() < 84)
  {
    return "binary STL shorter than its 84-byte header";
  }
  std::uint32_t count = 0;
  for (int i = 3; i >= 0; --i)
  {
    count = (count << 8) | static_cast<unsigned char>(contents[80 + i]);
  }
  const std::uint64_t expected = 84 + 50 * static_cast<std::uint64_t>(count);
  if (contents.size() < expected)
  {
    return "binary STL declares " + std::to_string(count) + " triangles but holds only " +
      std::to_string((contents.size() - 84) / 50) + " (truncated?)";
  }
  return std::string();
}

/** The container problem VTK's reader would crash on or silently lose data over, or "". */
std::string ContainerProblem(
  const std::string& path, const std::string& extension, const std::string& contents)
{
  if (extension == ".ply")
  {
    return PlyChecker().Check(contents);
  }
  if (extension == ".obj")
  {
    return CheckOBJVertices(contents);
  }
  if (extension == ".stl" &&
    vtksys::SystemTools::DetectFileType(path.c_str()) != vtksys::SystemTools::FileTypeText)
  {
    // Same test as vtkSTLReader uses to pick binary over ASCII.
    return CheckBinarySTL(contents);
  }
  return std::string();
}

/** VTK's reader for the extension (.ply, .obj, else .stl), set to read path. */
vtkSmartPointer<vtkPolyDataAlgorithm> NewVTKReader(
  const std::string& path, const std::string& extension)
{
  if (extension == ".ply")
  {
    auto ply = vtkSmartPointer<vtkPLYReader>::New();
    ply->SetFileName(path.c_str());
    return ply;
  }
  if (extension == ".obj")
  {
    auto obj = vtkSmartPointer<vtkOBJReader>::New();
    obj->SetFileName(path.c_str());
    return obj;
  }
  auto stl = vtkSmartPointer<vtkSTLReader>::New();
  stl->SetFileName(path.c_str());
  return stl;
}

/**
 * Counts the polygons and strips with at least three vertices: usable ones (all
 * vertices finite) and those with a NaN/Inf vertex. Returns the first vertex index
 * out of range as a problem, or "".
 */
std::string CountFaces(vtkPolyData* mesh, vtkIdType& usable, vtkIdType& withNonFinite)
{
  const vtkIdType numPoints = mesh->GetNumberOfPoints();
  usable = withNonFinite = 0;
  for (vtkCellArray* cells : { mesh->GetPolys(), mesh->GetStrips() })
  {
    vtkIdType npts = 0;
    const vtkIdType* ids = nullptr;
    vtkIdType cellIndex = 0;
    for (cells->InitTraversal(); cells->GetNextCell(npts, ids); ++cellIndex)
    {
      bool finite = npts >= 3;
      for (vtkIdType k = 0; k < npts; ++k)
      {
        if (ids[k] < 0 || ids[k] >= numPoints)
        {
          return "face " + std::to_string(cellIndex) + " refers to vertex " +
            std::to_string(ids[k] + 1) + " (1-based), but the file has " +
            std::to_string(numPoints) + " vertices";
        }
        double p[3];
        mesh->GetPoint(ids[k], p);
        finite = finite && std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
      }
      usable += finite ? 1 : 0;
      withNonFinite += finite || npts < 3 ? 0 : 1;
    }
  }
  return std::string();
}
}

vtkCausticsMeshReader::vtkCausticsMeshReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkCausticsMeshReader::~vtkCausticsMeshReader()
{
  this->SetFileName(nullptr);
}

bool vtkCausticsMeshReader::IsSupportedExtension(const std::string& fileName)
{
  const std::string extension = LowerExtension(fileName);
  return extension == ".ply" || extension == ".obj" || extension == ".stl";
}

bool vtkCausticsMeshReader::SetRoleFromName(const char* name)
{
  const std::string role = name ? name : "";
  if (role == "none")
  {
    this->SetRole(vtkCausticsMaterial::ROLE_NONE);
  }
  else if (role == "receiver")
  {
    this->SetRole(vtkCausticsMaterial::ROLE_RECEIVER);
  }
  else if (role == "reflector" || role == "mirror")
  {
    this->SetRole(vtkCausticsMaterial::ROLE_REFLECTOR);
  }
  else if (role == "refractor" || role == "glass")
  {
    this->SetRole(vtkCausticsMaterial::ROLE_REFRACTOR);
  }
  else
  {
    this->Fail("unknown role '" + role +
      "' (known: none, receiver, reflector or mirror, refractor or glass)");
    return false;
  }
  return true;
}

int vtkCausticsMeshReader::Fail(const std::string& message)
{
  this->LastError = message;
  vtkErrorMacro(<< message);
  return 0;
}

int vtkCausticsMeshReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  this->LastError.clear();
  this->ReadError.clear();
  vtkPolyData* output = vtkPolyData::GetData(outputVector);

  // 1. The file and its extension.
  if (!this->FileName || !*this->FileName)
  {
    return this->ReadFail("no mesh file name given");
  }
  const std::string path = this->FileName;
  std::string contents;
  if (!this->ReadFile(path, contents))
  {
    return 0;
  }
  // 2. The container, where VTK's reader would crash or silently lose data.
  const std::string problem = ContainerProblem(path, LowerExtension(path), contents);
  if (!problem.empty())
  {
    return this->ReadFail(path + ": " + problem);
  }
  // 3. VTK's reader; its complaints become this reader's error.
  vtkSmartPointer<vtkPolyDataAlgorithm> reader = this->RunVTKReader(path);
  // 4. The geometry.
  if (!reader || !this->CheckGeometry(path, reader->GetOutput()))
  {
    return 0;
  }
  output->ShallowCopy(reader->GetOutput());
  return 1;
}

int vtkCausticsMeshReader::ReadFail(const std::string& message)
{
  this->ReadError = message;
  return this->Fail(message);
}

int vtkCausticsMeshReader::ReadFile(const std::string& path, std::string& contents)
{
  if (!vtksys::SystemTools::FileExists(path))
  {
    return this->ReadFail(path + ": no such file");
  }
  if (vtksys::SystemTools::FileIsDirectory(path))
  {
    return this->ReadFail(path + ": is a folder, not a mesh file");
  }
  const std::string extension = LowerExtension(path);
  if (!IsSupportedExtension(path))
  {
    return this->ReadFail(
      path + ": unknown mesh extension '" + extension + "' (supported: .ply, .obj, .stl)");
  }
  if (!ReadWholeFile(path, contents))
  {
    return this->ReadFail(path + ": cannot be read (permissions?)");
  }
  if (contents.empty())
  {
    return this->ReadFail(path + ": the file is empty, no triangles");
  }
  return 1;
}

vtkSmartPointer<vtkPolyDataAlgorithm> vtkCausticsMeshReader::RunVTKReader(const std::string& path)
{
  vtkSmartPointer<vtkPolyDataAlgorithm> reader = NewVTKReader(path, LowerExtension(path));
  ReaderMessages messages;
  vtkNew<vtkCallbackCommand> collect;
  collect->SetCallback(CollectMessages);
  collect->SetClientData(&messages);
  reader->AddObserver(vtkCommand::ErrorEvent, collect);
  reader->AddObserver(vtkCommand::WarningEvent, collect);
  reader->Update();
  if (!messages.Errors.empty())
  {
    this->ReadFail(path + ": VTK's " + reader->GetClassName() + " failed: " + messages.Errors[0]);
    return nullptr;
  }
  for (const std::string& warning : messages.Warnings)
  {
    vtkWarningMacro(<< path << ": VTK's " << reader->GetClassName() << ": " << warning);
  }
  return reader;
}

int vtkCausticsMeshReader::CheckGeometry(const std::string& path, vtkPolyData* mesh)
{
  vtkIdType usable = 0, withNonFinite = 0;
  const std::string problem = CountFaces(mesh, usable, withNonFinite);
  if (!problem.empty())
  {
    return this->ReadFail(path + ": " + problem);
  }
  if (usable == 0)
  {
    return this->ReadFail(path + ": no triangles with finite vertices (" +
      std::to_string(mesh->GetNumberOfPoints()) + " vertices, " +
      std::to_string(mesh->GetNumberOfPolys() + mesh->GetNumberOfStrips()) + " faces)");
  }
  if (withNonFinite > 0)
  {
    vtkWarningMacro(<< path << ": " << withNonFinite
                    << " face(s) have NaN/Inf vertices; caustics will drop them");
  }
  return 1;
}

vtkSmartPointer<vtkActor> vtkCausticsMeshReader::CreateActor()
{
  const int role = this->Role;
  if (role < vtkCausticsMaterial::ROLE_NONE || role > vtkCausticsMaterial::ROLE_REFRACTOR)
  {
    this->Fail("role " + std::to_string(role) +
      " is not one of 0 (none), 1 (receiver), 2 (reflector), 3 (refractor)");
    return nullptr;
  }
  if (!(std::isfinite(this->RefractiveIndex) && this->RefractiveIndex >= 1.0))
  {
    this->Fail(
      "refractive index " + std::to_string(this->RefractiveIndex) + " must be finite and >= 1");
    return nullptr;
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!(this->Color[c] >= 0.0 && this->Color[c] <= 1.0))
    {
      this->Fail("colour component " + std::to_string(this->Color[c]) + " is outside [0, 1]");
      return nullptr;
    }
  }
  // Update() re-reads only when the file name changed; ReadError keeps the
  // outcome of the last read.
  this->Update();
  if (!this->ReadError.empty())
  {
    this->LastError = this->ReadError;
    return nullptr;
  }
  this->LastError.clear();

  auto polyData = vtkSmartPointer<vtkPolyData>::New();
  polyData->ShallowCopy(this->GetOutput());
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(polyData);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  vtkCausticsMaterial::SetName(actor, vtksys::SystemTools::GetFilenameName(this->FileName));

  // The property says what the role means, so VTK draws it alike and the
  // classification agrees; the explicit role makes the choice independent of
  // vtkCausticsSceneExtractor's roughness cut-off.
  vtkProperty* property = actor->GetProperty();
  property->SetColor(this->Color);
  switch (role)
  {
    case vtkCausticsMaterial::ROLE_REFLECTOR:
    {
      // Polished conductor; complex IOR from F0 = Color (vtkCausticsMaterial rule 3).
      property->SetInterpolationToPBR();
      property->SetMetallic(1.0);
      property->SetRoughness(0.0);
      break;
    }
    case vtkCausticsMaterial::ROLE_REFRACTOR:
      vtkCausticsMaterial::MakeGlass(property, this->RefractiveIndex);
      break;
    default:
      property->SetDiffuse(1.0);
      property->SetAmbient(0.0);
      property->SetSpecular(0.0);
      break;
  }
  vtkCausticsMaterial::SetRole(actor, role);
  return actor;
}

void vtkCausticsMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Role: " << vtkCausticsMaterial::GetRoleName(this->Role) << " (" << this->Role
     << ")\n";
  os << indent << "RefractiveIndex: " << this->RefractiveIndex << "\n";
  os << indent << "Color: " << this->Color[0] << ", " << this->Color[1] << ", " << this->Color[2]
     << "\n";
  os << indent << "LastError: " << (this->LastError.empty() ? "(none)" : this->LastError) << "\n";
}
