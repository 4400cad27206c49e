/**
 * @file   vtkCausticsGLTFDocumentChecker.h
 * @brief  Validation of a glTF 2.0 document before VTK's loader sees it (private).
 *
 * VTK 9.1's glTF loader crashes on node cycles, missing scenes and out-of-range
 * indices, and half-loads other broken files. vtkCausticsGLTFImporter therefore
 * checks the parsed JSON first: structure (every index in range, accessor and
 * buffer sizes, GLB chunks, data URIs), supported extensions, and physical
 * sanity (finite transforms, IOR >= 1, light and camera parameters). The first
 * problem is returned as one line with its JSON path ("meshes[0].primitives[1]").
 */
#ifndef vtkCausticsGLTFDocumentChecker_h
#define vtkCausticsGLTFDocumentChecker_h

#include <vtk_jsoncpp.h> // For Json::Value

#include <cstddef> // For std::size_t
#include <string>  // For std::string

namespace caustics
{
namespace gltf
{
/** The first problem of a parsed document, or "" when VTK's loader can take it. */
std::string CheckDocument(
  const Json::Value& root, const std::string& folder, bool binary, std::size_t binSize);

/** Splits a .glb file's JSON chunk from its binary chunk; returns a problem or "". */
std::string SplitBinary(const std::string& contents, std::string& json, std::size_t& binSize);

/** jsoncpp's multi-line parse errors as one line. */
std::string OneLineErrors(const std::string& jsoncppErrors);

/** True if a message of VTK's loader is about an extension the importer reads itself. */
bool MentionsOwnExtension(const std::string& message);

/** `text` in double quotes, for messages. */
std::string QuotedName(const std::string& text);

/** "1 camera", "3 cameras". */
std::string CountOf(std::size_t count, const char* noun);
}
}

#endif
