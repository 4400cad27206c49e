#include "vtkCausticsMeshReader.h"

#include "vtkCausticsFileText.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCausticsMaterial.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkObjectFactory.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSTLReader.h"
#include "vtksys/SystemTools.hxx"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

vtkStandardNewMacro(vtkCausticsMeshReader);

namespace
{
/**
 * vtkOBJReader (9.1) reads lines with fgets into a 256 KiB buffer and fails on a
 * longer one, quoting all of it; its content (without '\n') is at most this long.
 */
constexpr std::size_t OBJLineLimit = 256 * 1024 - 2;
/** vtkOBJReader copies a material name with sscanf("%s") into a 100-byte buffer. */
constexpr std::size_t OBJNameLimit = 99;
/**
 * Longest PLY header line accepted (real ones are a few dozen bytes): vtkPLY
 * (9.1) reads each line with its '\n' into a 4096-byte buffer (4095 bytes and a
 * NUL), so a longer one is split and VTK then fails with a vague message.
 */
constexpr std::size_t PLYHeaderLineLimit = 4094;
/**
 * Longest line of an ASCII PLY body (one element) accepted, and of a header line
 * naming "vertex_index": vtkPLY (9.1) reads lines into a 4096-byte buffer (4095
 * bytes and a NUL) and rewrites "vertex_index" there as "vertex_indices", two
 * bytes longer.
 */
constexpr std::size_t PLYLineLimit = 4093;

std::string LowerExtension(const std::string& fileName)
{
  return vtksys::SystemTools::LowerCase(vtksys::SystemTools::GetFilenameLastExtension(fileName));
}

using caustics::text::Printable;
using caustics::text::Quote;
using caustics::text::ReasonLength;

/**
 * Why `path` cannot be a mesh file, judged by stat() alone, or "". Opening a FIFO
 * blocks until a writer comes and /dev/zero never ends, so only regular files go on.
 */
std::string PathProblem(const std::string& path, std::uint64_t& size)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
  {
    const int error = errno;
    return error == ENOENT || error == ENOTDIR
      ? "no such file"
      : std::string("cannot be examined: ") + std::strerror(error);
  }
  if (S_ISDIR(info.st_mode))
  {
    return "is a folder, not a mesh file";
  }
  if (!S_ISREG(info.st_mode))
  {
    const char* kind = S_ISFIFO(info.st_mode)          ? "a FIFO (named pipe)"
      : S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode) ? "a device"
      : S_ISSOCK(info.st_mode)                         ? "a socket"
                                                       : "something else";
    return std::string("is ") + kind + ", not a regular file";
  }
  size = static_cast<std::uint64_t>(info.st_size);
  return std::string();
}

/**
 * Lines of a stream, counted from 1, each at most `limit` bytes (so a huge line
 * costs no more memory than that); a "\r\n" ending counts as "\n".
 */
class LineReader
{
public:
  LineReader(std::istream& in, std::size_t limit)
    : Buffer(in.rdbuf())
    , Limit(limit)
  {
  }

  /**
   * Reads the next line into `line`. False at the end of the stream, or for a line
   * over the limit (TooLong(); `line` then holds its first `limit` bytes).
   */
  bool Next(std::string& line)
  {
    using Traits = std::char_traits<char>;
    line.clear();
    int c = this->Buffer->sbumpc();
    if (c == Traits::eof())
    {
      return false;
    }
    ++this->Number;
    for (; c != Traits::eof() && c != '\n'; c = this->Buffer->sbumpc())
    {
      if (line.size() == this->Limit)
      {
        this->Long = true;
        return false;
      }
      line.push_back(static_cast<char>(c));
    }
    this->Terminated = c == '\n';
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    return true;
  }

  bool TooLong() const { return this->Long; }
  /** Whether the line Next() read ended with '\n' (else with the end of the stream). */
  bool Ended() const { return this->Terminated; }
  long long GetNumber() const { return this->Number; }
  std::size_t GetLimit() const { return this->Limit; }
  void SetLimit(std::size_t limit) { this->Limit = limit; }

private:
  std::streambuf* Buffer;
  std::size_t Limit;
  long long Number = 0;
  bool Long = false;
  bool Terminated = false;
};

/**
 * The message of a VTK error/warning event on one printable line, without VTK's
 * "file, line" preamble and without the mesh's path (this reader's message starts
 * with it), and short: it may quote the bad file.
 */
std::string EventText(const char* text, const std::string& path)
{
  std::string message = text ? text : "";
  // vtkErrorMacro texts look like "ERROR: In file, line N\nClass (0x...): message\n\n".
  const std::size_t object = message.find("): ");
  if (object != std::string::npos)
  {
    message = message.substr(object + 3);
  }
  // "error while reading file /long/path/mesh.stl at line 5: ..." would push the
  // reason past the length kept.
  for (std::size_t at = message.find(path); !path.empty() && at != std::string::npos;
       at = message.find(path, at))
  {
    const std::size_t begin = at >= 5 && message.compare(at - 5, 5, "file ") == 0 ? at - 5 : at;
    const std::size_t end = at + path.size() < message.size() && message[at + path.size()] == ' '
      ? at + path.size() + 1
      : at + path.size();
    message.erase(begin, end - begin);
    at = begin;
  }
  while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
  {
    message.pop_back();
  }
  std::replace(message.begin(), message.end(), '\n', ' ');
  return Printable(message, ReasonLength);
}

/** Errors and warnings of VTK's reader, in order, and errors of its executive. */
struct ReaderMessages
{
  vtkObject* Reader = nullptr;
  std::string Path;
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
  /**
   * The executive's "returned failure for request: <vtkInformation dump>" after the
   * reader's own error; kept out of the output window, where a program that shows
   * the last line of the first error would show "FORWARD_DIRECTION: 0".
   */
  std::vector<std::string> ExecutiveErrors;
};

void CollectMessages(vtkObject* caller, unsigned long event, void* clientData, void* callData)
{
  auto* messages = static_cast<ReaderMessages*>(clientData);
  const std::string text = EventText(static_cast<const char*>(callData), messages->Path);
  if (caller != messages->Reader)
  {
    messages->ExecutiveErrors.push_back(text);
    return;
  }
  (event == vtkCommand::ErrorEvent ? messages->Errors : messages->Warnings).push_back(text);
}

// --- PLY container check --------------------------------------------------------------------
// vtkPLYReader (VTK 9.1) frees invalid pointers when the body is shorter than the
// header says, so the body is walked here first, streamed from the file. This
// keeps no geometry: VTK reads it.

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

/**
 * The words of a PLY line as vtkPLY (9.1) splits it: "vertex_index" and everything
 * after it rewritten as "vertex_indices", then words separated by spaces, tabs and
 * carriage returns only (so "1\v2" is one word).
 */
void PlyWords(std::string& line, std::vector<std::string_view>& words)
{
  const std::size_t alias = line.find("vertex_index");
  if (alias != std::string::npos)
  {
    line.replace(alias, std::string::npos, "vertex_indices");
  }
  words.clear();
  std::size_t i = 0;
  auto separator = [&line](std::size_t k)
  { return line[k] == ' ' || line[k] == '\t' || line[k] == '\r'; };
  while (i < line.size())
  {
    while (i < line.size() && separator(i))
    {
      ++i;
    }
    const std::size_t begin = i;
    while (i < line.size() && !separator(i))
    {
      ++i;
    }
    if (i > begin)
    {
      words.push_back(std::string_view(line).substr(begin, i - begin));
    }
  }
}

/**
 * Walks a PLY file's header and body; Check() returns the first problem or "".
 * vtkPLY (9.1) reads the header and an ASCII body one line per element and takes
 * the words it needs without counting them: a line with too few words, a last line
 * without a line break (read as the end of the file) or a NUL byte (which ends its
 * C string) made it read through a null pointer (SIGSEGV, found by fuzzing). So the
 * lines are read here as it reads them.
 */
class PlyChecker
{
public:
  std::string Check(std::istream& in)
  {
    this->Buffer = in.rdbuf();
    LineReader lines(in, PLYHeaderLineLimit);
    this->Lines = &lines;
    std::string problem = this->ParseHeader();
    lines.SetLimit(PLYLineLimit);
    for (std::size_t e = 0; problem.empty() && e < this->Elements.size(); ++e)
    {
      problem = this->CheckElement(this->Elements[e], e + 1 == this->Elements.size());
    }
    return problem;
  }

private:
  enum class Read
  {
    Ok,
    End,       ///< the data ended
    NotNumber, ///< an ASCII word that is not a number
    LineShort  ///< an ASCII line without the word asked for
  };

  /** The instances of an element; `last`: the last element of the header. */
  std::string CheckElement(const PlyElement& element, bool last)
  {
    if (element.properties.empty() && element.count > 0)
    {
      // Nothing to read per instance, so nothing bounds the count by the file's size.
      return "element " + Quote(element.name) + " declares " + std::to_string(element.count) +
        " instances but no properties";
    }
    const bool isFace = element.name == "face";
    for (std::uint64_t i = 0; i < element.count; ++i)
    {
      if (this->Ascii)
      {
        const std::string problem = this->NextAsciiLine(element, i, last && i + 1 == element.count);
        if (!problem.empty())
        {
          return problem;
        }
      }
      for (const PlyProperty& property : element.properties)
      {
        double count = 1.0;
        if (!property.countType.empty())
        {
          const Read read = this->Value(property.countType, count);
          if (read != Read::Ok)
          {
            return this->ReadProblem(read, element, i);
          }
        }
        if (!(count >= 0.0) || count != std::floor(count))
        {
          return "element " + Quote(element.name) + " " + std::to_string(i) + ": list length " +
            this->NumberText(count) + " is not a non-negative integer";
        }
        const bool isIndex = isFace && !property.countType.empty() &&
          (property.name == "vertex_indices" || property.name == "vertex_index");
        for (double k = 0; k < count; ++k)
        {
          double value = 0.0;
          const Read read = this->Value(property.type, value);
          if (read != Read::Ok)
          {
            return this->ReadProblem(read, element, i);
          }
          if (isIndex && !(value >= 0.0 && value < static_cast<double>(this->VertexCount)))
          {
            return "face " + std::to_string(i) + " refers to vertex " + this->NumberText(value) +
              ", but the file has " + std::to_string(this->VertexCount) + " vertices";
          }
        }
      }
    }
    return std::string();
  }

  /**
   * A value read from the file, for a message: an integer as such, else the word
   * of an ASCII file (quoted) or the binary value. (Converting a NaN or a value
   * beyond long long to an integer, as this once did, is undefined behaviour.)
   */
  std::string NumberText(double value) const
  {
    if (std::isfinite(value) && std::fabs(value) < 1e18 && value == std::floor(value))
    {
      return std::to_string(static_cast<long long>(value));
    }
    if (this->Ascii)
    {
      return Quote(this->Token);
    }
    std::ostringstream text;
    text << value;
    return text.str();
  }

  /**
   * The line of an ASCII element: present, ended by a line break (the last line of
   * the file too: `last`), without NUL bytes.
   */
  std::string NextAsciiLine(const PlyElement& element, std::uint64_t index, bool last)
  {
    const std::string where = "element " + Quote(element.name) + " " + std::to_string(index);
    if (!this->Lines->Next(this->Line))
    {
      return this->Lines->TooLong()
        ? "line " + std::to_string(this->Lines->GetNumber()) + " (" + where + ") is longer than " +
          std::to_string(PLYLineLimit) + " bytes: " + Quote(this->Line)
        : "the file ends before " + where + " of " + std::to_string(element.count) +
          " (truncated?)";
    }
    const std::string at = "line " + std::to_string(this->Lines->GetNumber()) + " (" + where + ")";
    if (this->Line.find('\0') != std::string::npos)
    {
      return at + " holds a NUL byte: " + Quote(this->Line);
    }
    if (!this->Lines->Ended())
    {
      return last ? at +
          " does not end with a line break (vtkPLYReader takes it for the end "
          "of the file)"
                  : "the file ends inside " + where + " of " + std::to_string(element.count) +
          " (truncated?)";
    }
    PlyWords(this->Line, this->Words);
    this->Word = 0;
    return std::string();
  }

  std::string ParseHeader()
  {
    std::string line;
    if (!this->Lines->Next(line) || line.compare(0, 3, "ply") != 0)
    {
      return "not a PLY file (it does not start with 'ply')";
    }
    bool haveFormat = false;
    while (this->Lines->Next(line))
    {
      const std::string number = "header line " + std::to_string(this->Lines->GetNumber());
      if (line.find('\0') != std::string::npos)
      {
        return number + " holds a NUL byte: " + Quote(line);
      }
      if (!this->Lines->Ended())
      {
        return number + " does not end with a line break: " + Quote(line);
      }
      if (line.size() > PLYLineLimit && line.find("vertex_index") != std::string::npos)
      {
        return number + " is longer than " + std::to_string(PLYLineLimit) +
          " bytes and names vertex_index, which vtkPLYReader lengthens past its buffer: " +
          Quote(line);
      }
      const std::string quoted = Quote(line);
      PlyWords(line, this->Words);
      const std::string keyword = this->Words.empty() ? "" : std::string(this->Words[0]);
      if (keyword == "end_header")
      {
        if (!haveFormat)
        {
          return "the header has no 'format' line";
        }
        return this->CheckVertexElement();
      }
      std::string problem;
      if (keyword == "format")
      {
        // A second one would let this check read the body in a format VTK does not
        // (found by fuzzing: an ASCII body read as binary here, then VTK crashed).
        problem = haveFormat ? number + " is a second 'format' line" : this->ParseFormat(quoted);
        haveFormat = true;
      }
      else if (keyword == "element")
      {
        problem = this->ParseElement(quoted);
      }
      else if (keyword == "property")
      {
        problem = this->ParseProperty(quoted);
      }
      else if (keyword.empty())
      {
        // vtkPLY reads the first word of every header line, even of an empty one
        // (found by fuzzing: it then misread the body and crashed).
        problem = number + " is empty";
      }
      else if (keyword != "comment" && keyword != "obj_info")
      {
        problem = "unknown " + number + " " + quoted;
      }
      if (!problem.empty())
      {
        return problem;
      }
    }
    if (this->Lines->TooLong())
    {
      return "header line " + std::to_string(this->Lines->GetNumber()) + " is longer than " +
        std::to_string(PLYHeaderLineLimit) + " bytes: " + Quote(line);
    }
    return "the header has no 'end_header' line";
  }

  /** "format ascii|binary_little_endian|binary_big_endian 1.0" */
  std::string ParseFormat(const std::string& quoted)
  {
    const std::string format = this->Words.size() >= 2 ? std::string(this->Words[1]) : "";
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
      return "unknown PLY format in header line " + quoted;
    }
    return std::string();
  }

  /** "element <name> <count>", the count in decimal digits. */
  std::string ParseElement(const std::string& quoted)
  {
    const std::string_view count = this->Words.size() == 3 ? this->Words[2] : std::string_view();
    if (count.empty() || count.size() > 18 ||
      !std::all_of(count.begin(), count.end(),
        [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }))
    {
      return "malformed header line " + quoted + " (expected 'element <name> <count>')";
    }
    PlyElement element;
    element.name = std::string(this->Words[1]);
    element.count = std::stoull(std::string(count));
    this->Elements.push_back(element);
    return std::string();
  }

  /** "property <type> <name>" or "property list <count type> <type> <name>" */
  std::string ParseProperty(const std::string& quoted)
  {
    if (this->Elements.empty())
    {
      return "header line " + quoted + " comes before any element";
    }
    const bool list = this->Words.size() >= 2 && this->Words[1] == "list";
    if (this->Words.size() != (list ? 5u : 3u))
    {
      return "malformed header line " + quoted;
    }
    PlyProperty property;
    property.countType = list ? std::string(this->Words[2]) : std::string();
    property.type = std::string(this->Words[list ? 3 : 1]);
    property.name = std::string(this->Words[list ? 4 : 2]);
    if (list && (PlyTypeSize(property.countType) == 0 || PlyTypeIsFloat(property.countType)))
    {
      return "header line " + quoted + ": bad list length type";
    }
    if (PlyTypeSize(property.type) == 0)
    {
      return "malformed header line " + quoted + ": unknown type";
    }
    this->Elements.back().properties.push_back(property);
    return std::string();
  }

  /**
   * The elements vtkPLYReader reads, as it needs them. It takes the file's word for
   * whether a property is a list, but stores what it reads where it expects its own
   * kind: a face without a vertex_indices list left the index pointer unset (free()
   * of an invalid pointer, SIGSEGV; found by fuzzing), a list where it expects a
   * scalar (vertex "alpha", face "intensity") wrote a pointer over its one-byte field.
   * So in "vertex" and "face" every property is a scalar but the face's
   * vertex_indices and texcoord lists, each element is declared once, and a vertex
   * element with scalar x, y and z is required.
   */
  std::string CheckVertexElement()
  {
    const PlyElement* vertices = nullptr;
    const PlyElement* faces = nullptr;
    for (const PlyElement& element : this->Elements)
    {
      const bool isVertex = element.name == "vertex";
      if (isVertex || element.name == "face")
      {
        const PlyElement*& seen = isVertex ? vertices : faces;
        if (seen)
        {
          return "the header declares element " + Quote(element.name) + " twice";
        }
        seen = &element;
      }
    }
    if (!vertices)
    {
      return "the header declares no 'vertex' element";
    }
    auto has = [](const PlyElement* element, const char* name)
    {
      return element &&
        std::any_of(element->properties.begin(), element->properties.end(),
          [name](const PlyProperty& property) { return property.name == name; });
    };
    if (!has(vertices, "x") || !has(vertices, "y") || !has(vertices, "z"))
    {
      return "the 'vertex' element lacks scalar x, y and z properties";
    }
    if (faces && faces->count > 0 && !has(faces, "vertex_indices"))
    {
      return "the 'face' element has no vertex_indices list";
    }
    for (const PlyElement* element : { vertices, faces })
    {
      for (std::size_t p = 0; element && p < element->properties.size(); ++p)
      {
        const PlyProperty& property = element->properties[p];
        const bool list =
          element == faces && (property.name == "vertex_indices" || property.name == "texcoord");
        if (list == property.countType.empty())
        {
          return "property " + Quote(property.name) + " of element " + Quote(element->name) +
            " must be " + (list ? "a list" : "a scalar") + ", as vtkPLYReader reads it";
        }
      }
    }
    this->VertexCount = vertices->count;
    return std::string();
  }

  std::string ReadProblem(Read read, const PlyElement& element, std::uint64_t index) const
  {
    const std::string where = "element " + Quote(element.name) + " " + std::to_string(index);
    if (read == Read::NotNumber)
    {
      return where + ": " + Quote(this->Token) + " is not a number";
    }
    if (read == Read::LineShort)
    {
      return "line " + std::to_string(this->Lines->GetNumber()) + " (" + where + ") has " +
        std::to_string(this->Words.size()) +
        " values, fewer than its properties need (vtkPLYReader reads one element per line)";
    }
    return "the file ends inside " + where + " of " + std::to_string(element.count) +
      " (truncated?)";
  }

  /** Reads the next value of a PLY type. */
  Read Value(const std::string& type, double& value)
  {
    return this->Ascii ? this->AsciiValue(value) : this->BinaryValue(type, value);
  }

  /** The next word of the current line as a number. */
  Read AsciiValue(double& value)
  {
    if (this->Word >= this->Words.size())
    {
      return Read::LineShort;
    }
    const std::string_view word = this->Words[this->Word++];
    this->Token = std::string(word.substr(0, 65));
    if (word.size() > 64)
    {
      return Read::NotNumber;
    }
    char* end = nullptr;
    value = std::strtod(this->Token.c_str(), &end);
    return end && *end == '\0' ? Read::Ok : Read::NotNumber;
  }

  Read BinaryValue(const std::string& type, double& value)
  {
    const int size = PlyTypeSize(type);
    unsigned char bytes[8];
    if (this->Buffer->sgetn(reinterpret_cast<char*>(bytes), size) != size)
    {
      return Read::End;
    }
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
      return Read::Ok;
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
    return Read::Ok;
  }

  std::vector<PlyElement> Elements;
  std::streambuf* Buffer = nullptr;
  LineReader* Lines = nullptr;
  std::string Line;                    ///< the current line of an ASCII body
  std::vector<std::string_view> Words; ///< its words (views into Line)
  std::size_t Word = 0;                ///< the next word to read
  std::string Token;                   ///< the last ASCII word read, for messages
  std::uint64_t VertexCount = 0;
  bool Ascii = false;
  bool BigEndian = false;
};

// --- OBJ container check --------------------------------------------------------------------
// vtkOBJReader (VTK 9.1) trusts the file: an out-of-range normal or texture
// coordinate index reads out of bounds (a crash for a far one, garbage normals for a
// near one), a coordinate it cannot parse ("nan", "1.0.0") becomes 0 or the previous
// line's value, a NUL byte or a long material name breaks its C string handling. So
// the file is streamed here first, keeping only counts.

bool IsSpace(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/** The whitespace-separated words of `line` (views into it). */
void SplitWords(std::string_view line, std::vector<std::string_view>& words)
{
  words.clear();
  std::size_t i = 0;
  while (i < line.size())
  {
    while (i < line.size() && IsSpace(line[i]))
    {
      ++i;
    }
    const std::size_t begin = i;
    while (i < line.size() && !IsSpace(line[i]))
    {
      ++i;
    }
    if (i > begin)
    {
      words.push_back(line.substr(begin, i - begin));
    }
  }
}

/** Why a vertex coordinate stored as float is unusable, or "". */
std::string CoordinateProblem(double value)
{
  if (!std::isfinite(value))
  {
    return "is not a finite number";
  }
  return std::fabs(value) > FLT_MAX ? "is outside the range of a 32-bit float (3.4e38)"
                                    : std::string();
}

/** Why `word` is not a decimal number that fits a 32-bit float (as VTK keeps it), or "". */
std::string NumberProblem(std::string_view word)
{
  // Only the decimal syntax vtkOBJReader's stream parsing reads: strtod would also
  // take "0x1p3", "infinity" or "nan", which the stream reads as 0.
  const bool decimal = word.size() <= 64 &&
    std::all_of(word.begin(), word.end(),
      [](char c) {
        return std::isdigit(static_cast<unsigned char>(c)) ||
          (c != '\0' && std::strchr("+-.eE", c));
      });
  if (!decimal)
  {
    return "is not a finite number";
  }
  char* end = nullptr;
  const std::string text(word);
  const double value = std::strtod(text.c_str(), &end);
  return !end || *end != '\0' ? "is not a finite number" : CoordinateProblem(value);
}

/** One kind of indexed OBJ data: vertices ("v"), texture coordinates ("vt"), normals ("vn"). */
struct ObjArray
{
  const char* Name;           ///< "vertex"
  const char* Plural;         ///< "vertices"
  long long Count = 0;        ///< lines seen so far
  long long MaxIndex = 0;     ///< largest positive index used
  long long MaxIndexLine = 0; ///< the line of the first use of MaxIndex
};

/**
 * Streams an OBJ file: counts its v/vt/vn lines, checks vertex coordinates, and
 * checks every index of its f/l/p lines, positive (absolute, checked against the
 * whole file's count at the end, as vtkOBJReader allows forward references) or
 * negative (relative to the lines above, as vtkOBJReader resolves them).
 */
class ObjChecker
{
public:
  /** Returns the first problem, or "". */
  std::string Check(std::istream& in)
  {
    LineReader lines(in, OBJLineLimit);
    std::string line;
    while (lines.Next(line))
    {
      const std::string problem = this->CheckLine(line, lines);
      if (!problem.empty())
      {
        return "line " + std::to_string(this->Line) + ": " + problem;
      }
    }
    if (lines.TooLong())
    {
      return "line " + std::to_string(lines.GetNumber()) + " is longer than " +
        std::to_string(lines.GetLimit()) + " bytes (vtkOBJReader's limit): " + Quote(line);
    }
    return this->IndexRangeProblem();
  }

  /** The first 'vn' line that is not three finite numbers, or "" (the normals are then fine). */
  std::string BadNormal;
  /** The number of 'f' elements. */
  long long Faces = 0;

private:
  std::string CheckLine(const std::string& line, LineReader& lines)
  {
    this->Line = lines.GetNumber();
    if (line.find('\0') != std::string::npos)
    {
      return "holds a NUL byte (a binary file?): " + Quote(line);
    }
    SplitWords(line, this->Words);
    if (this->Words.empty())
    {
      return std::string();
    }
    const std::string_view keyword = this->Words[0];
    this->Faces += keyword == "f" ? 1 : 0;
    if (keyword == "v")
    {
      ++this->Vertices.Count;
      return this->CheckVertex();
    }
    if (keyword == "vn")
    {
      ++this->Normals.Count;
      this->CheckNormal(line);
      return std::string();
    }
    if (keyword == "vt")
    {
      ++this->TexCoords.Count;
      return std::string();
    }
    if (keyword == "usemtl" || keyword == "mtllib")
    {
      return this->CheckName();
    }
    if (keyword == "f" || keyword == "l" || keyword == "p")
    {
      return this->CheckElement(keyword[0], lines);
    }
    return std::string();
  }

  std::string CheckVertex()
  {
    if (this->Words.size() < 4)
    {
      return "a vertex needs x, y and z";
    }
    for (std::size_t c = 1; c <= 3; ++c)
    {
      const std::string problem = NumberProblem(this->Words[c]);
      if (!problem.empty())
      {
        return "vertex coordinate " + Quote(this->Words[c]) + " " + problem;
      }
    }
    return std::string();
  }

  /** Bad normals are repaired, not refused: the first is remembered for the warning. */
  void CheckNormal(const std::string& line)
  {
    if (!this->BadNormal.empty())
    {
      return;
    }
    bool good = this->Words.size() >= 4;
    for (std::size_t c = 1; good && c <= 3; ++c)
    {
      good = NumberProblem(this->Words[c]).empty();
    }
    if (!good)
    {
      this->BadNormal = "line " + std::to_string(this->Line) + ": normal " + Quote(line) +
        " is not three finite numbers";
    }
  }

  std::string CheckName() const
  {
    if (this->Words.size() >= 2 && this->Words[1].size() > OBJNameLimit)
    {
      return "name " + Quote(this->Words[1]) + " is longer than " + std::to_string(OBJNameLimit) +
        " bytes (vtkOBJReader's limit)";
    }
    return std::string();
  }

  /**
   * A face ("f v[/vt[/vn]] ..."), line ("l v[/vt] ...") or point ("p v ...") element,
   * continued on the next line after a final "\". vtkOBJReader only uses the vertex
   * index of lines and points.
   */
  std::string CheckElement(char kind, LineReader& lines)
  {
    std::string continued; // a continuation line, which this->Words then views
    int vertices = 0, texCoords = 0, normals = 0;
    for (std::size_t w = 1; w < this->Words.size(); ++w)
    {
      if (this->Words[w] == "\\" && w + 1 == this->Words.size())
      {
        if (!lines.Next(continued))
        {
          return lines.TooLong() ? "the continuation line is longer than " +
              std::to_string(lines.GetLimit()) + " bytes (vtkOBJReader's limit)"
                                 : "the file ends after a '\\' continuation";
        }
        this->Line = lines.GetNumber();
        SplitWords(continued, this->Words);
        this->Words.insert(this->Words.begin(), std::string_view());
        w = 0; // the loop steps to the first word of the continuation
        continue;
      }
      const std::string problem =
        this->CheckElementVertex(kind, this->Words[w], texCoords, normals);
      if (!problem.empty())
      {
        return problem;
      }
      ++vertices;
    }
    const int needed = kind == 'f' ? 3 : kind == 'l' ? 2 : 1;
    if (vertices < needed)
    {
      return std::string(kind == 'f' ? "a face"
                 : kind == 'l'       ? "a line"
                                     : "a point element") +
        " needs at least " + std::to_string(needed) + " vertices";
    }
    if ((texCoords != 0 && texCoords != vertices) || (normals != 0 && normals != vertices))
    {
      return "a face gives texture coordinates or normals for some of its vertices only";
    }
    return std::string();
  }

  /** One "v", "v/vt", "v/vt/vn" or "v//vn" word; counts the vt and vn it gives. */
  std::string CheckElementVertex(char kind, std::string_view word, int& texCoords, int& normals)
  {
    std::string_view parts[3];
    std::size_t count = 0;
    for (std::size_t begin = 0;; ++count)
    {
      const std::size_t slash = word.find('/', begin);
      if (count < 3)
      {
        parts[count] = word.substr(begin, slash == std::string_view::npos ? slash : slash - begin);
      }
      if (slash == std::string_view::npos)
      {
        ++count;
        break;
      }
      begin = slash + 1;
    }
    const bool wellFormed = count <= 3 && !parts[0].empty() && !(count == 2 && parts[1].empty()) &&
      !(count == 3 && parts[2].empty()) &&
      (kind == 'f' || count == 1 || (kind == 'l' && count == 2));
    if (!wellFormed)
    {
      const char* forms = kind == 'f' ? "v, v/vt, v/vt/vn or v//vn"
        : kind == 'l'                 ? "v or v/vt"
                                      : "v";
      return "malformed element vertex " + Quote(word) + " (expected " + forms + ")";
    }
    std::string problem = this->CheckIndex(parts[0], this->Vertices);
    if (problem.empty() && kind == 'f' && count >= 2 && !parts[1].empty())
    {
      ++texCoords;
      problem = this->CheckIndex(parts[1], this->TexCoords);
    }
    if (problem.empty() && kind == 'f' && count == 3)
    {
      ++normals;
      problem = this->CheckIndex(parts[2], this->Normals);
    }
    return problem;
  }

  /**
   * An index into `array`: 1..count (checked at the end, when the count is known),
   * or -1..-(lines so far), counting back from the last line above.
   */
  std::string CheckIndex(std::string_view text, ObjArray& array)
  {
    const bool negative = text[0] == '-';
    const std::string_view digits = text.substr(text[0] == '+' || negative ? 1 : 0);
    if (digits.empty() ||
      !std::all_of(digits.begin(), digits.end(),
        [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }))
    {
      return std::string(array.Name) + " index " + Quote(text) + " is not an integer";
    }
    long long value = 0;
    for (std::size_t i = 0; i < digits.size() && value <= INT_MAX; ++i)
    {
      value = 10 * value + (digits[i] - '0');
    }
    if (value > INT_MAX)
    {
      // vtkOBJReader reads indices as int; no file holds that many lines anyway.
      return std::string(array.Name) + " index " + Quote(text) + " is out of range";
    }
    if (value == 0)
    {
      return std::string(array.Name) + " index 0 is invalid (OBJ indices start at 1)";
    }
    if (negative)
    {
      if (value > array.Count)
      {
        return "relative " + std::string(array.Name) + " index -" + std::to_string(value) +
          " is out of range: only " + std::to_string(array.Count) + " " +
          (array.Count == 1 ? array.Name : array.Plural) + " above it";
      }
      return std::string();
    }
    if (value > array.MaxIndex)
    {
      array.MaxIndex = value;
      array.MaxIndexLine = this->Line;
    }
    return std::string();
  }

  /** The earliest positive index past its array's end, once the file is read. */
  std::string IndexRangeProblem() const
  {
    const ObjArray* worst = nullptr;
    for (const ObjArray* array : { &this->Vertices, &this->TexCoords, &this->Normals })
    {
      if (array->MaxIndex > array->Count && (!worst || array->MaxIndexLine < worst->MaxIndexLine))
      {
        worst = array;
      }
    }
    if (!worst)
    {
      return std::string();
    }
    return "line " + std::to_string(worst->MaxIndexLine) + ": " + worst->Name + " index " +
      std::to_string(worst->MaxIndex) + " is out of range: the file has " +
      std::to_string(worst->Count) + " " + (worst->Count == 1 ? worst->Name : worst->Plural);
  }

  ObjArray Vertices{ "vertex", "vertices" };
  ObjArray TexCoords{ "texture coordinate", "texture coordinates" };
  ObjArray Normals{ "normal", "normals" };
  std::vector<std::string_view> Words;
  long long Line = 0;
};

// --- STL container check --------------------------------------------------------------------
// vtkSTLReader merges coincident points with a vtkMergePoints locator, which
// converts each coordinate to a bucket index: undefined behaviour for a NaN (a NaN
// converted to int). So coordinates are checked here first, naming the triangle
// or line.

/**
 * A binary STL is an 80-byte header, a 32-bit triangle count and 50 bytes per
 * triangle: a normal, three vertices (12 little-endian floats) and 2 attribute
 * bytes. vtkSTLReader reads what is there, so a short file would silently lose
 * triangles. Returns the problem or "".
 */
std::string CheckBinarySTL(std::istream& in, std::uint64_t size)
{
  unsigned char header[84];
  if (size < 84 || !in.read(reinterpret_cast<char*>(header), 84))
  {
    return "binary STL shorter than its 84-byte header";
  }
  std::uint32_t count = 0;
  for (int i = 3; i >= 0; --i)
  {
    count = (count << 8) | header[80 + i];
  }
  const std::uint64_t expected = 84 + 50 * static_cast<std::uint64_t>(count);
  if (size < expected)
  {
    return "binary STL declares " + std::to_string(count) + " triangles but holds only " +
      std::to_string((size - 84) / 50) + " (truncated?)";
  }
  unsigned char record[50];
  for (std::uint32_t t = 0; t < count; ++t)
  {
    if (!in.read(reinterpret_cast<char*>(record), 50))
    {
      return "binary STL cannot be read to its end";
    }
    for (int v = 3; v < 12; ++v) // the vertices, after the normal
    {
      std::uint32_t bits = 0;
      for (int i = 3; i >= 0; --i)
      {
        bits = (bits << 8) | record[4 * v + i];
      }
      float value;
      std::memcpy(&value, &bits, 4);
      if (!std::isfinite(value))
      {
        return "triangle " + std::to_string(t + 1) + " has a NaN or infinite vertex coordinate";
      }
    }
  }
  return std::string();
}

/** The "vertex x y z" lines of an ASCII STL, read as vtkSTLReader does (strtod). */
std::string CheckAsciiSTL(std::istream& in)
{
  LineReader lines(in, 4096); // longer lines: vtkSTLReader reports them as parse errors
  std::string line;
  std::vector<std::string_view> words;
  while (lines.Next(line))
  {
    SplitWords(line, words);
    if (words.size() < 4 || vtksys::SystemTools::LowerCase(std::string(words[0])) != "vertex")
    {
      continue;
    }
    for (std::size_t c = 1; c <= 3; ++c)
    {
      const std::string word(words[c]);
      char* end = nullptr;
      const double value = std::strtod(word.c_str(), &end);
      const std::string problem = end == word.c_str() ? std::string() : CoordinateProblem(value);
      if (!problem.empty())
      {
        return "line " + std::to_string(lines.GetNumber()) + ": vertex coordinate " + Quote(word) +
          " " + problem;
      }
    }
  }
  return std::string();
}

/** What the container check found: a problem that refuses the file, a bad normal to repair. */
struct ContainerReport
{
  std::string Problem;
  std::string BadNormal;
  long long OBJFaces = -1; ///< the 'f' elements of an OBJ file
};

/**
 * The container problem VTK's reader would crash on or silently lose data over,
 * found by streaming the file once.
 */
ContainerReport CheckContainer(
  const std::string& path, const std::string& extension, std::uint64_t size)
{
  ContainerReport report;
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    report.Problem = "cannot be read (permissions?)";
    return report;
  }
  if (extension == ".ply")
  {
    report.Problem = PlyChecker().Check(file);
  }
  else if (extension == ".obj")
  {
    ObjChecker checker;
    report.Problem = checker.Check(file);
    report.BadNormal = checker.BadNormal;
    report.OBJFaces = checker.Faces;
  }
  else if (vtksys::SystemTools::DetectFileType(path.c_str()) != vtksys::SystemTools::FileTypeText)
  {
    // .stl: the same test as vtkSTLReader uses to pick binary over ASCII.
    report.Problem = CheckBinarySTL(file, size);
  }
  else
  {
    report.Problem = CheckAsciiSTL(file);
  }
  return report;
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
 * Removes point and cell arrays shorter than the points or cells they describe,
 * except the point normals (RepairNormals() reports those). vtkOBJReader attaches
 * its texture coordinate list as it is when every face uses texture coordinate i
 * with vertex i, however many "vt" lines there are; filters would read past its end.
 */
void RemoveShortArrays(vtkPolyData* mesh)
{
  const vtkIdType counts[2] = { mesh->GetNumberOfPoints(), mesh->GetNumberOfCells() };
  vtkDataSetAttributes* attributes[2] = { mesh->GetPointData(), mesh->GetCellData() };
  for (int a = 0; a < 2; ++a)
  {
    for (int i = attributes[a]->GetNumberOfArrays() - 1; i >= 0; --i)
    {
      vtkAbstractArray* array = attributes[a]->GetAbstractArray(i);
      if (array->GetNumberOfTuples() < counts[a] && array != mesh->GetPointData()->GetNormals())
      {
        attributes[a]->RemoveArray(i);
      }
    }
  }
}

/** Index of the first tuple of `array` with a NaN/Inf component, or -1. */
vtkIdType FirstNonFinite(vtkDataArray* array)
{
  const int components = array->GetNumberOfComponents();
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < components; ++c)
    {
      if (!std::isfinite(array->GetComponent(i, c)))
      {
        return i;
      }
    }
  }
  return -1;
}

/**
 * Whether triangle abc has non-zero area relative to its own size: the test
 * vtkCausticsSceneExtractor drops triangles by, so a mesh that passes here keeps at
 * least one triangle there.
 */
bool HasArea(vtkPoints* points, vtkIdType a, vtkIdType b, vtkIdType c)
{
  double pa[3], pb[3], pc[3], e1[3], e2[3], normal[3];
  points->GetPoint(a, pa);
  points->GetPoint(b, pb);
  points->GetPoint(c, pc);
  vtkMath::Subtract(pb, pa, e1);
  vtkMath::Subtract(pc, pa, e2);
  vtkMath::Cross(e1, e2, normal);
  const double edgeScale = std::max(vtkMath::Dot(e1, e1), vtkMath::Dot(e2, e2));
  return edgeScale > 0.0 && vtkMath::Norm(normal) > 1e-12 * edgeScale;
}

/** Whether a polygon (fan) or strip (`strip`) has a triangle of non-zero area. */
bool CellHasArea(vtkPoints* points, vtkIdType npts, const vtkIdType* ids, bool strip)
{
  for (vtkIdType k = 1; k + 1 < npts; ++k)
  {
    if (HasArea(points, strip ? ids[k - 1] : ids[0], ids[k], ids[k + 1]))
    {
      return true;
    }
  }
  return false;
}

/**
 * Counts the polygons and strips with at least three vertices, and those of them
 * with a triangle of non-zero area. Returns the first vertex index out of range as
 * a problem, or "".
 */
std::string CountFaces(vtkPolyData* mesh, vtkIdType& faces, vtkIdType& withArea)
{
  const vtkIdType numPoints = mesh->GetNumberOfPoints();
  faces = withArea = 0;
  for (vtkCellArray* cells : { mesh->GetPolys(), mesh->GetStrips() })
  {
    const bool strip = cells == mesh->GetStrips();
    vtkIdType npts = 0;
    const vtkIdType* ids = nullptr;
    vtkIdType cellIndex = 0;
    for (cells->InitTraversal(); cells->GetNextCell(npts, ids); ++cellIndex)
    {
      for (vtkIdType k = 0; k < npts; ++k)
      {
        if (ids[k] < 0 || ids[k] >= numPoints)
        {
          return "face " + std::to_string(cellIndex) + " refers to vertex " +
            std::to_string(ids[k] + 1) + " (1-based), but the file has " +
            std::to_string(numPoints) + " vertices";
        }
      }
      if (npts >= 3)
      {
        ++faces;
        withArea += CellHasArea(mesh->GetPoints(), npts, ids, strip) ? 1 : 0;
      }
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
    this->Fail("unknown role " + Quote(role) +
      " (known: none, receiver, reflector or mirror, refractor or glass)");
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

  // 1. The file: a regular file with a known extension.
  if (!this->FileName || !*this->FileName)
  {
    return this->ReadFail("no mesh file name given");
  }
  const std::string path = this->FileName;
  std::uint64_t size = 0;
  if (!this->CheckFile(path, size))
  {
    return 0;
  }
  // 2. The container, where VTK's reader would crash or silently lose data.
  const ContainerReport container = CheckContainer(path, LowerExtension(path), size);
  if (!container.Problem.empty())
  {
    return this->ReadFail(path + ": " + container.Problem);
  }
  // 3. VTK's reader; its complaints become this reader's error.
  vtkSmartPointer<vtkPolyDataAlgorithm> reader = this->RunVTKReader(path);
  // 4. The geometry.
  if (!reader || !this->CheckGeometry(path, reader->GetOutput()))
  {
    return 0;
  }
  output->ShallowCopy(reader->GetOutput());
  RemoveShortArrays(output);
  // 5. What VTK's reader dropped, and the normals, repaired rather than refused.
  if (container.OBJFaces > output->GetNumberOfPolys())
  {
    // vtkOBJReader drops such faces when it duplicates vertices for per-face data.
    vtkWarningMacro(<< path << ": vtkOBJReader dropped "
                    << container.OBJFaces - output->GetNumberOfPolys() << " of "
                    << container.OBJFaces
                    << " faces (faces without normals or texture coordinates in a file where "
                       "other faces have them)");
  }
  this->RepairNormals(path, output, container.BadNormal);
  return 1;
}

int vtkCausticsMeshReader::ReadFail(const std::string& message)
{
  this->ReadError = message;
  return this->Fail(message);
}

int vtkCausticsMeshReader::CheckFile(const std::string& path, std::uint64_t& size)
{
  const std::string problem = PathProblem(path, size);
  if (!problem.empty())
  {
    return this->ReadFail(path + ": " + problem);
  }
  if (!IsSupportedExtension(path))
  {
    return this->ReadFail(path + ": unknown mesh extension " + Quote(LowerExtension(path)) +
      " (supported: .ply, .obj, .stl)");
  }
  if (size == 0)
  {
    return this->ReadFail(path + ": the file is empty, no triangles");
  }
  return 1;
}

vtkSmartPointer<vtkPolyDataAlgorithm> vtkCausticsMeshReader::RunVTKReader(const std::string& path)
{
  vtkSmartPointer<vtkPolyDataAlgorithm> reader = NewVTKReader(path, LowerExtension(path));
  ReaderMessages messages;
  messages.Reader = reader;
  messages.Path = path;
  vtkNew<vtkCallbackCommand> collect;
  collect->SetCallback(CollectMessages);
  collect->SetClientData(&messages);
  reader->AddObserver(vtkCommand::ErrorEvent, collect);
  reader->AddObserver(vtkCommand::WarningEvent, collect);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, collect);
  reader->Update();
  if (!messages.Errors.empty())
  {
    this->ReadFail(path + ": VTK's " + reader->GetClassName() + " failed: " + messages.Errors[0]);
    return nullptr;
  }
  if (!messages.ExecutiveErrors.empty())
  {
    this->ReadFail(path + ": VTK's " + reader->GetClassName() + " failed without giving a reason");
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
  vtkIdType faces = 0, withArea = 0;
  const std::string problem = CountFaces(mesh, faces, withArea);
  if (!problem.empty())
  {
    return this->ReadFail(path + ": " + problem);
  }
  const vtkIdType badPoint = mesh->GetPoints() ? FirstNonFinite(mesh->GetPoints()->GetData()) : -1;
  if (badPoint >= 0)
  {
    return this->ReadFail(path + ": vertex " + std::to_string(badPoint + 1) +
      " (1-based) has a NaN or infinite coordinate");
  }
  if (faces == 0)
  {
    return this->ReadFail(path + ": no triangles (" + std::to_string(mesh->GetNumberOfPoints()) +
      " vertices, no faces)");
  }
  if (withArea == 0)
  {
    return this->ReadFail(path + ": no triangle with non-zero area (" +
      (faces == 1 ? std::string("its only face is")
                  : "all " + std::to_string(faces) + " faces are") +
      " degenerate)");
  }
  return 1;
}

void vtkCausticsMeshReader::RepairNormals(
  const std::string& path, vtkPolyData* mesh, std::string problem)
{
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  if (problem.empty() && normals && normals->GetNumberOfTuples() != mesh->GetNumberOfPoints())
  {
    // vtkOBJReader attaches its "vn" list as point normals when every face uses
    // normal i with vertex i, even when there are fewer "vn" than "v" lines.
    problem = "the file gives " + std::to_string(normals->GetNumberOfTuples()) + " normals for " +
      std::to_string(mesh->GetNumberOfPoints()) + " vertices";
  }
  if (problem.empty() && normals)
  {
    const vtkIdType bad = FirstNonFinite(normals);
    if (bad >= 0)
    {
      problem = "vertex " + std::to_string(bad + 1) + " (1-based) has a NaN or infinite normal";
    }
  }
  if (problem.empty())
  {
    return;
  }
  // Without normals, vtkCausticsSceneExtractor (and VTK's mapper, for display)
  // compute them from the triangles.
  mesh->GetPointData()->SetNormals(nullptr);
  if (mesh->GetPointData()->GetNormals())
  {
    mesh->GetPointData()->RemoveArray(mesh->GetPointData()->GetNormals()->GetName());
  }
  vtkWarningMacro(<< path << ": " << problem
                  << "; the file's normals are ignored and recomputed from the triangles");
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
