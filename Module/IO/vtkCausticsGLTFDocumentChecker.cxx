#include "vtkCausticsGLTFDocumentChecker.h"

#include "vtkCausticsFileText.h"
#include "vtkCausticsGLTFImporter.h"

#include "vtkMath.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <vector>

namespace caustics
{
namespace gltf
{
namespace
{
/** Extensions this importer reads, on top of those VTK's loader reads. */
const char* const OwnExtensions[] = { "KHR_materials_ior", "KHR_materials_transmission",
  "KHR_materials_volume" };
/** Extensions a file may list in extensionsRequired. */
const char* const SupportedExtensions[] = { "KHR_lights_punctual", "KHR_materials_unlit",
  "KHR_materials_ior", "KHR_materials_transmission", "KHR_materials_volume" };

const double Pi = vtkMath::Pi();
const double NaN = std::numeric_limits<double>::quiet_NaN();
/** Upper bound of "any finite number" (VTK_DOUBLE_MAX is only 1e299). */
const double Huge = std::numeric_limits<double>::max();
const double MaxIOR = vtkCausticsGLTFImporter::MAX_IOR;
const double MaxLightIntensity = vtkCausticsGLTFImporter::MAX_LIGHT_INTENSITY;
const double MinAttenuationDistance = vtkCausticsGLTFImporter::MIN_ATTENUATION_DISTANCE;
const int MaxNodeDepth = vtkCausticsGLTFImporter::MAX_NODE_DEPTH;

using caustics::text::Printable;
using caustics::text::ReasonLength;

/** Text from the file in quotes, short and printable (vtkCausticsFileText.h). */
std::string Quoted(const std::string& text)
{
  return caustics::text::Quote(text);
}

/**
 * The JSON path of member `name` of `path`: "path.name", or "path['...']" (quoted,
 * short, printable) when the name is not a plain identifier.
 */
std::string MemberPath(const std::string& path, const std::string& name)
{
  const bool plain = !name.empty() && name.size() <= caustics::text::QuoteLength &&
    std::all_of(name.begin(), name.end(),
      [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
  if (!plain)
  {
    return path + "[" + Quoted(name) + "]";
  }
  return path.empty() ? name : path + "." + name;
}

std::string Plural(std::size_t count, const char* noun)
{
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

std::string Entries(std::size_t count)
{
  return std::to_string(count) + (count == 1 ? " entry" : " entries");
}

/** A checked range in words: "in [0, 1]", "> 0", ">= 0.1", "in (0, 1.5708]" or "finite". */
std::string Range(double low, double high)
{
  // VTK_DBL_MIN as a lower bound stands for "strictly positive".
  const bool positive = low == VTK_DBL_MIN;
  std::ostringstream range;
  if (high == Huge && low == -Huge)
  {
    range << "finite";
  }
  else if (high == Huge)
  {
    range << (positive ? "> 0" : ">= ");
    if (!positive)
    {
      range << low;
    }
  }
  else
  {
    range << "in ";
    if (positive)
    {
      range << "(0";
    }
    else
    {
      range << "[" << low;
    }
    range << ", " << high << "]";
  }
  return range.str();
}

std::uint32_t LittleEndian32(const std::string& bytes, std::size_t offset)
{
  std::uint32_t value = 0;
  for (int i = 3; i >= 0; --i)
  {
    value = (value << 8) | static_cast<unsigned char>(bytes[offset + i]);
  }
  return value;
}

/**
 * The JSON and BIN chunks of a binary glTF (.glb): a 12-byte header (magic
 * "glTF", version, length) followed by length-prefixed chunks, the first one
 * JSON. Returns the problem or "". The whole chain of chunks is walked as VTK
 * 9.1's loader walks it (chunk by chunk by their lengths, taking the first BIN
 * chunk), so it must be exact: the header's length is the file's, every chunk
 * header is whole, and every chunk lies inside the file and is a multiple of 4
 * bytes long (as glTF requires). VTK's walk looped for ever on a partial chunk
 * header at the end of the file, growing its list of chunks.
 */
std::string SplitGLB(const std::string& contents, std::string& json, std::size_t& binSize)
{
  binSize = 0;
  if (contents.size() < 20)
  {
    return "binary glTF shorter than its 20-byte header";
  }
  const std::uint32_t version = LittleEndian32(contents, 4);
  if (version != 2)
  {
    return "binary glTF container version " + std::to_string(version) +
      "; only glTF 2.x is supported";
  }
  if (LittleEndian32(contents, 8) != contents.size())
  {
    return "binary glTF header declares " + std::to_string(LittleEndian32(contents, 8)) +
      " bytes but the file has " + std::to_string(contents.size()) +
      (LittleEndian32(contents, 8) > contents.size() ? " (truncated?)" : "");
  }
  bool haveBin = false;
  for (std::uint64_t offset = 12; offset < contents.size();)
  {
    const std::string at = " at byte " + std::to_string(offset);
    if (offset + 8 > contents.size())
    {
      return "the binary glTF ends inside a chunk header" + at + " (truncated?)";
    }
    const std::uint64_t length = LittleEndian32(contents, offset);
    const std::uint32_t type = LittleEndian32(contents, offset + 4);
    const bool isJSON = type == 0x4E4F534Au; // "JSON"
    const bool isBin = type == 0x004E4942u;  // "BIN\0"
    const std::string name = isJSON ? "JSON chunk" : isBin ? "BIN chunk" : "chunk" + at;
    if (offset == 12 && !isJSON)
    {
      return "the first chunk of the binary glTF is not JSON";
    }
    if (offset + 8 + length > contents.size())
    {
      return "the " + name + " runs past the end of the file (truncated?)";
    }
    if (length % 4 != 0)
    {
      return "the " + name + " is " + std::to_string(length) +
        " bytes long, not a multiple of 4 as glTF requires";
    }
    if (offset == 12)
    {
      json = contents.substr(20, length);
    }
    else if (isBin && !haveBin)
    {
      binSize = static_cast<std::size_t>(length);
      haveBin = true;
    }
    offset += 8 + length;
  }
  return std::string();
}

/** Bytes held by a base64 payload from `begin`; -1 when it has non-base64 characters. */
long long Base64Size(const std::string& text, std::size_t begin)
{
  long long symbols = 0;
  bool padding = false;
  for (std::size_t i = begin; i < text.size(); ++i)
  {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (std::isalnum(c) || c == '+' || c == '/')
    {
      if (padding)
      {
        return -1;
      }
      ++symbols;
    }
    else if (c == '=')
    {
      padding = true;
    }
    else
    {
      return -1;
    }
  }
  return symbols * 3 / 4;
}

/** jsoncpp's "* Line 3, Column 5\n  Missing ','..." as "line 3, column 5: Missing ','...". */
std::string OneLine(const std::string& jsoncppErrors)
{
  std::istringstream lines(jsoncppErrors);
  std::string where, what;
  std::getline(lines, where);
  std::getline(lines, what);
  auto trim = [](std::string text)
  {
    const std::size_t first = text.find_first_not_of("* \t");
    const std::size_t last = text.find_last_not_of(" \t\r");
    return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
  };
  return Printable(vtksys::SystemTools::LowerCase(trim(where)) + ": " + trim(what), ReasonLength);
}

/** The first number that is NaN or infinite, as a JSON path; false when there is none. */
bool FindNonFinite(const Json::Value& value, const std::string& path, std::string& where)
{
  if (value.type() == Json::realValue && !std::isfinite(value.asDouble()))
  {
    where = path;
    return true;
  }
  if (value.isArray())
  {
    for (Json::ArrayIndex i = 0; i < value.size(); ++i)
    {
      if (FindNonFinite(value[i], path + "[" + std::to_string(i) + "]", where))
      {
        return true;
      }
    }
  }
  else if (value.isObject())
  {
    for (const std::string& name : value.getMemberNames())
    {
      if (FindNonFinite(value[name], MemberPath(path, name), where))
      {
        return true;
      }
    }
  }
  return false;
}

int ComponentSize(int componentType)
{
  switch (componentType)
  {
    case 5120: // BYTE
    case 5121: // UNSIGNED_BYTE
      return 1;
    case 5122: // SHORT
    case 5123: // UNSIGNED_SHORT
      return 2;
    case 5125: // UNSIGNED_INT
    case 5126: // FLOAT
      return 4;
    default:
      return 0;
  }
}

int ComponentCount(const std::string& type)
{
  static const std::map<std::string, int> counts = { { "SCALAR", 1 }, { "VEC2", 2 }, { "VEC3", 3 },
    { "VEC4", 4 }, { "MAT2", 4 }, { "MAT3", 9 }, { "MAT4", 16 } };
  const auto it = counts.find(type);
  return it == counts.end() ? 0 : it->second;
}

/** Whether `name` is `prefix` followed by a set index ("TEXCOORD_0"). */
bool IsIndexed(const std::string& name, const char* prefix)
{
  const std::size_t length = std::strlen(prefix);
  return name.size() > length && name.compare(0, length, prefix) == 0 &&
    std::all_of(name.begin() + length, name.end(),
      [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
}

/**
 * The accessor types glTF 2.0 allows for vertex attribute `name` (3.7.2.1), in
 * words, or "" when `accessor` has one of them or the name is not one glTF
 * defines (application-specific "_NAME"s). VTK 9.1's loader leaves an attribute
 * of another type empty, and the scene extractor read past an empty NORMAL array
 * (found by fuzzing). Morph targets (`target`) hold VEC3 FLOAT displacements.
 */
std::string AttributeTypeProblem(const std::string& name, const Json::Value& accessor, bool target)
{
  const std::string type = accessor["type"].asString();
  const int component = accessor["componentType"].asInt();
  const bool normalized = accessor.get("normalized", false).asBool();
  const bool floats = component == 5126;
  const bool unorm = normalized && (component == 5121 || component == 5123);
  const bool unsignedInt = !normalized && (component == 5121 || component == 5123);
  if (name == "POSITION" || name == "NORMAL" || (target && name == "TANGENT"))
  {
    return type == "VEC3" && floats ? "" : "a VEC3 FLOAT accessor";
  }
  if (name == "TANGENT")
  {
    return type == "VEC4" && floats ? "" : "a VEC4 FLOAT accessor";
  }
  if (IsIndexed(name, "TEXCOORD_"))
  {
    return type == "VEC2" && (floats || unorm)
      ? ""
      : "a VEC2 accessor of FLOAT or normalized UNSIGNED_BYTE/SHORT";
  }
  if (IsIndexed(name, "COLOR_"))
  {
    return (type == "VEC3" || type == "VEC4") && (floats || unorm)
      ? ""
      : "a VEC3 or VEC4 accessor of FLOAT or normalized UNSIGNED_BYTE/SHORT";
  }
  if (IsIndexed(name, "JOINTS_"))
  {
    return type == "VEC4" && unsignedInt ? "" : "a VEC4 UNSIGNED_BYTE/SHORT accessor";
  }
  if (IsIndexed(name, "WEIGHTS_"))
  {
    return type == "VEC4" && (floats || unorm)
      ? ""
      : "a VEC4 accessor of FLOAT or normalized UNSIGNED_BYTE/SHORT";
  }
  return std::string();
}

/**
 * Structural and physical checks of a parsed glTF document; the first problem
 * found is kept. Paths in messages are JSON paths ("meshes[0].primitives[1].material").
 */
class DocumentChecker
{
public:
  DocumentChecker(
    const Json::Value& root, const std::string& folder, bool binary, std::size_t binSize)
    : Root(root)
    , Folder(folder)
    , Binary(binary)
    , BinSize(binSize)
  {
  }

  /** Returns the first problem, or "" for a document VTK's loader can take. */
  std::string Check()
  {
    // Members are checked in dependency order so that later checks can index
    // what earlier ones validated.
    this->CheckTopLevel() && this->CheckAsset() && this->CheckExtensions() &&
      this->CheckBuffers() && this->CheckBufferViews() && this->CheckAccessors() &&
      this->CheckImagesAndTextures() && this->CheckMaterials() && this->CheckMeshes() &&
      this->CheckCameras() && this->CheckLights() && this->CheckNodes() && this->CheckScenes() &&
      this->CheckSkinsAndAnimations();
    return this->Problem;
  }

private:
  bool Fail(const std::string& problem)
  {
    if (this->Problem.empty())
    {
      this->Problem = problem;
    }
    return false;
  }

  std::size_t Count(const std::string& array) const
  {
    const auto it = this->Counts.find(array);
    return it == this->Counts.end() ? 0 : it->second;
  }

  static std::string Member(const std::string& path, const char* key)
  {
    return path.empty() ? std::string(key) : path + "." + key;
  }

  /** An index into `array` (a top-level array name, or "lights"). */
  bool IndexValue(const Json::Value& value, const std::string& path, const std::string& array)
  {
    if (!value.isInt64() || value.asInt64() < 0)
    {
      return this->Fail(path + " must be a non-negative integer index into " + Quoted(array));
    }
    const std::size_t count = this->Count(array);
    if (static_cast<std::uint64_t>(value.asInt64()) >= count)
    {
      return this->Fail(path + " = " + std::to_string(value.asInt64()) +
        " is out of range: " + Quoted(array) + " has " + Entries(count));
    }
    return true;
  }

  bool Index(const Json::Value& object, const char* key, const std::string& path,
    const std::string& array, bool required = false)
  {
    if (!object.isMember(key))
    {
      return required ? this->Fail(Member(path, key) + " is missing") : true;
    }
    return this->IndexValue(object[key], Member(path, key), array);
  }

  bool Integer(const Json::Value& object, const char* key, const std::string& path, long long low,
    long long high, bool required = false)
  {
    if (!object.isMember(key))
    {
      return required ? this->Fail(Member(path, key) + " is missing") : true;
    }
    const Json::Value& value = object[key];
    if (!value.isInt64() || value.asInt64() < low || value.asInt64() > high)
    {
      return this->Fail(Member(path, key) + " must be an integer in [" + std::to_string(low) +
        ", " + std::to_string(high) + "]");
    }
    return true;
  }

  /** A number in [low, high]. */
  bool Number(const Json::Value& object, const char* key, const std::string& path, double low,
    double high, bool required = false)
  {
    if (!object.isMember(key))
    {
      return required ? this->Fail(Member(path, key) + " is missing") : true;
    }
    const Json::Value& value = object[key];
    if (!value.isNumeric())
    {
      return this->Fail(Member(path, key) + " must be a number");
    }
    if (!(value.asDouble() >= low && value.asDouble() <= high))
    {
      std::ostringstream message;
      message << Member(path, key) << " = " << value.asDouble() << ", but it must be "
              << Range(low, high);
      return this->Fail(message.str());
    }
    return true;
  }

  /** An array of `size` numbers in [low, high]. */
  bool Numbers(const Json::Value& object, const char* key, const std::string& path,
    Json::ArrayIndex size, double low, double high)
  {
    if (!object.isMember(key))
    {
      return true;
    }
    const Json::Value& value = object[key];
    bool ok = value.isArray() && value.size() == size;
    for (Json::ArrayIndex i = 0; ok && i < size; ++i)
    {
      ok = value[i].isNumeric() && value[i].asDouble() >= low && value[i].asDouble() <= high;
    }
    if (!ok)
    {
      return this->Fail(
        Member(path, key) + " must be " + std::to_string(size) + " numbers, " + Range(low, high));
    }
    return true;
  }

  bool IsObjectOrAbsent(const Json::Value& object, const char* key, const std::string& path)
  {
    if (object.isMember(key) && !object[key].isObject())
    {
      return this->Fail(Member(path, key) + " must be a JSON object");
    }
    return true;
  }

  bool CheckTopLevel()
  {
    if (!this->Root.isObject())
    {
      return this->Fail("the top level of the JSON is not an object");
    }
    static const char* const arrays[] = { "accessors", "animations", "buffers", "bufferViews",
      "cameras", "images", "materials", "meshes", "nodes", "samplers", "scenes", "skins",
      "textures" };
    for (const char* name : arrays)
    {
      if (!this->Root.isMember(name))
      {
        continue;
      }
      const Json::Value& array = this->Root[name];
      if (!array.isArray())
      {
        return this->Fail(std::string(name) + " must be a JSON array");
      }
      for (Json::ArrayIndex i = 0; i < array.size(); ++i)
      {
        const std::string path = std::string(name) + "[" + std::to_string(i) + "]";
        if (!array[i].isObject())
        {
          return this->Fail(path + " must be a JSON object");
        }
        if (array[i].isMember("name") && !array[i]["name"].isString())
        {
          return this->Fail(path + ".name must be a string");
        }
      }
      this->Counts[name] = array.size();
    }
    std::string where;
    if (FindNonFinite(this->Root, "", where))
    {
      // The path of a number nested 1000 levels deep would be 3000 bytes long.
      return this->Fail(
        Printable(where, ReasonLength) + " is not a finite number (NaN or infinity)");
    }
    return this->IsObjectOrAbsent(this->Root, "extensions", "");
  }

  bool CheckAsset()
  {
    const Json::Value& asset = this->Root["asset"];
    if (!asset.isObject() || !asset["version"].isString())
    {
      return this->Fail("asset.version is missing: not a glTF 2.0 file");
    }
    const std::string version = asset["version"].asString();
    if (version.compare(0, 2, "2.") != 0)
    {
      return this->Fail("asset.version is " + Quoted(version) + "; only glTF 2.x is supported");
    }
    if (asset.isMember("minVersion") &&
      (!asset["minVersion"].isString() || asset["minVersion"].asString() != "2.0"))
    {
      return this->Fail("asset.minVersion is " +
        (asset["minVersion"].isString() ? Quoted(asset["minVersion"].asString()) : "not a string") +
        "; only glTF 2.0 features are supported");
    }
    return true;
  }

  bool CheckExtensions()
  {
    const Json::Value& required = this->Root["extensionsRequired"];
    for (Json::ArrayIndex i = 0; required.isArray() && i < required.size(); ++i)
    {
      const std::string name = required[i].isString() ? required[i].asString() : "?";
      if (std::find(std::begin(SupportedExtensions), std::end(SupportedExtensions), name) ==
        std::end(SupportedExtensions))
      {
        return this->Fail(
          "the file requires extension " + Quoted(name) + ", which is not supported");
      }
    }
    return true;
  }

  bool CheckBuffers()
  {
    const Json::Value& buffers = this->Root["buffers"];
    for (Json::ArrayIndex i = 0; i < this->Count("buffers"); ++i)
    {
      const std::string path = "buffers[" + std::to_string(i) + "]";
      const Json::Value& buffer = buffers[i];
      if (!this->Integer(buffer, "byteLength", path, 1, INT32_MAX, true))
      {
        return false;
      }
      const std::uint64_t length = buffer["byteLength"].asUInt64();
      this->BufferLengths.push_back(length);
      if (!buffer.isMember("uri"))
      {
        if (!this->Binary || i != 0)
        {
          return this->Fail(path + " has no uri (only the first buffer of a .glb may omit it)");
        }
        if (this->BinSize < length)
        {
          return this->Fail(path + ".byteLength is " + std::to_string(length) +
            " but the .glb BIN chunk holds " + std::to_string(this->BinSize) + " bytes");
        }
        continue;
      }
      if (!this->CheckURI(buffer["uri"], path + ".uri", length))
      {
        return false;
      }
    }
    return true;
  }

  /** A data URI or a file next to the glTF holding at least `length` bytes (0: any). */
  bool CheckURI(const Json::Value& value, const std::string& path, std::uint64_t length)
  {
    if (!value.isString())
    {
      return this->Fail(path + " must be a string");
    }
    const std::string uri = value.asString();
    std::uint64_t available = 0;
    if (uri.compare(0, 5, "data:") == 0)
    {
      const std::size_t marker = uri.find(";base64,");
      if (marker == std::string::npos)
      {
        return this->Fail(path + " is a data URI without ';base64,' (only base64 is supported)");
      }
      const long long size = Base64Size(uri, marker + 8);
      if (size < 0)
      {
        return this->Fail(path + " holds characters that are not base64");
      }
      available = static_cast<std::uint64_t>(size);
    }
    else
    {
      const std::string file = vtksys::SystemTools::CollapseFullPath(uri, this->Folder);
      if (!vtksys::SystemTools::FileExists(file, true))
      {
        return this->Fail(path + " " + Quoted(uri) + " not found (looked for " +
          Printable(file, ReasonLength) + ")");
      }
      available = vtksys::SystemTools::FileLength(file);
    }
    if (available < length)
    {
      return this->Fail(path + " holds " + std::to_string(available) + " bytes but byteLength is " +
        std::to_string(length));
    }
    return true;
  }

  bool CheckBufferViews()
  {
    const Json::Value& views = this->Root["bufferViews"];
    for (Json::ArrayIndex i = 0; i < this->Count("bufferViews"); ++i)
    {
      const std::string path = "bufferViews[" + std::to_string(i) + "]";
      const Json::Value& view = views[i];
      if (!this->Index(view, "buffer", path, "buffers", true) ||
        !this->Integer(view, "byteLength", path, 1, INT32_MAX, true) ||
        !this->Integer(view, "byteOffset", path, 0, INT32_MAX) ||
        !this->Integer(view, "byteStride", path, 4, 252))
      {
        return false;
      }
      const std::uint64_t end =
        view.get("byteOffset", 0).asUInt64() + view["byteLength"].asUInt64();
      const std::uint64_t available = this->BufferLengths[view["buffer"].asUInt()];
      if (end > available)
      {
        return this->Fail(path + " ends at byte " + std::to_string(end) + " but buffers[" +
          std::to_string(view["buffer"].asUInt()) + "] has " + std::to_string(available));
      }
    }
    return true;
  }

  bool CheckAccessors()
  {
    const Json::Value& accessors = this->Root["accessors"];
    const Json::Value& views = this->Root["bufferViews"];
    for (Json::ArrayIndex i = 0; i < this->Count("accessors"); ++i)
    {
      const std::string path = "accessors[" + std::to_string(i) + "]";
      const Json::Value& accessor = accessors[i];
      if (!this->Index(accessor, "bufferView", path, "bufferViews") ||
        !this->Integer(accessor, "byteOffset", path, 0, INT32_MAX) ||
        !this->Integer(accessor, "count", path, 1, INT32_MAX, true))
      {
        return false;
      }
      const int componentSize =
        accessor["componentType"].isInt() ? ComponentSize(accessor["componentType"].asInt()) : 0;
      const int components =
        accessor["type"].isString() ? ComponentCount(accessor["type"].asString()) : 0;
      if (componentSize == 0)
      {
        return this->Fail(path + ".componentType is missing or not a glTF component type");
      }
      if (accessor.isMember("normalized") && !accessor["normalized"].isBool())
      {
        return this->Fail(path + ".normalized must be true or false");
      }
      // VTK 9.1's loader reads one bound per component (a short max array threw
      // std::length_error from inside it; found by fuzzing).
      if (!this->Numbers(accessor, "min", path, components, -Huge, Huge) ||
        !this->Numbers(accessor, "max", path, components, -Huge, Huge))
      {
        return false;
      }
      if (components == 0)
      {
        return this->Fail(path + ".type is missing or not one of SCALAR, VEC2-4, MAT2-4");
      }
      if (accessor.isMember("sparse"))
      {
        // VTK 9.1's loader drops an accessor whose sparse byteOffsets are absent (they
        // are optional, default 0), which shifts every later accessor index: a
        // primitive then reads a wrong or missing accessor (std::bad_array_new_length).
        // It also never sizes the array of a sparse accessor without a bufferView
        // before writing into it, nor bounds the sparse indices. Refused until the
        // importer densifies sparse accessors itself.
        return this->Fail(path +
          ".sparse: sparse accessors are not supported (store the "
          "accessor's values densely in a bufferView)");
      }
      if (!accessor.isMember("bufferView"))
      {
        // glTF reads such an accessor as zeros; VTK 9.1's loader dereferences the
        // missing view instead (SIGSEGV in ExtractPrimitiveAccessorData, found by
        // fuzzing).
        return this->Fail(path + " has no bufferView: accessors of zeros are not supported");
      }
      const Json::Value& view = views[accessor["bufferView"].asUInt()];
      const std::uint64_t element = static_cast<std::uint64_t>(componentSize) * components;
      const std::uint64_t stride =
        view.get("byteStride", 0).asUInt64() > 0 ? view["byteStride"].asUInt64() : element;
      const std::uint64_t end = accessor.get("byteOffset", 0).asUInt64() +
        stride * (accessor["count"].asUInt64() - 1) + element;
      if (end > view["byteLength"].asUInt64())
      {
        return this->Fail(path + " reads " + std::to_string(end) + " bytes but bufferViews[" +
          std::to_string(accessor["bufferView"].asUInt()) + "] has " +
          std::to_string(view["byteLength"].asUInt64()));
      }
    }
    return true;
  }

  bool CheckImagesAndTextures()
  {
    const Json::Value& images = this->Root["images"];
    for (Json::ArrayIndex i = 0; i < this->Count("images"); ++i)
    {
      const std::string path = "images[" + std::to_string(i) + "]";
      if (images[i].isMember("uri") && !this->CheckURI(images[i]["uri"], path + ".uri", 0))
      {
        return false;
      }
      if (!this->Index(images[i], "bufferView", path, "bufferViews"))
      {
        return false;
      }
      if (!images[i].isMember("uri") && !images[i].isMember("bufferView"))
      {
        return this->Fail(path + " has neither uri nor bufferView");
      }
    }
    const Json::Value& textures = this->Root["textures"];
    for (Json::ArrayIndex i = 0; i < this->Count("textures"); ++i)
    {
      const std::string path = "textures[" + std::to_string(i) + "]";
      if (!this->Index(textures[i], "source", path, "images") ||
        !this->Index(textures[i], "sampler", path, "samplers"))
      {
        return false;
      }
    }
    return true;
  }

  bool CheckTextureInfo(const Json::Value& object, const char* key, const std::string& path)
  {
    if (!object.isMember(key))
    {
      return true;
    }
    return this->IsObjectOrAbsent(object, key, path) &&
      this->Index(object[key], "index", Member(path, key), "textures", true);
  }

  bool CheckMaterials()
  {
    const Json::Value& materials = this->Root["materials"];
    for (Json::ArrayIndex i = 0; i < this->Count("materials"); ++i)
    {
      const std::string path = "materials[" + std::to_string(i) + "]";
      if (!this->CheckMaterial(materials[i], path) ||
        !this->CheckMaterialExtensions(materials[i], path))
      {
        return false;
      }
    }
    return true;
  }

  /** A material's core members: factors in range, texture references, alpha mode. */
  bool CheckMaterial(const Json::Value& material, const std::string& path)
  {
    if (!this->IsObjectOrAbsent(material, "pbrMetallicRoughness", path) ||
      !this->IsObjectOrAbsent(material, "extensions", path))
    {
      return false;
    }
    const Json::Value& pbr = material["pbrMetallicRoughness"];
    const std::string pbrPath = Member(path, "pbrMetallicRoughness");
    if (!this->Numbers(pbr, "baseColorFactor", pbrPath, 4, 0.0, 1.0) ||
      !this->Number(pbr, "metallicFactor", pbrPath, 0.0, 1.0) ||
      !this->Number(pbr, "roughnessFactor", pbrPath, 0.0, 1.0) ||
      !this->CheckTextureInfo(pbr, "baseColorTexture", pbrPath) ||
      !this->CheckTextureInfo(pbr, "metallicRoughnessTexture", pbrPath) ||
      !this->CheckTextureInfo(material, "normalTexture", path) ||
      !this->CheckTextureInfo(material, "occlusionTexture", path) ||
      !this->CheckTextureInfo(material, "emissiveTexture", path) ||
      !this->Numbers(material, "emissiveFactor", path, 3, 0.0, Huge) ||
      !this->Number(material, "alphaCutoff", path, 0.0, Huge))
    {
      return false;
    }
    const std::string alphaMode = material.get("alphaMode", "OPAQUE").isString()
      ? material.get("alphaMode", "OPAQUE").asString()
      : "";
    if (alphaMode != "OPAQUE" && alphaMode != "MASK" && alphaMode != "BLEND")
    {
      return this->Fail(path + ".alphaMode " + Quoted(alphaMode) + " is not OPAQUE, MASK or BLEND");
    }
    return true;
  }

  /** The material extensions this importer reads (ior, transmission, volume). */
  bool CheckMaterialExtensions(const Json::Value& material, const std::string& path)
  {
    const Json::Value& extensions = material["extensions"];
    const std::string extPath = Member(path, "extensions");
    for (const char* name : OwnExtensions)
    {
      if (!this->IsObjectOrAbsent(extensions, name, extPath))
      {
        return false;
      }
    }
    const Json::Value& ior = extensions["KHR_materials_ior"];
    if (ior.isMember("ior") &&
      !(ior["ior"].isNumeric() && ior["ior"].asDouble() >= 1.0 && ior["ior"].asDouble() <= MaxIOR))
    {
      const double value = ior["ior"].isNumeric() ? ior["ior"].asDouble() : NaN;
      std::ostringstream message;
      message << extPath << ".KHR_materials_ior.ior = " << value;
      if (value > MaxIOR)
      {
        message << " is beyond the largest index of refraction supported (" << MaxIOR << ")";
      }
      else
      {
        message << " is not a physical index of refraction (it must be finite and >= 1)";
      }
      if (material.isMember("name"))
      {
        message << " in material " << Quoted(material["name"].asString());
      }
      return this->Fail(message.str());
    }
    const Json::Value& transmission = extensions["KHR_materials_transmission"];
    const Json::Value& volume = extensions["KHR_materials_volume"];
    if (!this->Number(transmission, "transmissionFactor",
          Member(extPath, "KHR_materials_transmission"), 0.0, 1.0) ||
      !this->CheckTextureInfo(
        transmission, "transmissionTexture", Member(extPath, "KHR_materials_transmission")) ||
      !this->Number(
        volume, "thicknessFactor", Member(extPath, "KHR_materials_volume"), 0.0, Huge) ||
      !this->Number(volume, "attenuationDistance", Member(extPath, "KHR_materials_volume"),
        MinAttenuationDistance, Huge) ||
      !this->Numbers(
        volume, "attenuationColor", Member(extPath, "KHR_materials_volume"), 3, 0.0, 1.0))
    {
      return false;
    }
    return true;
  }

  bool CheckMeshes()
  {
    const Json::Value& meshes = this->Root["meshes"];
    for (Json::ArrayIndex m = 0; m < this->Count("meshes"); ++m)
    {
      const std::string meshPath = "meshes[" + std::to_string(m) + "]";
      const Json::Value& primitives = meshes[m]["primitives"];
      if (!primitives.isArray() || primitives.empty())
      {
        return this->Fail(meshPath + ".primitives must be a non-empty array");
      }
      for (Json::ArrayIndex p = 0; p < primitives.size(); ++p)
      {
        const std::string path = meshPath + ".primitives[" + std::to_string(p) + "]";
        if (!this->CheckPrimitive(primitives[p], path))
        {
          return false;
        }
      }
    }
    return true;
  }

  /**
   * A primitive: a VEC3 FLOAT POSITION, every attribute an accessor of as many
   * elements, unsigned integer indices, morph targets that are accessors.
   */
  bool CheckPrimitive(const Json::Value& primitive, const std::string& path)
  {
    const Json::Value& accessors = this->Root["accessors"];
    if (!primitive.isObject() || !primitive["attributes"].isObject() ||
      !primitive["attributes"].isMember("POSITION"))
    {
      return this->Fail(path + ".attributes.POSITION is missing");
    }
    const Json::Value& attributes = primitive["attributes"];
    for (const std::string& name : attributes.getMemberNames())
    {
      if (!this->IndexValue(attributes[name], MemberPath(path + ".attributes", name), "accessors"))
      {
        return false;
      }
    }
    const std::uint64_t vertices = accessors[attributes["POSITION"].asUInt()]["count"].asUInt64();
    if (!this->CheckAttributes(attributes, path + ".attributes", vertices, false))
    {
      return false;
    }
    if (!this->Index(primitive, "indices", path, "accessors") ||
      !this->Index(primitive, "material", path, "materials") ||
      !this->Integer(primitive, "mode", path, 0, 6))
    {
      return false;
    }
    if (primitive.isMember("indices"))
    {
      const Json::Value& indices = accessors[primitive["indices"].asUInt()];
      const int type = indices.get("componentType", 0).asInt();
      if (indices.get("type", "").asString() != "SCALAR" ||
        (type != 5121 && type != 5123 && type != 5125))
      {
        return this->Fail(path + ".indices must be a SCALAR accessor of unsigned integers");
      }
    }
    const Json::Value& targets = primitive["targets"];
    if (primitive.isMember("targets") && !targets.isArray())
    {
      return this->Fail(path + ".targets must be an array");
    }
    for (Json::ArrayIndex t = 0; targets.isArray() && t < targets.size(); ++t)
    {
      const std::string targetPath = path + ".targets[" + std::to_string(t) + "]";
      if (!targets[t].isObject())
      {
        return this->Fail(targetPath + " must be a JSON object");
      }
      for (const std::string& name : targets[t].getMemberNames())
      {
        if (!this->IndexValue(targets[t][name], MemberPath(targetPath, name), "accessors"))
        {
          return false;
        }
      }
      if (!this->CheckAttributes(targets[t], targetPath, vertices, true))
      {
        return false;
      }
    }
    return true;
  }

  /**
   * The accessors of a primitive's attributes (or of a morph target's, `target`),
   * already known to be valid indices: of a type glTF allows for the attribute,
   * with one element per vertex.
   */
  bool CheckAttributes(
    const Json::Value& attributes, const std::string& path, std::uint64_t vertices, bool target)
  {
    const Json::Value& accessors = this->Root["accessors"];
    for (const std::string& name : attributes.getMemberNames())
    {
      const Json::Value& accessor = accessors[attributes[name].asUInt()];
      const std::string expected = AttributeTypeProblem(name, accessor, target);
      if (!expected.empty())
      {
        return this->Fail(MemberPath(path, name) + " must be " + expected + " (accessors[" +
          std::to_string(attributes[name].asUInt()) + "] is " + accessor["type"].asString() +
          " of component type " + std::to_string(accessor["componentType"].asInt()) + ")");
      }
      if (accessor["count"].asUInt64() != vertices)
      {
        return this->Fail(MemberPath(path, name) + " has " +
          std::to_string(accessor["count"].asUInt64()) + " elements but POSITION has " +
          std::to_string(vertices));
      }
    }
    return true;
  }

  bool CheckCameras()
  {
    const Json::Value& cameras = this->Root["cameras"];
    for (Json::ArrayIndex i = 0; i < this->Count("cameras"); ++i)
    {
      const std::string path = "cameras[" + std::to_string(i) + "]";
      const std::string type =
        cameras[i]["type"].isString() ? cameras[i]["type"].asString() : std::string();
      if (type != "perspective" && type != "orthographic")
      {
        return this->Fail(path + ".type must be 'perspective' or 'orthographic'");
      }
      const Json::Value& camera = cameras[i][type];
      const std::string cameraPath = path + "." + type;
      if (!camera.isObject())
      {
        return this->Fail(cameraPath + " is missing");
      }
      if (type == "perspective")
      {
        // A frustum needs 0 < yfov < pi and 0 < znear < zfar.
        if (!this->Number(camera, "yfov", cameraPath, VTK_DBL_MIN, Pi * (1.0 - 1e-9), true) ||
          !this->Number(camera, "znear", cameraPath, VTK_DBL_MIN, Huge, true) ||
          !this->Number(camera, "aspectRatio", cameraPath, VTK_DBL_MIN, Huge) ||
          !this->Number(
            camera, "zfar", cameraPath, camera.get("znear", 0.0).asDouble() * (1.0 + 1e-12), Huge))
        {
          return false;
        }
      }
      else if (!this->Number(camera, "xmag", cameraPath, VTK_DBL_MIN, Huge, true) ||
        !this->Number(camera, "ymag", cameraPath, VTK_DBL_MIN, Huge, true) ||
        !this->Number(camera, "znear", cameraPath, 0.0, Huge, true) ||
        !this->Number(camera, "zfar", cameraPath,
          camera.get("znear", 0.0).asDouble() * (1.0 + 1e-12) + VTK_DBL_MIN, Huge, true))
      {
        return false;
      }
    }
    return true;
  }

  bool CheckLights()
  {
    const Json::Value& extensions = this->Root["extensions"];
    if (!this->IsObjectOrAbsent(extensions, "KHR_lights_punctual", "extensions"))
    {
      return false;
    }
    const Json::Value& lights = extensions["KHR_lights_punctual"]["lights"];
    if (extensions["KHR_lights_punctual"].isMember("lights") && !lights.isArray())
    {
      return this->Fail("extensions.KHR_lights_punctual.lights must be an array");
    }
    this->Counts["lights"] = lights.isArray() ? lights.size() : 0;
    for (Json::ArrayIndex i = 0; i < this->Count("lights"); ++i)
    {
      const std::string path = "extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]";
      const Json::Value& light = lights[i];
      const std::string type =
        light.isObject() && light["type"].isString() ? light["type"].asString() : "";
      if (type != "directional" && type != "point" && type != "spot")
      {
        return this->Fail(path + ".type must be 'directional', 'point' or 'spot'");
      }
      if (!this->Numbers(light, "color", path, 3, 0.0, 1.0) ||
        !this->Number(light, "intensity", path, 0.0, Huge) ||
        !this->Number(light, "range", path, VTK_DBL_MIN, Huge))
      {
        return false;
      }
      if (light.get("intensity", 1.0).asDouble() > MaxLightIntensity)
      {
        std::ostringstream message;
        message << path << ".intensity = " << light["intensity"].asDouble()
                << " is beyond the largest intensity the GPU passes represent ("
                << MaxLightIntensity << ", float range)";
        return this->Fail(message.str());
      }
      if (type == "spot")
      {
        const Json::Value& spot = light["spot"];
        if (!spot.isObject())
        {
          return this->Fail(path + ".spot is missing");
        }
        const double outer = spot.get("outerConeAngle", Pi / 4.0).asDouble();
        if (!this->Number(spot, "outerConeAngle", path + ".spot", VTK_DBL_MIN, Pi / 2.0) ||
          !this->Number(spot, "innerConeAngle", path + ".spot", 0.0, outer * (1.0 - 1e-12)))
        {
          return false;
        }
      }
    }
    return true;
  }

  bool CheckNodes()
  {
    const Json::Value& nodes = this->Root["nodes"];
    const std::size_t count = this->Count("nodes");
    this->Parents.assign(count, -1);
    for (Json::ArrayIndex i = 0; i < count; ++i)
    {
      const std::string path = "nodes[" + std::to_string(i) + "]";
      if (!this->CheckNode(nodes[i], path) || !this->CheckChildren(nodes[i], path, i))
      {
        return false;
      }
    }
    return this->CheckNodeTree() && this->CheckNodeDepth();
  }

  /** A node's references, transform and light link. */
  bool CheckNode(const Json::Value& node, const std::string& path)
  {
    if (!this->Index(node, "mesh", path, "meshes") ||
      !this->Index(node, "camera", path, "cameras") || !this->Index(node, "skin", path, "skins") ||
      !this->Numbers(node, "matrix", path, 16, -Huge, Huge) ||
      !this->Numbers(node, "translation", path, 3, -Huge, Huge) ||
      !this->Numbers(node, "rotation", path, 4, -1.0, 1.0) ||
      !this->Numbers(node, "scale", path, 3, -Huge, Huge) ||
      !this->IsObjectOrAbsent(node, "extensions", path) ||
      !this->IsObjectOrAbsent(node["extensions"], "KHR_lights_punctual", path + ".extensions") ||
      !this->Index(node["extensions"]["KHR_lights_punctual"], "light",
        path + ".extensions.KHR_lights_punctual", "lights",
        node["extensions"].isMember("KHR_lights_punctual")))
    {
      return false;
    }
    if (node.isMember("rotation"))
    {
      // glTF rotations are unit quaternions; exporters write float32, ~1e-7 off.
      const Json::Value& q = node["rotation"];
      const double norm =
        std::sqrt(q[0].asDouble() * q[0].asDouble() + q[1].asDouble() * q[1].asDouble() +
          q[2].asDouble() * q[2].asDouble() + q[3].asDouble() * q[3].asDouble());
      if (std::abs(norm - 1.0) > 1e-3)
      {
        return this->Fail(
          path + ".rotation is not a unit quaternion (norm " + std::to_string(norm) + ")");
      }
    }
    return true;
  }

  /** Node `parent`'s children: valid node indices, none with another parent. */
  bool CheckChildren(const Json::Value& node, const std::string& path, Json::ArrayIndex parent)
  {
    const Json::Value& children = node["children"];
    if (node.isMember("children") && !children.isArray())
    {
      return this->Fail(path + ".children must be an array");
    }
    for (Json::ArrayIndex c = 0; children.isArray() && c < children.size(); ++c)
    {
      const std::string childPath = path + ".children[" + std::to_string(c) + "]";
      if (!this->IndexValue(children[c], childPath, "nodes"))
      {
        return false;
      }
      const int child = children[c].asInt();
      if (this->Parents[child] >= 0)
      {
        return this->Fail(childPath + ": node " + std::to_string(child) +
          " already has a parent (node " + std::to_string(this->Parents[child]) +
          "); glTF nodes form a tree");
      }
      this->Parents[child] = static_cast<int>(parent);
    }
    return true;
  }

  /**
   * No cycles. With at most one parent each, a cycle is a parent chain that comes
   * back to itself. Each chain is walked once: 1 marks the current walk, 2 a
   * checked node.
   */
  bool CheckNodeTree()
  {
    const std::size_t count = this->Parents.size();
    std::vector<char> state(count, 0);
    for (std::size_t i = 0; i < count; ++i)
    {
      int n = static_cast<int>(i);
      while (n >= 0 && state[n] == 0)
      {
        state[n] = 1;
        n = this->Parents[n];
      }
      if (n >= 0 && state[n] == 1)
      {
        return this->Fail(
          "nodes[" + std::to_string(n) + "] is its own ancestor: the node hierarchy has a cycle");
      }
      for (n = static_cast<int>(i); n >= 0 && state[n] == 1; n = this->Parents[n])
      {
        state[n] = 2;
      }
    }
    return true;
  }

  /**
   * At most MaxNodeDepth levels (a root is level 1). VTK's loader recurses once per
   * level, so this is checked without recursion: a node's level is its parent's
   * plus one, found by walking up to a node whose level is known (each node is
   * walked over once; the forest has no cycles, CheckNodeTree() saw to it).
   */
  bool CheckNodeDepth()
  {
    const std::size_t count = this->Parents.size();
    std::vector<int> level(count, 0);
    std::vector<int> chain;
    int deepest = -1;
    for (std::size_t i = 0; i < count; ++i)
    {
      chain.clear();
      int n = static_cast<int>(i);
      for (; n >= 0 && level[n] == 0; n = this->Parents[n])
      {
        chain.push_back(n);
      }
      int depth = n >= 0 ? level[n] : 0;
      for (auto it = chain.rbegin(); it != chain.rend(); ++it)
      {
        level[*it] = ++depth;
      }
      deepest = deepest < 0 || depth > level[deepest] ? static_cast<int>(i) : deepest;
    }
    if (deepest >= 0 && level[deepest] > MaxNodeDepth)
    {
      return this->Fail("the node hierarchy is " + std::to_string(level[deepest]) +
        " levels deep (down to nodes[" + std::to_string(deepest) + "]); at most " +
        std::to_string(MaxNodeDepth) + " levels are supported (VTK's glTF loader recurses " +
        "once per level)");
    }
    return true;
  }

  bool CheckScenes()
  {
    if (this->Count("scenes") == 0)
    {
      return this->Fail("the file has no scenes: nothing to import");
    }
    if (!this->Index(this->Root, "scene", "", "scenes"))
    {
      return false;
    }
    const Json::Value& scenes = this->Root["scenes"];
    for (Json::ArrayIndex s = 0; s < this->Count("scenes"); ++s)
    {
      const Json::Value& roots = scenes[s]["nodes"];
      if (scenes[s].isMember("nodes") && !roots.isArray())
      {
        return this->Fail("scenes[" + std::to_string(s) + "].nodes must be an array");
      }
      std::set<int> seen;
      for (Json::ArrayIndex r = 0; roots.isArray() && r < roots.size(); ++r)
      {
        const std::string path =
          "scenes[" + std::to_string(s) + "].nodes[" + std::to_string(r) + "]";
        if (!this->IndexValue(roots[r], path, "nodes"))
        {
          return false;
        }
        const int node = roots[r].asInt();
        if (this->Parents[node] >= 0)
        {
          return this->Fail(path + ": node " + std::to_string(node) + " is a child of node " +
            std::to_string(this->Parents[node]) + ", not a root");
        }
        if (!seen.insert(node).second)
        {
          return this->Fail(path + ": node " + std::to_string(node) + " is listed twice");
        }
      }
    }
    return true;
  }

  bool CheckSkinsAndAnimations()
  {
    const Json::Value& skins = this->Root["skins"];
    for (Json::ArrayIndex i = 0; i < this->Count("skins"); ++i)
    {
      const std::string path = "skins[" + std::to_string(i) + "]";
      const Json::Value& joints = skins[i]["joints"];
      if (!joints.isArray() || joints.empty())
      {
        return this->Fail(path + ".joints must be a non-empty array");
      }
      for (Json::ArrayIndex j = 0; j < joints.size(); ++j)
      {
        if (!this->IndexValue(joints[j], path + ".joints[" + std::to_string(j) + "]", "nodes"))
        {
          return false;
        }
      }
      if (!this->Index(skins[i], "inverseBindMatrices", path, "accessors") ||
        !this->Index(skins[i], "skeleton", path, "nodes"))
      {
        return false;
      }
    }
    const Json::Value& animations = this->Root["animations"];
    for (Json::ArrayIndex a = 0; a < this->Count("animations"); ++a)
    {
      const std::string path = "animations[" + std::to_string(a) + "]";
      const Json::Value& samplers = animations[a]["samplers"];
      const Json::Value& channels = animations[a]["channels"];
      if (!samplers.isArray() || !channels.isArray())
      {
        return this->Fail(path + " needs 'samplers' and 'channels' arrays");
      }
      for (Json::ArrayIndex s = 0; s < samplers.size(); ++s)
      {
        const std::string samplerPath = path + ".samplers[" + std::to_string(s) + "]";
        if (!this->Index(samplers[s], "input", samplerPath, "accessors", true) ||
          !this->Index(samplers[s], "output", samplerPath, "accessors", true))
        {
          return false;
        }
      }
      for (Json::ArrayIndex c = 0; c < channels.size(); ++c)
      {
        const std::string channelPath = path + ".channels[" + std::to_string(c) + "]";
        const Json::Value& sampler = channels[c]["sampler"];
        if (!sampler.isInt64() || sampler.asInt64() < 0 ||
          sampler.asInt64() >= static_cast<long long>(samplers.size()))
        {
          return this->Fail(channelPath + ".sampler is out of range: the animation has " +
            Plural(samplers.size(), "sampler"));
        }
        if (!channels[c]["target"].isObject() ||
          !this->Index(channels[c]["target"], "node", channelPath + ".target", "nodes"))
        {
          return this->Fail(channelPath + ".target is malformed");
        }
      }
    }
    return true;
  }

  const Json::Value& Root;
  std::string Folder;
  bool Binary;
  std::size_t BinSize;
  std::map<std::string, std::size_t> Counts;
  std::vector<std::uint64_t> BufferLengths;
  std::vector<int> Parents;
  std::string Problem;
};
}

std::string QuotedName(const std::string& text)
{
  return Quoted(text);
}

std::string CountOf(std::size_t count, const char* noun)
{
  return Plural(count, noun);
}

std::string SplitBinary(const std::string& contents, std::string& json, std::size_t& binSize)
{
  return SplitGLB(contents, json, binSize);
}

std::string OneLineErrors(const std::string& jsoncppErrors)
{
  return OneLine(jsoncppErrors);
}

bool MentionsOwnExtension(const std::string& message)
{
  return std::any_of(std::begin(OwnExtensions), std::end(OwnExtensions),
    [&](const char* name) { return message.find(name) != std::string::npos; });
}

std::string CheckDocument(
  const Json::Value& root, const std::string& folder, bool binary, std::size_t binSize)
{
  return DocumentChecker(root, folder, binary, binSize).Check();
}
}
}
