/**
 * @file   vtkCausticsFileText.h
 * @brief  Text from an untrusted file, fit for a one-line message (private).
 *
 * vtkCausticsMeshReader and vtkCausticsGLTFImporter quote pieces of the file they
 * refuse (a word, a version string, a member name, VTK's own reason). A piece is
 * cut to a few dozen characters and bytes outside printable ASCII are written as
 * \xNN, so that a 5 MB line or binary junk never floods the terminal or breaks a
 * message over several lines.
 */
#ifndef vtkCausticsFileText_h
#define vtkCausticsFileText_h

#include <cstddef>     // For std::size_t
#include <string>      // For std::string
#include <string_view> // For std::string_view

namespace caustics
{
namespace text
{
/** Characters of the file that a message quotes: enough to recognise the place. */
constexpr std::size_t QuoteLength = 60;
/** Characters of a VTK reader's message passed on (it may quote the file itself). */
constexpr std::size_t ReasonLength = 120;

/**
 * `text` at most `limit` characters long, bytes outside printable ASCII written as
 * \xNN, "..." where it was cut.
 */
std::string Printable(std::string_view text, std::size_t limit);

/** Printable(text, QuoteLength) in single quotes. */
std::string Quote(std::string_view text);
}
}

#endif
